"""The coupled solver's state file (docs/results.md), written again for an earlier step.

A run saves its state only at its last saved step; a run's results file keeps every step's
converged x. rewind_state() writes the state a memoryless coupled solver (IQN-ILS without
reuse, or any coupled solver restarted with --fresh-coupling) would have saved after an
earlier step: the predictor's history from the results file, no secant columns. With the
solvers' restart data of that step, `cocopp run case.yaml --restart` continues from there.
"""
from pathlib import Path

import h5py
import numpy as np

from cocopp.results import ResultsFile


class StateError(SystemExit):
    """A state that cannot be rewound, with the reason."""


def first_residuals(results, step):
    """The first-iteration residual of every step up to `step`."""
    return [norms[0] for number, norms, _ in results.residual_histories()
            if number <= step and len(norms)]


def rewind_state(results_file, state_file, step, output, history_length=None):
    """Write to `output` the state after `step` of the run whose results and state files are
    given: the later state's attributes, the predictor's history of x from the results file
    (`history_length` steps, default the later state's), the largest first residual up to
    `step`, no model memory. Refuses a state whose coupled
    solver carries memory between steps (secant columns, a Jacobian, Aitken's factor)."""
    with h5py.File(state_file, "r") as later, ResultsFile(results_file) as results:
        if step not in list(results.steps):
            raise StateError(f"{results_file}: no step {step} (it has {results.steps[0]} .. "
                             f"{results.steps[-1]})")
        carried = [name for name in ("model/v", "model/jacobian", "model/steps", "omega")
                   if name in later and np.size(later[name]) > 0
                   and not (name == "model/steps" and int(later[name][()]) == 0)]
        if carried:
            raise StateError(f"{state_file}: the coupled solver carries {', '.join(carried)} "
                             "from step to step, which the results file does not keep: "
                             "rewind a run without reuse, and restart with --fresh-coupling")
        parts = results.model_parts("x")
        if len(parts) != 1:
            raise StateError(f"{results_file}: x has {len(parts)} model parts; rewinding "
                             "knows the order of one")
        history_length = history_length or later["predictor/history"].shape[1]
        steps = [s for s in range(step, step - history_length, -1) if s in results.steps]
        x = results.values("x", parts[0], "displacement")
        history = np.stack([x[results.row(s)].reshape(-1) for s in steps], axis=1)
        with h5py.File(output, "w") as state:
            for key, value in later.attrs.items():
                state.attrs[key] = value
            state.attrs["step"] = step
            state.attrs["time"] = float(results.times[results.row(step)])
            state["predictor/history"] = history
            state["largest_first_residual"] = float(np.max(first_residuals(results, step)))
            for group in ("model", "scaling"):
                if group in later:
                    later.copy(later[group], state, name=group)
    return Path(output)
