#!/usr/bin/python3
"""The approach to steady drawing of a wire drawing run (docs/wire-drawing.md), as a figure.

    steady.py [CASE_DIR] [-o FIGURE]

Reads CASE_DIR/checks.json (checks.py writes it; run checks.py first) and draws, per time
step, the drawing force beside its estimate from its terms (back force + ideal work of the
reduction the die draws + the film's viscous shear) at the last step, and the film where the
die's approach ends beside Wilson and Walowit's inlet-zone estimate, with the band of +-0.5 %
about the mean of the last 10 steps (the steadiness checks.py measures: within 1 %) and the
step where the die stops closing. Written to CASE_DIR/wire-drawing-steady.png, or -o.
"""
import argparse
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from wire_results import made_with  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent


def history(checks, key):
    """A per-step history of checks.json as sorted steps and values."""
    items = sorted((int(step), value) for step, value in checks[key].items())
    return [s for s, _ in items], [v for _, v in items]


def draw_band(axis, steps, values, window):
    """The +-0.5 % band about the mean of the last `window` steps (a 1 % spread)."""
    last = values[-window:]
    mean = sum(last) / len(last)
    axis.axhspan(0.995 * mean, 1.005 * mean, color="0.85", zorder=0,
                 label=f"mean of steps {steps[-len(last)]}-{steps[-1]} +- 0.5 %")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", nargs="?", default=str(HERE / "results" / "steady"))
    parser.add_argument("-o", "--output", help="the figure (default CASE/wire-drawing-steady.png)")
    args = parser.parse_args()
    case = pathlib.Path(args.case)
    checks_file = case / "checks.json"
    if not checks_file.exists():
        sys.exit(f"steady.py: {checks_file} does not exist: run checks.py {case} first")
    checks = json.loads(checks_file.read_text())
    if "drawing_force_history" not in checks:
        sys.exit(f"steady.py: {checks_file} has no per-step histories: the run has fewer than "
                 f"{checks.get('steady_window', 10)} steps, or checks.py is older than this script")
    p, _ = made_with(case, HERE / "parameters.yaml", [])
    closing_ends = p["time"]["steps"]
    window = checks["steady_window"][1] - checks["steady_window"][0] + 1

    figure, (force_axis, film_axis) = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True)
    steps, force = history(checks, "drawing_force_history")
    draw_band(force_axis, steps, force, window)
    force_axis.plot(steps, force, "o-", ms=3, label="drawing force (exit end)")
    force_axis.axhline(checks["drawing_force_estimate"], color="C1", ls="--",
                       label=f"back force + ideal work + film shear, step {checks['step']}")
    force_axis.set_ylabel("drawing force (N)")
    force_axis.set_title(f"drawing force within {100 * checks['drawing_force_spread']:.2f} %, "
                         f"film within {100 * checks['film_at_cone_end_spread']:.2f} % over "
                         f"steps {checks['steady_window'][0]}-{checks['steady_window'][1]}",
                         fontsize=10)

    steps, film = history(checks, "film_at_cone_end_history")
    film_um = [1e6 * h for h in film]
    draw_band(film_axis, steps, film_um, window)
    film_axis.plot(steps, film_um, "o-", ms=3, label="film where the approach ends")
    film_axis.axhline(1e6 * checks["wilson_walowit_h0"], color="C1", ls="--",
                      label="Wilson-Walowit inlet film")
    film_axis.set_ylabel("film thickness (um)")
    film_axis.set_xlabel("time step")
    for axis, where in ((force_axis, "lower right"), (film_axis, "center right")):
        axis.axvline(closing_ends, color="0.4", lw=0.8, ls=":")
        axis.legend(fontsize=8, loc=where)
        axis.grid(alpha=0.3)
    film_axis.annotate("die held closed", (closing_ends, film_axis.get_ylim()[1]),
                       xytext=(4, -12), textcoords="offset points", fontsize=8)
    figure.tight_layout()
    output = pathlib.Path(args.output) if args.output else case / "wire-drawing-steady.png"
    figure.savefig(output, dpi=110)
    print(f"steady.py: {output}")


if __name__ == "__main__":
    main()
