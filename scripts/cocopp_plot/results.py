"""Reading a cocopp results file (docs/results.md) for the figures."""
import sys

import h5py
import numpy as np

AXES = {"x": 0, "y": 1, "z": 2}


class ResultsFile:
    """An open results file. `live` opens without HDF5 file locking, to read a file a run still
    writes (all steps up to its last flush)."""

    def __init__(self, path, live=False):
        self.path = str(path)
        try:
            self.file = h5py.File(path, "r", locking=False) if live else h5py.File(path, "r")
        except OSError as error:
            hint = " (a running cocopp holds it: try --live)" if "lock" in str(error) else ""
            raise SystemExit(f"cannot open {path}: {error}{hint}")
        self.steps = self.file["steps/step"][:]
        self.times = self.file["steps/time"][:]

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.file.close()

    @property
    def title(self):
        attrs = self.file.attrs
        return f"{attrs['case_file']} ({attrs['coupled_solver']}, status {attrs['status']})"

    # --- residuals --------------------------------------------------------------------------

    def residual_histories(self):
        """[(step, 2-norms of its iterations, converged)] for every step written."""
        norms = self.file["residuals/norms"][:]
        offset, count = self.file["residuals/offset"][:], self.file["residuals/count"][:]
        converged = self.file["steps/converged"][:]
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
        return steps, [int(np.flatnonzero(numbers == s)[0]) for s in steps]

    def find_part(self, interface, variable, wanted=None):
        """The first model part of `interface` ("x", "y", "watchpoints") carrying `variable`
        (`wanted` if given), or None."""
        if interface not in self.file:
            return None
        group = self.file[interface]
        for part in group.attrs["model_parts"]:
            if (wanted is None or part == wanted) and variable in group[part]:
                return str(part)
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
        return self.file[interface][part]["coordinates"][:]

    def values(self, interface, part, variable, rows=slice(None)):
        """(rows, points, components) values of a variable."""
        return self.file[interface][part][variable][rows]

    def unit(self, interface, part, variable):
        return self.file[interface][part][variable].attrs.get("unit", "")

    def watchpoint_names(self):
        return [str(p) for p in self.file["watchpoints"].attrs["model_parts"]] \
            if "watchpoints" in self.file else []


def along_axis(coordinates, axis=None):
    """The coordinate index along the interface: `axis` ("x", "y", "z") or the longest extent."""
    return AXES[axis] if axis else int(np.argmax(np.ptp(coordinates, axis=0)))


def varying_component(values, component=None):
    """`component`, or the component of (..., c) values that varies most."""
    if component is None:
        component = int(np.argmax(np.ptp(values.reshape(-1, values.shape[-1]), axis=0)))
    return min(component, values.shape[-1] - 1)


def label(variable, components, component, unit):
    name = variable if components == 1 else f"{variable}[{'xyz'[component]}]"
    return f"{name} ({unit})" if unit else name
