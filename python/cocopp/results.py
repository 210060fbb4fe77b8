"""A run's results: the HDF5 results file (docs/results.md), the run summary beside it and the
output of `cocopp bench`. The one reader of these files for the scripts and examples, so that
a change of their layout is mended here once.

    from cocopp import results

    with results.ResultsFile("examples/tube/flow_structure/results/case.h5") as run:
        print(run.status, run.steps[-1], run.iterations.mean())
        displacement = run.values("x", "wall", "displacement")   # (steps, points, components)
        for step, norms, converged in run.residual_histories():
            ...
    summary = results.read_summary("examples/tube/flow_structure/results/case.h5")

ResultsFile needs h5py (Debian: python3-h5py); the summary, the bench file and the paths do not.
"""
import json
import pathlib
import sys

import numpy as np

AXES = {"x": 0, "y": 1, "z": 2}
POINT_DATASETS = ("ids", "coordinates")  # a model part's datasets that are not variables


def results_path(case_file):
    """The results file a run of `case_file` writes, named as cocopp names it:
    settings.results_directory (default results/, relative to the case file's folder) and
    settings.results_name (default the case file's name without extension), with .h5."""
    import yaml  # only here: the other readers need no yaml

    case_file = pathlib.Path(case_file)
    if not case_file.is_file():
        raise SystemExit(f"no case file {case_file}")
    case = yaml.safe_load(case_file.read_text()) or {}
    settings = case.get("settings") or {}
    directory = case_file.parent / settings.get("results_directory", "results")
    return directory / (settings.get("results_name", case_file.stem) + ".h5")


def summary_path(results_file):
    """The run summary beside a results file: results/case.h5 -> results/case.summary.json."""
    return pathlib.Path(results_file).with_suffix(".summary.json")


def read_summary(results_file, missing_ok=False):
    """The run summary (a dict) of a results file; {} if it has none yet (a run still going, or
    killed) and `missing_ok`, else an exit with the path."""
    path = summary_path(results_file)
    if not path.exists():
        if missing_ok:
            return {}
        raise SystemExit(f"no run summary {path} (the run has not ended)")
    return json.loads(path.read_text())


def bench_run_directory(output_directory, run):
    """Where `cocopp bench` ran one of its runs (an entry of bench.json's "runs"):
    <output_directory>/[<case>/]<name>, holding its case.yaml and results/."""
    return pathlib.Path(output_directory) / run.get("case", "") / run["name"]


def read_bench(path):
    """The result of `cocopp bench` (docs/bench.md): its bench.json, or the output directory
    holding it."""
    path = pathlib.Path(path)
    if path.is_dir():
        path = path / "bench.json"
    return json.loads(path.read_text())


class ResultsFileError(SystemExit):
    """A results file that cannot be opened: ends a script with its message, unless caught."""


