#!/usr/bin/python3
"""Benchmark: each solver at its own time step (substeps, docs/coupling.md "Substeps").

Two studies on cocopp's built-in tube solvers, each run a fresh copy of an example with the
case changed, written under bench/results/substeps/ (or --output):

1. error against run time, examples/tube/flow_structure (a pressure pulse through a tube with
   inertia, coupling time step 1e-4 s, 100 steps): both solvers at the coupling step, every
   substep coupled (both at 1/4 of it), the flow or the structure with 4 substeps, with each
   `time_interpolation` and `time_average`. Error: relative L2 of the wall's displacement at
   the coupling steps against a fully resolved run (both solvers at 1/16 of the step);
   iterations; the whole process's wall time (median of --repeat runs).
2. the order in time of the interpolation, examples/tube/flow_ringmodel (massless rings, so
   that the wall's answer is exact at any time): the flow with 4 substeps against the same
   flow coupled at every substep (`time_average: false`), for coupling steps 2 .. 0.25 ms
   (shorter than a pressure wave's way along the tube, 9 ms) over 0.1 s, measured after the
   start-up (from 0.05 s: the run starts from a state that is not the flow's, and that jump
   is no smooth function of time): the difference is what the interpolation in time alone
   makes.

    /usr/bin/python3 bench/substeps.py [--repeat 3] [--output bench/results/substeps]
"""
import argparse
import json
import math
import shutil
import statistics
import subprocess
import time
from pathlib import Path

import h5py
import numpy as np

from cocopp.case import read as read_case, write as write_case
from cocopp.executable import find_cocopp

ROOT = Path(__file__).resolve().parent.parent


def prepare(example, directory, delta_t, steps, flow_substeps=1, structure_substeps=1,
            interpolation="linear", average=True, tolerance=1e-9):
    """A copy of `example` with the time step, the solvers' substeps and the coupling's time
    interpolation changed, converged tightly."""
    shutil.rmtree(directory, ignore_errors=True)
    shutil.copytree(ROOT / example, directory,
                    ignore=shutil.ignore_patterns("results", "output", "*.log", "*.fifo"))
    case = read_case(directory / "case.yaml")
    case["settings"]["delta_t"] = delta_t
    case["settings"]["number_of_timesteps"] = steps
    case["settings"].pop("results_write_interval", None)
    coupled = case["coupled_solver"]
    coupled["time_interpolation"] = interpolation
    coupled["time_average"] = average
    coupled["divergence"] = {"growth_iterations": 0}  # tight tolerances meet round-off
    coupled["convergence_criterion"] = {
        "type": "or", "criteria": [{"type": "relative_norm", "tolerance": tolerance},
                                   {"type": "iteration_limit", "maximum": 100}]}
    for wrapper, substeps in zip(case["solver_wrappers"], (flow_substeps, structure_substeps)):
        if substeps > 1:
            wrapper["substeps"] = substeps
    write_case(directory / "case.yaml", case)
    return directory / "case.yaml"


