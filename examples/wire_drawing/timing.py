#!/usr/bin/python3
"""Where a wire drawing run's time went, phase by phase (docs/wire-drawing.md, "Performance").

    timing.py [CASE_DIR] [--phases 10 30 50 70]

Reads CASE_DIR/results/case.h5 (default results/case) and prints a Markdown table: for each
phase of time steps its coupling iterations per step, its wall time, and each solver's and the
coupler's time per coupling iteration; then the whole run's totals with each part's share of
the wall time. --phases gives the last step of each phase but the last (default 10 30 50 70:
the paper's 10 held steps, then its closing steps in groups of 20).
"""
import argparse
import pathlib

from cocopp.results import ResultsFile, results_path

HERE = pathlib.Path(__file__).resolve().parent


def phase_bounds(steps, ends):
    """[(first, last)] step numbers of each phase; `ends` are the last steps of all but the last."""
    first, bounds = int(steps[0]), []
    for end in sorted(e for e in ends if steps[0] <= e < steps[-1]):
        bounds.append((first, end))
        first = end + 1
    return bounds + [(first, int(steps[-1]))]


def rows(results, ends):
    steps, iterations = results.steps, results.iterations
    wall, coupler, solvers = results.wall_time, results.coupler_time, results.solver_times
    names = results.solver_names
    header = (["steps", "iterations per step", "wall time"] +
              [f"{n} per iteration" for n in names] + ["coupler per iteration"])
    table = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for first, last in phase_bounds(steps, ends):
        part = (steps >= first) & (steps <= last)
        n = iterations[part].sum()
        cells = [f"{first}–{last}", f"{iterations[part].mean():.2f} (max {iterations[part].max()})",
                 f"{wall[part].sum():.0f} s"]
        cells += [f"{solvers[part, i].sum() / n:.2f} s" for i in range(len(names))]
        cells.append(f"{1e6 * coupler[part].sum() / n:.0f} µs")
        table.append("| " + " | ".join(cells) + " |")
    total = wall.sum()
    table.append("")
    table.append(f"{len(steps)} steps, {iterations.sum()} coupling iterations "
                 f"({iterations.mean():.2f} per step), {total:.0f} s inside the steps:")
    for i, name in enumerate(names):
        table.append(f"- {name}: {solvers[:, i].sum():.0f} s ({100 * solvers[:, i].sum() / total:.1f} %)")
    table.append(f"- coupler: {coupler.sum():.2f} s ({1e6 * coupler.sum() / iterations.sum():.0f} µs "
                 "per coupling iteration; a mapped wrapper's mapping counts in its solver's time)")
    return table


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", nargs="?", default=str(HERE / "results" / "case"))
    parser.add_argument("--phases", type=int, nargs="*", default=None, metavar="STEP",
                        help="last step of each phase but the last (default: 10 30 50 70)")
    args = parser.parse_args()
    path = results_path(pathlib.Path(args.case) / "case.yaml")
    if not path.exists():
        raise SystemExit(f"timing.py: no results file {path} (run run.sh first)")
    with ResultsFile(path, live=True) as results:  # a run still writing may be timed
        if len(results.steps) == 0:
            raise SystemExit(f"timing.py: {path} holds no time step")
        print("\n".join(rows(results, args.phases if args.phases is not None else [10, 30, 50, 70])))


if __name__ == "__main__":
    main()
