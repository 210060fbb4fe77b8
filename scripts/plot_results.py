#!/usr/bin/python3
"""Plot a cocopp results file: residuals against the criterion's tolerance, iterations per
step, and the interface at chosen steps, to one PNG; on request also the history at a point, a
space-time map and an animation of a variable along the interface.

Needs h5py and matplotlib (Debian: python3-h5py, python3-matplotlib); the figures are in the
package cocopp (cocopp.plot, docs/python.md). The file layout is in docs/results.md.
A running cocopp keeps its results file locked: use --live to read it anyway.

Examples:
  plot_results.py results/case.h5                       # results/case.png
  plot_results.py results/case.h5 --steps 10 20 -o tube.png
  plot_results.py results/case.h5 --history middle      # a watchpoint: results/case_history.png
  plot_results.py results/case.h5 --point 0 0.005 0     # the interface point nearest to it
  plot_results.py results/case.h5 --space-time pressure # results/case_space_time_pressure.png
  plot_results.py results/case.h5 --animate displacement  # results/case_displacement.gif
  plot_results.py results/case.h5 --live                # while the run still writes it
"""
import argparse
import os
import sys

# The package cocopp beside this script, as cocopp bench runs it without a PYTHONPATH: a
# checkout's python/, or an install's (and the build tree's) lib/python3/dist-packages.
HERE = os.path.dirname(os.path.realpath(__file__))
sys.path[:0] = [os.path.join(HERE, "..", "python"),
                os.path.join(HERE, "..", "..", "lib", "python3", "dist-packages")]
import matplotlib  # noqa: E402

matplotlib.use("Agg")  # files only; no display needed
import matplotlib.pyplot as plt  # noqa: E402

from cocopp.plot import history, interface, residuals  # noqa: E402
from cocopp.results import AXES, ResultsFile  # noqa: E402


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
    parser.add_argument("--history", metavar="WATCHPOINT",
                        help="also plot a watchpoint's variables over time (RESULTS_history.png)")
    parser.add_argument("--point", type=float, nargs=3, metavar=("X", "Y", "Z"),
                        help="also plot the variables over time at the interface point nearest "
                             "to X Y Z (RESULTS_history.png)")
    parser.add_argument("--space-time", metavar="VARIABLE",
                        help="also plot VARIABLE along the interface against time "
                             "(RESULTS_space_time_VARIABLE.png)")
    parser.add_argument("--animate", metavar="VARIABLE",
                        help="also animate VARIABLE along the interface (RESULTS_VARIABLE.gif)")
    parser.add_argument("--movie", metavar="FILE",
                        help="the animation's file: .gif, or .mp4 with ffmpeg installed")
    parser.add_argument("--live", action="store_true",
                        help="open without HDF5 file locking, to plot a file a run still writes")
    return parser.parse_args(argv)


def overview(results, args, output):
    steps, rows = results.rows_of(args.steps)
    figure, axes = plt.subplots(2, 2, figsize=(13, 9), constrained_layout=True)
    residuals.plot_residuals(axes[0, 0], results)
    residuals.plot_iterations(axes[0, 1], results)
    for ax, name, variable in ((axes[1, 0], "x", args.displacement),
                               (axes[1, 1], "y", args.pressure)):
        interface.plot_snapshots(ax, results, name, variable, steps, rows, args.model_part,
                                 args.component, args.axis)
    figure.suptitle(results.title)
    figure.savefig(output, dpi=120)
    plt.close(figure)
    print(f"wrote {output}")


def main(argv=None):
    args = parse_arguments(argv)
    stem = str(args.results).rsplit(".", 1)[0]
    with ResultsFile(args.results, args.live) as results:
        if len(results.steps) == 0 and not results.unfinished_step():
            sys.exit("the results file has no time steps yet")
        overview(results, args, args.output or stem + ".png")
        if args.history or args.point:
            series, where = (results.watchpoint_series(args.history) if args.history
                             else results.nearest_point_series(args.point))
            figure, axes = plt.subplots(len(series), 1, figsize=(8, 2.6 * len(series)),
                                        sharex=True, constrained_layout=True, squeeze=False)
            history.plot_history(list(axes[:, 0]), series, where)
            figure.suptitle(results.title, fontsize=9)
            figure.savefig(stem + "_history.png", dpi=120)
            print(f"wrote {stem}_history.png")
        if args.space_time:
            figure, ax = plt.subplots(figsize=(8, 6), constrained_layout=True)
            interface.plot_space_time(ax, results, args.space_time, args.model_part,
                                      args.component, args.axis)
            output = f"{stem}_space_time_{args.space_time}.png"
            figure.savefig(output, dpi=120)
            print(f"wrote {output}")
        if args.animate:
            output = args.movie or f"{stem}_{args.animate}.gif"
            frames = interface.animate(results, args.animate, output, args.model_part,
                                       args.component, args.axis)
            print(f"wrote {output} ({frames} frames)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
