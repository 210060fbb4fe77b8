#!/usr/bin/env python3
"""Tip displacement, drag and lift of a Turek-Hron FSI run against the published values
(docs/validation-turek-hron.md).

    post.py RUN [--periods 2] [--plot turek-hron.png]

RUN is a run directory of run.sh (its turek_hron.json says which test): u(A) from the coupler's
results (results/case.h5: the fluid's flag point at A = (0.6, 0.2)), drag and lift of cylinder
and flag together from OpenFOAM's forces (fluid/postProcessing/forces/*/force.dat) per metre of
depth. fsi1 (steady): the means over the last 0.5 s and the range there. fsi2, fsi3:
mean = (max + min) / 2, amplitude = (max - min) / 2 over the last --periods periods of each
quantity, the frequency from its crossings of the mean; cfd3 (the flag rigid, no coupler): the
same for drag and lift against the CFD3 table. Prints a table, writes RUN/post.json and the time histories
(RUN/turek-hron.png unless --plot).
"""
import argparse
import json
import pathlib
import re
import sys

import numpy as np

from cocopp.results import ResultsFile, results_path

POINT_A = (0.6, 0.2)
# S. Turek, J. Hron (2006), tables of the FSI tests (displacements in m, forces in N per m of
# depth): steady values (fsi1), or (mean, amplitude, frequency in Hz).
REFERENCE = {
    "fsi1": {"ux": 0.0227e-3, "uy": 0.8209e-3, "drag": 14.295, "lift": 0.7638},
    "fsi2": {"ux": (-14.58e-3, 12.44e-3, 3.8), "uy": (1.23e-3, 80.6e-3, 2.0),
             "drag": (208.83, 73.75, 3.8), "lift": (0.88, 234.2, 2.0)},
    "fsi3": {"ux": (-2.69e-3, 2.53e-3, 10.9), "uy": (1.48e-3, 34.38e-3, 5.3),
             "drag": (457.3, 22.66, 10.9), "lift": (2.22, 149.78, 5.3)},
    # CFD3, the flag rigid: forces only.
    "cfd3": {"drag": (439.45, 5.6183, 4.3956), "lift": (-11.893, 437.81, 4.3956)},
}


def read_forces(fluid, depth):
    """(time, drag, lift) from every forces/<start>/force*.dat (a restarted run adds a file:
    force_0.dat, ...); a time written twice keeps the value of the file written last."""
    number = r"[-+0-9.eE]+"
    pattern = re.compile(rf"^\s*({number})\s+\(({number})\s+({number})\s+{number}\)")
    rows = {}
    for path in sorted((fluid / "postProcessing/forces").glob("*/force*.dat"),
                       key=lambda p: p.stat().st_mtime):
        for line in path.read_text().splitlines():
            match = pattern.match(line)
            if match:
                t, fx, fy = (float(v) for v in match.groups())
                rows[round(t, 9)] = (fx / depth, fy / depth)
    if not rows:
        sys.exit(f"post.py: no forces in {fluid}/postProcessing/forces/*/force.dat")
    times = np.array(sorted(rows))
    values = np.array([rows[t] for t in times])
    return times, values[:, 0], values[:, 1]


def read_tip(results):
    with ResultsFile(results) as run:
        coordinates = run.coordinates("x", "flag_points")
        nearest = np.argmin(np.hypot(coordinates[:, 0] - POINT_A[0],
                                     coordinates[:, 1] - POINT_A[1]))
        displacement = run.values("x", "flag_points", "displacement")[:, nearest, :]
        return run.times, displacement[:, 0], displacement[:, 1], run.iterations


def crossings(times, values, level):
    """Times where `values` rises through `level` (linear between samples)."""
    below = values[:-1] < level
    up = np.flatnonzero(below & (values[1:] >= level))
    return [times[k] + (level - values[k]) / (values[k + 1] - values[k]) * (times[k + 1] - times[k])
            for k in up]


def oscillation(times, values, periods, window_s):
    """(mean, amplitude, frequency) of the last `periods` periods, or None if too few: the
    frequency from the upward crossings of the mean of the last `window_s` seconds (robust to
    noise on the peaks, which the lift carries), mean and amplitude from the maximum and
    minimum between the first and last of the crossings used (as Turek & Hron define them)."""
    recent = times >= times[-1] - window_s
    level = 0.5 * (values[recent].max() + values[recent].min())
    # Noise around the level crosses it too: a crossing closer than 0.3 of the typical period
    # to the one before it is dropped.
    up = crossings(times, values, level)
    if len(up) < 2:
        return None
    period_guess = np.median(np.diff(up[-8:]))
    up = [t for k, t in enumerate(up) if k == 0 or t - up[k - 1] > 0.3 * period_guess]
    if len(up) < periods + 1:
        return None
    start, end = up[-1 - periods], up[-1]
    window = (times >= start) & (times <= end)
    top, bottom = values[window].max(), values[window].min()
    return 0.5 * (top + bottom), 0.5 * (top - bottom), periods / (end - start)


