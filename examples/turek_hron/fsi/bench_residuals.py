#!/usr/bin/env python3
"""Residual histories of a Turek-Hron bench's runs (docs/validation-turek-hron.md):

    bench_residuals.py BENCH_OUTPUT [--steps 3] [-o residuals.png]

BENCH_OUTPUT is a cocopp bench output directory (bench.json and one directory per run, e.g.
examples/turek_hron/fsi/results/bench_fsi3): the coupling residual per iteration of each run's
last --steps time steps, one after the other, on a log scale, with the runs' tolerance; a run
that stopped inside a step (diverged) ends with that step's residuals, dotted.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from cocopp.results import (ResultsFile, bench_run_directory, read_bench,  # noqa: E402
                            results_path)


def last_steps(results, steps):
    """[(step, norms)] of the last `steps` steps of a results file, then the step the run
    stopped in, if it stopped inside one (a divergence), and the tolerance."""
    with ResultsFile(results, live=True) as run:
        histories = run.residual_histories()
        tolerance = run.tolerance()
        history = [(step, norms) for step, norms, _ in histories[len(histories) - steps:]]
        return history, run.unfinished_step(), tolerance[2] if tolerance else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bench", type=pathlib.Path)
    parser.add_argument("--steps", type=int, default=3)
    parser.add_argument("-o", "--output", type=pathlib.Path)
    args = parser.parse_args()
    runs = read_bench(args.bench)["runs"]
    figure, axis = plt.subplots(figsize=(9, 4.5))
    tolerance = None
    for run in runs:
        if run["name"] == "reference":
            continue
        # Only the run's own steps: a run continuing a saved state holds the base run's too.
        own = min(args.steps, run["steps_completed"] or 0)
        history, stopped, run_tolerance = last_steps(
            results_path(bench_run_directory(args.bench, run) / "case.yaml"), own)
        tolerance = tolerance or run_tolerance
        if stopped:
            history.append(stopped)
            label = f"{run['name']} ({run['outcome']} in step {stopped[0]})"
        else:
            label = f"{run['name']} ({run['average_iterations']:.2f} it/step)"
        x, y, start = [], [], 0
        for _, norms in history:
            x += [start + k for k in range(len(norms))]
            y += list(norms)
            x.append(float("nan"))
            y.append(float("nan"))
            start += len(norms) + 1
        axis.semilogy(x, y, marker=".", lw=0.8, ls=":" if stopped else "-", label=label)
    if tolerance:
        axis.axhline(tolerance, color="k", ls="--", lw=0.8, label="tolerance")
    axis.set_xlabel(f"coupling iteration (the last {args.steps} steps, one after the other)")
    axis.set_ylabel("residual 2-norm [m]")
    axis.legend(fontsize=8)
    axis.set_title("Turek-Hron FSI3, developed oscillation: coupling residuals")
    figure.tight_layout()
    figure.savefig(args.output or args.bench / "residuals.png", dpi=110)


if __name__ == "__main__":
    main()