class ResultsFile:
    """An open results file. `live` opens without HDF5 file locking, to read a file a run still
    writes (all steps up to its last flush)."""

    def __init__(self, path, live=False):
        import h5py  # only here: summaries and case paths are read without it

        self.path = str(path)
        try:
            self.file = h5py.File(path, "r", locking=False) if live else h5py.File(path, "r")
        except (OSError, FileNotFoundError) as error:
            hint = " (a running cocopp holds it: try --live)" if "lock" in str(error) else ""
            raise ResultsFileError(f"cannot open {path}: {error}{hint}")
        self.steps = self.file["steps/step"][:]
        self.times = self.file["steps/time"][:]

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.close()

    def close(self):
        self.file.close()

    # --- the run ----------------------------------------------------------------------------

    @property
    def status(self):
        return str(self.file.attrs["status"])

    @property
    def title(self):
        attrs = self.file.attrs
        return f"{attrs['case_file']} ({attrs['coupled_solver']}, status {attrs['status']})"

    @property
    def solver_names(self):
        return [str(name) for name in self.file.attrs["solver_names"]]

    # --- per step: rows of the file, in the order the steps were computed --------------------

    def _per_step(self, name):
        """A /steps dataset, as long as steps (steps/step is written last in a step)."""
        return self.file["steps"][name][:len(self.steps)]

    @property
    def iterations(self):
        return self._per_step("iterations")

    @property
    def converged(self):
        return self._per_step("converged").astype(bool)

    @property
    def wall_time(self):
        return self._per_step("wall_time")

    @property
    def coupler_time(self):
        return self._per_step("coupler_time")

    @property
    def solver_times(self):
        """(steps, solvers) seconds in each solver wrapper, columns in solver_names' order."""
        return self._per_step("solver_times")

    def row(self, step):
        """The row of time step `step`; exits with the steps the file has if it is not there."""
        rows = np.flatnonzero(self.steps == step)
        if len(rows) == 0:
            sys.exit(f"step {step} not in {self.path}; it has steps "
                     + (f"{self.steps[0]} .. {self.steps[-1]}" if len(self.steps) else "none"))
        return int(rows[0])

    def rows_of(self, steps):
        """(steps, rows): the requested step numbers (default: first, middle and last) and
        their rows; exits with the steps the file has if one is missing."""
        numbers = self.steps
        if len(numbers) == 0:
            return [], []
        if not steps:
            steps = sorted({int(numbers[0]), int(numbers[len(numbers) // 2]), int(numbers[-1])})
        missing = [s for s in steps if s not in numbers]
        if missing:
            sys.exit(f"step(s) {missing} not in the file; it has steps {numbers[0]} .. "
                     f"{numbers[-1]}")
        return steps, [self.row(s) for s in steps]

    # --- residuals --------------------------------------------------------------------------

    def residual_histories(self):
        """[(step, 2-norms of its iterations, converged)] for every step written."""
        norms = self.file["residuals/norms"][:]
        offset, count = self.file["residuals/offset"][:], self.file["residuals/count"][:]
        converged = self.converged
        return [(int(step), norms[offset[row]:offset[row] + count[row]], bool(converged[row]))
                for row, step in enumerate(self.steps)]

    def unfinished_step(self):
        """(step, 2-norms) of the step the run stopped in, or None."""
        if "unfinished_step" not in self.file:
            return None
        group = self.file["unfinished_step"]
        return int(group.attrs["step"]), group["residual_norms"][:]

    def tolerance(self):
        """(measure "relative"/"absolute", norm order, value) of the criterion's first tolerance,
        or None (an iteration limit alone, or a file written before cocopp kept it)."""
        attrs = self.file.attrs
        if "tolerance" not in attrs or len(attrs["tolerance"]) == 0:
            return None
        return (str(attrs["tolerance_measure"][0]), str(attrs["tolerance_order"][0]),
                float(attrs["tolerance"][0]))

    @property
    def criterion(self):
        return str(self.file.attrs.get("convergence_criterion", ""))

    # --- interfaces -------------------------------------------------------------------------

    def model_parts(self, interface):
        """The model parts of an interface ("x", "y", "watchpoints") in interface order."""
        if interface not in self.file:
            return []
        return [str(part) for part in self.file[interface].attrs["model_parts"]]

    def variables(self, interface, part):
        return [str(v) for v in self.file[interface][part] if v not in POINT_DATASETS]

    def find_part(self, interface, variable, wanted=None):
        """The first model part of `interface` carrying `variable` (`wanted` if given), or None."""
        for part in self.model_parts(interface):
            if (wanted is None or part == wanted) and variable in self.file[interface][part]:
                return part
        return None

    def find_variable(self, variable, wanted_part=None):
        """(interface, model part) where `variable` is, x first; exits if it is nowhere."""
        for interface in ("x", "y"):
            part = self.find_part(interface, variable, wanted_part)
            if part:
                return interface, part
        sys.exit(f"no variable '{variable}'"
                 + (f" on model part '{wanted_part}'" if wanted_part else "")
                 + f" in {self.path}")

    def coordinates(self, interface, part):
        """(points, 3) initial coordinates."""
        return self.file[interface][part]["coordinates"][:]

    def values(self, interface, part, variable, rows=slice(None)):
        """(rows, points, components) values of a variable (all steps unless `rows`)."""
        return self.file[interface][part][variable][rows]

    def unit(self, interface, part, variable):
        return self.file[interface][part][variable].attrs.get("unit", "")

    # --- watchpoints and points over time ---------------------------------------------------

    def watchpoint_names(self):
        return self.model_parts("watchpoints")

    def watchpoint_series(self, name):
        """({variable: (times, values (steps, components), unit)}, the point) of a watchpoint;
        exits naming the watchpoints the file has if it has no `name`."""
        names = self.watchpoint_names()
        if name not in names:
            sys.exit(f"no watchpoint '{name}' in {self.path}"
                     + (f"; it has {', '.join(names)}" if names else
                        " (the run had no settings.watchpoints: use --point X Y Z)"))
        series = {variable: (self.times, self.values("watchpoints", name, variable)[:, 0, :],
                             self.unit("watchpoints", name, variable))
                  for variable in self.variables("watchpoints", name)}
        return series, self.coordinates("watchpoints", name)[0]

    def nearest_point_series(self, point):
        """The same for the interface point nearest to `point`: on x and on y the one point
        nearest to it (over all model parts), and every variable there."""
        point = np.asarray(point, dtype=float)
        series, where = {}, None
        for interface in ("x", "y"):
            nearest = self._nearest_point(interface, point)
            if nearest is None:
                continue
            part, index, where = nearest
            for variable in self.variables(interface, part):
                series[variable] = (self.times, self.values(interface, part, variable)[:, index, :],
                                    self.unit(interface, part, variable))
        return series, where

    def _nearest_point(self, interface, point):
        """(model part, index, coordinates) of the point of `interface` nearest to `point`."""
        best = None
        for part in self.model_parts(interface):
            coordinates = self.coordinates(interface, part)
            if len(coordinates) == 0:
                continue
            distances = ((coordinates - point) ** 2).sum(axis=1)
            index = int(np.argmin(distances))
            if best is None or distances[index] < best[0]:
                best = (distances[index], part, index, coordinates[index])
        return None if best is None else best[1:]
