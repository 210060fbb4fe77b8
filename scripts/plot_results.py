#!/usr/bin/python3
"""Plot a cocopp results file: the residual history of every time step and the interface
displacement and pressure at chosen steps, to one PNG.

Needs h5py and matplotlib (Debian: python3-h5py, python3-matplotlib). The file layout is
described in docs/results.md. A running cocopp keeps its results file locked: use --live to
read it anyway (all steps up to the last flush), or plot a copy.

Examples:
  plot_results.py results/case.h5                       # first, middle and last step
  plot_results.py results/case.h5 --steps 10 20 -o tube.png
  plot_results.py results/case.h5 --component 1 --axis z
  plot_results.py results/case.h5 --live                # while the run still writes it
"""
import argparse
import sys

import h5py
import matplotlib
import matplotlib.ticker
import numpy as np

matplotlib.use("Agg")  # files only; no display needed
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

AXES = {"x": 0, "y": 1, "z": 2}


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog=__doc__.split("\n\n", 2)[2],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", help="results file written by cocopp (.h5)")
    parser.add_argument("--steps", type=int, nargs="+", metavar="STEP",
                        help="time steps to plot the interface at "
                             "(default: first, middle and last)")
    parser.add_argument("-o", "--output", help="PNG to write (default: RESULTS with .png)")
    parser.add_argument("--model-part", help="model part to plot (default: the first one "
                                             "carrying the variable)")
    parser.add_argument("--displacement", default="displacement", metavar="VARIABLE",
                        help="variable of the x interface to plot (default: %(default)s)")
    parser.add_argument("--pressure", default="pressure", metavar="VARIABLE",
                        help="variable of the y interface to plot (default: %(default)s)")
    parser.add_argument("--component", type=int,
                        help="component of vector variables (default: the one varying most)")
    parser.add_argument("--axis", choices=sorted(AXES),
                        help="coordinate along the interface (default: the longest extent)")
    parser.add_argument("--live", action="store_true",
                        help="open without HDF5 file locking, to plot a file a run still writes")
    return parser.parse_args(argv)


def rows_of(f, steps):
    """Row indices of the requested step numbers; exits with the available range if absent."""
    numbers = f["steps/step"][:]
    if len(numbers) == 0:
        if "unfinished_step" in f:  # the run stopped in its first step: its residuals only
            return [], []
        sys.exit("the results file has no time steps yet")
    if not steps:
        steps = sorted({int(numbers[0]), int(numbers[len(numbers) // 2]), int(numbers[-1])})
    missing = [s for s in steps if s not in numbers]
    if missing:
        sys.exit(f"step(s) {missing} not in the file; it has steps {numbers[0]} .. {numbers[-1]}")
    return steps, [int(np.flatnonzero(numbers == s)[0]) for s in steps]


def plot_residuals(ax, f):
    numbers = f["steps/step"][:]
    norms, offset, count = f["residuals/norms"][:], f["residuals/offset"][:], f["residuals/count"][:]
    converged = f["steps/converged"][:]
    colors = plt.cm.viridis(np.linspace(0, 1, max(len(numbers), 1)))
    for row, step in enumerate(numbers):
        history = norms[offset[row]:offset[row] + count[row]]
        history = np.where(np.isfinite(history) & (history > 0), history, np.nan)
        ax.semilogy(np.arange(1, len(history) + 1), history, "-" if converged[row] else "--",
                    marker="." if converged[row] else "x", color=colors[row], linewidth=0.8)
    if len(numbers):
        mappable = plt.cm.ScalarMappable(
            cmap="viridis", norm=matplotlib.colors.Normalize(numbers[0], numbers[-1]))
        plt.colorbar(mappable, ax=ax, label="time step")
    if "unfinished_step" in f:  # the step the run stopped in (diverged, solver failed, ...)
        unfinished = f["unfinished_step"]
        history = unfinished["residual_norms"][:]
        history = np.where(np.isfinite(history) & (history > 0), history, np.nan)
        ax.semilogy(np.arange(1, len(history) + 1), history, "-", marker="o", color="red",
                    linewidth=1.5, label=f"step {unfinished.attrs['step']}: the run stopped here")
        ax.legend()
    ax.set_xlabel("coupling iteration")
    ax.set_ylabel("residual 2-norm")
    ax.set_title("residual history per time step (x, dashed: accepted unconverged)")
    ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
    ax.grid(True, which="both", alpha=0.3)


def find_part(group, variable, wanted):
    for part in group.attrs["model_parts"]:
        if (wanted is None or part == wanted) and variable in group[part]:
            return part
    return None


def plot_interface(ax, f, name, variable, rows, steps, args):
    group = f[name]
    part = find_part(group, variable, args.model_part)
    if not rows:
        ax.text(0.5, 0.5, "no completed time step", ha="center", transform=ax.transAxes)
        ax.set_axis_off()
        return
    if part is None:
        ax.text(0.5, 0.5, f"no '{variable}' in interface {name}", ha="center",
                transform=ax.transAxes)
        ax.set_axis_off()
        return
    data = group[part][variable][sorted(set(rows))]  # (rows, points, components)
    data = data[[sorted(set(rows)).index(r) for r in rows]]
    coordinates = group[part]["coordinates"][:]
    axis = AXES[args.axis] if args.axis else int(np.argmax(np.ptp(coordinates, axis=0)))
    component = args.component
    if component is None:
        component = int(np.argmax(np.ptp(data.reshape(-1, data.shape[2]), axis=0)))
    component = min(component, data.shape[2] - 1)
    order = np.argsort(coordinates[:, axis])
    for row_data, step in zip(data, steps):
        ax.plot(coordinates[order, axis], row_data[order, component], marker=".",
                label=f"step {step}")
    unit = group[part][variable].attrs.get("unit", "")
    label = variable if data.shape[2] == 1 else f"{variable}[{component}]"
    ax.set_xlabel(f"initial {'xyz'[axis]} (m)")
    ax.set_ylabel(f"{label} ({unit})")
    ax.set_title(f"{name}/{part}/{variable}")
    ax.legend()
    ax.grid(True, alpha=0.3)


def main(argv=None):
    args = parse_arguments(argv)
    output = args.output or str(args.results).rsplit(".", 1)[0] + ".png"
    try:
        f = h5py.File(args.results, "r", locking=False) if args.live else h5py.File(args.results, "r")
    except OSError as error:
        hint = " (a running cocopp holds it: try --live)" if "lock" in str(error) else ""
        sys.exit(f"cannot open {args.results}: {error}{hint}")
    with f:
        steps, rows = rows_of(f, args.steps)
        figure, axes = plt.subplots(3, 1, figsize=(8, 11), constrained_layout=True)
        plot_residuals(axes[0], f)
        plot_interface(axes[1], f, "x", args.displacement, rows, steps, args)
        plot_interface(axes[2], f, "y", args.pressure, rows, steps, args)
        figure.suptitle(f"{f.attrs['case_file']} ({f.attrs['coupled_solver']}, "
                        f"status {f.attrs['status']})")
    figure.savefig(output, dpi=120)
    print(f"wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