def evaluate(test, histories, periods):
    table = {}
    for name, (times, values) in histories.items():
        reference = REFERENCE[test][name]
        if test == "fsi1":
            last = times >= times[-1] - 0.5
            value = float(values[last].mean())
            table[name] = {"value": value, "reference": reference,
                           "error": value / reference - 1,
                           "change_last_0.5s": float(np.ptp(values[last]))}
            continue
        found = oscillation(times, values, periods, window_s=1.0)
        if found is None:
            table[name] = {"reference": list(reference), "note": "fewer periods than asked"}
            continue
        table[name] = {"mean": found[0], "amplitude": found[1], "frequency": found[2],
                       "reference": list(reference),
                       "amplitude_error": found[1] / reference[1] - 1,
                       "frequency_error": found[2] / reference[2] - 1}
    return table


def print_table(test, table):
    for name, row in table.items():
        if "value" in row:
            print(f"{test} {name:5s} {row['value']: .5e}  reference {row['reference']: .5e}  "
                  f"{100 * row['error']:+.2f} %  (range over the last 0.5 s "
                  f"{row['change_last_0.5s']:.2e})")
        elif "mean" in row:
            mean, amplitude, frequency = row["reference"]
            print(f"{test} {name:5s} {row['mean']: .4e} +- {row['amplitude']:.4e} "
                  f"[{row['frequency']:.3f} Hz]  reference {mean: .4e} +- {amplitude:.4e} "
                  f"[{frequency} Hz]  amplitude {100 * row['amplitude_error']:+.1f} %, "
                  f"frequency {100 * row['frequency_error']:+.1f} %")
        else:
            print(f"{test} {name:5s} {row['note']}")


def plot(test, histories, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    units = {"ux": "u_x(A) [m]", "uy": "u_y(A) [m]", "drag": "drag [N/m]", "lift": "lift [N/m]"}
    figure, axes = plt.subplots(len(histories), 1, figsize=(8, 2.25 * len(histories)),
                                sharex=True)
    for axis, (name, (times, values)) in zip(axes, histories.items()):
        axis.plot(times, values, lw=0.8, label="cocopp")
        reference = REFERENCE[test][name]
        if test == "fsi1":
            axis.axhline(reference, color="k", ls="--", lw=0.8, label="Turek & Hron (2006)")
        else:
            for level in (reference[0] - reference[1], reference[0] + reference[1]):
                axis.axhline(level, color="k", ls="--", lw=0.8)
        axis.set_ylabel(units[name])
    axes[0].legend(loc="best", fontsize=8)
    axes[-1].set_xlabel("t [s]")
    axes[0].set_title(f"Turek-Hron {test.upper()} (dashed: the reference"
                      f"{'' if test == 'fsi1' else ' mean +- amplitude'})")
    figure.tight_layout()
    figure.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run", type=pathlib.Path)
    parser.add_argument("--periods", type=int, default=2)
    parser.add_argument("--plot", type=pathlib.Path)
    args = parser.parse_args()
    made = json.loads((args.run / "turek_hron.json").read_text())
    test = made["test"]
    coupled = test != "cfd3"  # cfd3: the fluid alone, forces only
    force_times, drag, lift = read_forces(args.run / "fluid", made["depth"])
    histories = {"drag": (force_times, drag), "lift": (force_times, lift)}
    if coupled:  # the tip too, and the coupling iterations
        times, ux, uy, iterations = read_tip(results_path(args.run / "case.yaml"))
        histories = {"ux": (times, ux), "uy": (times, uy), **histories}
    table = evaluate(test, histories, args.periods)
    print_table(test, table)
    if coupled:
        print(f"{test} coupling iterations per step {iterations.mean():.2f} over "
              f"{len(iterations)} steps (t = {times[-1]:g} s)")
        table["iterations_per_step"] = float(iterations.mean())
        table["steps"] = int(len(iterations))
    (args.run / "post.json").write_text(json.dumps(table, indent=1) + "\n")
    plot(test, histories, args.plot or args.run / "turek-hron.png")


if __name__ == "__main__":
    main()
