#!/usr/bin/env python3
"""The fluid at its own time step (substeps) on Turek-Hron FSI3 (docs/validation-turek-hron.md,
"The fluid at its own time step"): FSI3's first second from rest, run by run.sh as

  reference       fluid and flag at 1 ms, converged to 1e-10 m
  every_step      fluid and flag at 1 ms (the case's 1e-7 m): the fluid coupled at each of its steps
  both_2ms        fluid and flag at 2 ms
  fluid_K         the fluid at 1 ms in windows of K = 2, 4, 8 of its steps, the flag and the
                  coupling at K ms (--fluid-substeps K, quadratic in time)

then the tip displacement u(A) of each against the reference at the runs' coupling steps
(relative L2 over the second half, from 0.5 s, and the largest difference), iterations per
coupling step, the fluid's steps per coupling iteration and the wall time; and draws the error
against the wall time and against the fluid's steps (results/substeps.png, the figure of
docs/coupling.md's "Substeps": scripts/make_doc_figures.sh turek_hron_substeps).

    /usr/bin/python3 examples/turek_hron/fsi/substeps.py [--end-time 1] [--only NAME ...]

Writes examples/turek_hron/fsi/results/substeps_<name>/ (run.sh), results/substeps.json and
results/substeps.png.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from post import read_tip  # noqa: E402  (the same u(A) as post.py)

from cocopp.results import results_path  # noqa: E402

RUNS = {
    "reference": ["--dt", "0.001", "--tolerance", "1e-10"],
    "every_step": ["--dt", "0.001"],
    "both_2ms": ["--dt", "0.002"],
    "fluid_2": ["--dt", "0.002", "--fluid-substeps", "2"],
    "fluid_4": ["--dt", "0.004", "--fluid-substeps", "4"],
    "fluid_8": ["--dt", "0.008", "--fluid-substeps", "8"],
}


def run(name, options, end_time):
    started = time.perf_counter()
    done = subprocess.run([str(HERE / "run.sh"), "fsi3", "--name", "substeps_" + name,
                           "--end-time", str(end_time)] + options,
                          capture_output=True, text=True)
    seconds = time.perf_counter() - started
    if done.returncode != 0:
        print(done.stdout[-2000:], done.stderr[-2000:], file=sys.stderr)
    return seconds, done.returncode


def tip(name):
    case = HERE / "results" / ("substeps_" + name) / "case.yaml"
    times, ux, uy, iterations = read_tip(results_path(case))
    return np.asarray(times), np.stack([ux, uy], axis=1), np.asarray(iterations)


def compare(name, reference, seconds, end_time):
    times, u, iterations = tip(name)
    ref_times, ref_u, _ = reference
    # The reference at the run's coupling steps (the reference's step is the finest).
    index = np.searchsorted(ref_times, times - 1e-9)
    index = np.minimum(index, len(ref_times) - 1)
    assert np.allclose(ref_times[index], times, atol=1e-9), name
    second_half = times >= 0.5 * end_time - 1e-9
    difference = u[second_half] - ref_u[index][second_half]
    substeps = round((times[1] - times[0]) / (ref_times[1] - ref_times[0])) if len(times) > 1 else 1
    return {
        "name": name, "coupling_steps": len(times), "wall_time_s": seconds,
        "iterations_per_step": float(np.mean(iterations)),
        "fluid_steps_per_coupling_iteration": substeps if name.startswith("fluid_") else 1,
        "relative_error_uA": float(np.linalg.norm(difference) /
                                   np.linalg.norm(ref_u[index][second_half])),
        "largest_difference_uA_m": float(np.abs(difference).max()),
        "uA_at_end_m": [float(v) for v in u[-1]],
    }


LABELS = {"every_step": "both at 1 ms (every fluid step coupled)",
          "both_2ms": "both at 2 ms",
          "fluid_2": "fluid 1 ms, flag 2 ms (2 substeps)",
          "fluid_4": "fluid 1 ms, flag 4 ms (4 substeps)",
          "fluid_8": "fluid 1 ms, flag 8 ms (8 substeps)"}


def plot(rows, output):
    """The error of u(A) against the wall time and against the fluid's steps in all."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, (by_time, by_steps) = plt.subplots(1, 2, figsize=(10, 4.8), sharey=True)
    for row in rows:
        fluid_steps = (row["coupling_steps"] * row["iterations_per_step"] *
                       row["fluid_steps_per_coupling_iteration"])
        marker = "s" if row["name"].startswith("fluid_") else "o"
        for axes, x in ((by_time, row["wall_time_s"]), (by_steps, fluid_steps)):
            axes.semilogy(x, row["relative_error_uA"], marker, markersize=8,
                        label=LABELS.get(row["name"], row["name"]))
    by_time.set_xlabel("wall time (s, 2 cores)")
    by_steps.set_xlabel("fluid time steps solved (all coupling iterations)")
    by_time.set_ylabel("error of u(A), relative L2 over 0.5-1 s")
    for axes in (by_time, by_steps):
        axes.grid(True, which="both", alpha=0.3)
    by_time.set_xlim(left=0)
    by_steps.set_xlim(left=0)
    handles, labels = by_time.get_legend_handles_labels()
    figure.legend(handles, labels, fontsize=8, loc="lower center", ncol=3)
    figure.suptitle("Turek-Hron FSI3, level 1, first second: the fluid at its own time step")
    figure.tight_layout(rect=(0, 0.1, 1, 1))
    figure.savefig(output, dpi=110)
    plt.close(figure)
    print(f"wrote {output}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--end-time", type=float, default=1.0)
    parser.add_argument("--only", nargs="*", help="runs to (re)run; the others are read")
    args = parser.parse_args()
    seconds = {}
    timings = HERE / "results" / "substeps_times.json"
    if timings.exists():
        seconds = json.loads(timings.read_text())
    for name, options in RUNS.items():
        if args.only is None or name in args.only:
            print(f"running {name} ...", flush=True)
            seconds[name], code = run(name, options, args.end_time)
            if code != 0:
                seconds[name] = None
            timings.parent.mkdir(parents=True, exist_ok=True)
            timings.write_text(json.dumps(seconds, indent=1))
    reference = tip("reference")
    rows = []
    print(f"{'run':12s} {'steps':>6s} {'its/step':>8s} {'fluid steps/it':>14s} "
          f"{'error u(A)':>11s} {'largest (m)':>12s} {'wall (s)':>9s}")
    for name in RUNS:
        if name == "reference" or seconds.get(name) is None:
            continue
        row = compare(name, reference, seconds[name], args.end_time)
        rows.append(row)
        print(f"{name:12s} {row['coupling_steps']:6d} {row['iterations_per_step']:8.2f} "
              f"{row['fluid_steps_per_coupling_iteration']:14d} {row['relative_error_uA']:11.3e} "
              f"{row['largest_difference_uA_m']:12.3e} {row['wall_time_s']:9.1f}")
    (HERE / "results" / "substeps.json").write_text(json.dumps(rows, indent=1) + "\n")
    plot(rows, HERE / "results" / "substeps.png")


if __name__ == "__main__":
    main()