def run(cocopp, case_file, repeat=1):
    """Wall times of `repeat` runs and the summary of the last."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        done = subprocess.run([str(cocopp), "run", "-q", str(case_file)], capture_output=True,
                              text=True)
        times.append(time.perf_counter() - start)
    summary_file = case_file.parent / "results" / "case.summary.json"
    summary = json.loads(summary_file.read_text()) if summary_file.exists() else {}
    if done.returncode != 0:
        said = (done.stderr.strip() or done.stdout.strip() or "failed").splitlines()
        summary["failed"] = next((line for line in said if line.startswith("error:")), said[-1])
    return statistics.median(times), summary


def displacement(case_file):
    with h5py.File(case_file.parent / "results" / "case.h5", "r") as results:
        return results["x/wall/displacement"][:, :, 1]


def relative_error(values, reference, every):
    """||values - reference at every `every`-th step|| / ||reference there||."""
    sampled = reference[every - 1::every][:len(values)]
    return float(np.linalg.norm(values - sampled) / np.linalg.norm(sampled))


ERROR_VARIANTS = [
    # name, delta_t factor, flow substeps, structure substeps, interpolation, time_average
    ("both at the coupling step", 1, 1, 1, "linear", True),
    ("every substep coupled (both at 1/4)", 4, 1, 1, "linear", True),
    ("windows of 4 substeps each", 1, 4, 4, "linear", True),
    ("flow 4 substeps, linear, mean loads", 1, 4, 1, "linear", True),
    ("flow 4 substeps, quadratic, mean loads", 1, 4, 1, "quadratic", True),
    ("flow 4 substeps, linear, end-value loads", 1, 4, 1, "linear", False),
    ("structure 4 substeps, constant", 1, 1, 4, "constant", True),
    ("structure 4 substeps, linear", 1, 1, 4, "linear", True),
]


def error_study(cocopp, output, repeat):
    delta_t, steps, fine = 1e-4, 100, 16
    reference = prepare("examples/tube/flow_structure", output / "reference", delta_t / fine,
                        steps * fine)
    _, summary = run(cocopp, reference)
    if "failed" in summary:
        raise SystemExit(f"the reference run failed: {summary['failed']}")
    resolved = displacement(reference)
    rows = []
    for name, factor, flow, structure, interpolation, average in ERROR_VARIANTS:
        directory = output / name.replace(" ", "_").replace(",", "").replace("/", "_")
        case_file = prepare("examples/tube/flow_structure", directory, delta_t / factor,
                            steps * factor, flow, structure, interpolation, average)
        seconds, summary = run(cocopp, case_file, repeat)
        row = {"variant": name, "seconds": seconds}
        if "failed" in summary:
            row["failed"] = summary["failed"]
        else:
            values = displacement(case_file)[factor - 1::factor]
            row["error"] = relative_error(values, resolved, fine)
            row["iterations"] = int(sum(summary["iterations_per_step"]))
        rows.append(row)
        print(f"{name:45s} " + (f"error {row['error']:.3e}  iterations {row['iterations']:5d}  "
                                f"{seconds:.3f} s" if "error" in row else row["failed"]))
    return rows


ORDER_STEPS = (0.002, 0.001, 0.0005, 0.00025)
ORDER_END, ORDER_FROM = 0.1, 0.05  # s: the runs' end, and where the difference is measured from


def order_study(cocopp, output):
    rows, previous = [], {}
    for delta_t in ORDER_STEPS:
        steps = round(ORDER_END / delta_t)
        first = round(ORDER_FROM / delta_t)
        every = prepare("examples/tube/flow_ringmodel", output / f"every_{delta_t}", delta_t / 4,
                        steps * 4, tolerance=1e-12)
        _, summary = run(cocopp, every)
        reference = displacement(every)[3::4][first:]
        row = {"delta_t": delta_t}
        for interpolation in ("linear", "quadratic"):
            case_file = prepare("examples/tube/flow_ringmodel",
                                output / f"{interpolation}_{delta_t}", delta_t, steps, 4, 1,
                                interpolation, average=False, tolerance=1e-12)
            _, summary = run(cocopp, case_file)
            error = relative_error(displacement(case_file)[first:], reference, 1)
            order = math.log2(previous[interpolation] / error) if interpolation in previous \
                else float("nan")
            previous[interpolation] = error
            row[interpolation] = {"difference": error, "order": order}
        rows.append(row)
        print(f"coupling step {1e3 * delta_t:5.2f} ms: linear {row['linear']['difference']:.3e} "
              f"(order {row['linear']['order']:.2f}), quadratic "
              f"{row['quadratic']['difference']:.3e} (order {row['quadratic']['order']:.2f})")
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per variant (median time)")
    parser.add_argument("--output", type=Path, default=ROOT / "bench" / "results" / "substeps")
    arguments = parser.parse_args()
    cocopp = find_cocopp()
    arguments.output.mkdir(parents=True, exist_ok=True)
    print("1. error against run time (flow_structure, 100 steps of 1e-4 s)")
    errors = error_study(cocopp, arguments.output, arguments.repeat)
    print("2. the interpolation's order in time (flow_ringmodel, flow with 4 substeps)")
    orders = order_study(cocopp, arguments.output)
    (arguments.output / "substeps.json").write_text(
        json.dumps({"errors": errors, "orders": orders}, indent=1))
    print(f"written: {arguments.output / 'substeps.json'}")


if __name__ == "__main__":
    main()
