#!/usr/bin/env python3
"""Tip displacement, drag and lift of a Turek-Hron FSI run against the published values
(docs/validation-turek-hron.md).

    post.py RUN [--periods 2] [--plot turek-hron.png]

RUN is a run directory of run.sh (its turek_hron.json says which test): u(A) from the coupler's
results (results/case.h5: the fluid's flag point at A = (0.6, 0.2)), drag and lift of cylinder
and flag together from OpenFOAM's forces (fluid/postProcessing/forces/*/force.dat) per metre of
depth. fsi1 (steady): the values at the end and their change over the last 0.5 s. fsi2, fsi3:
mean = (max + min) / 2, amplitude = (max - min) / 2 and frequency over the last --periods
periods of each quantity. Prints a table, writes RUN/post.json and the time histories
(RUN/turek-hron.png unless --plot).
"""
import argparse
import json
import pathlib
import re
import sys

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "csm"))
from tip import maxima  # noqa: E402  (peaks with a parabola through three samples)

POINT_A = (0.6, 0.2)
# S. Turek, J. Hron (2006), tables of the FSI tests (displacements in m, forces in N per m of
# depth): steady values (fsi1), or (mean, amplitude, frequency in Hz).
REFERENCE = {
    "fsi1": {"ux": 0.0227e-3, "uy": 0.8209e-3, "drag": 14.295, "lift": 0.7638},
    "fsi2": {"ux": (-14.58e-3, 12.44e-3, 3.8), "uy": (1.23e-3, 80.6e-3, 2.0),
             "drag": (208.83, 73.75, 3.8), "lift": (0.88, 234.2, 2.0)},
    "fsi3": {"ux": (-2.69e-3, 2.53e-3, 10.9), "uy": (1.48e-3, 34.38e-3, 5.3),
             "drag": (457.3, 22.66, 10.9), "lift": (2.22, 149.78, 5.3)},
}


def read_forces(fluid, depth):
    """(time, drag, lift) from every forces/<start>/force.dat (a restart adds a directory); a
    time written twice keeps its last value."""
    number = r"[-+0-9.eE]+"
    pattern = re.compile(rf"^\s*({number})\s+\(({number})\s+({number})\s+{number}\)")
    rows = {}
    for path in sorted((fluid / "postProcessing/forces").glob("*/force.dat"),
                       key=lambda p: float(p.parent.name)):
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
    with h5py.File(results, "r") as f:
        coordinates = f["x/flag_points/coordinates"][:]
        nearest = np.argmin(np.hypot(coordinates[:, 0] - POINT_A[0],
                                     coordinates[:, 1] - POINT_A[1]))
        displacement = f["x/flag_points/displacement"][:, nearest, :]
        return (f["steps/time"][:], displacement[:, 0], displacement[:, 1],
                f["steps/iterations"][:])


def oscillation(times, values, periods):
    """(mean, amplitude, frequency) over the last `periods` periods, or None if too few."""
    peaks = maxima(times, values)
    if len(peaks) < periods + 1:
        return None
    window = (times >= peaks[-1 - periods]) & (times <= peaks[-1])
    top, bottom = values[window].max(), values[window].min()
    return 0.5 * (top + bottom), 0.5 * (top - bottom), periods / (peaks[-1] - peaks[-1 - periods])


def evaluate(test, histories, periods):
    table = {}
    for name, (times, values) in histories.items():
        reference = REFERENCE[test][name]
        if test == "fsi1":
            last = times >= times[-1] - 0.5
            table[name] = {"value": float(values[-1]), "reference": reference,
                           "error": float(values[-1] / reference - 1),
                           "change_last_0.5s": float(np.ptp(values[last]))}
            continue
        found = oscillation(times, values, periods)
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
                  f"{100 * row['error']:+.2f} %  (change over the last 0.5 s "
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
    figure, axes = plt.subplots(4, 1, figsize=(8, 9), sharex=True)
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
    times, ux, uy, iterations = read_tip(args.run / "results/case.h5")
    force_times, drag, lift = read_forces(args.run / "fluid", made["depth"])
    histories = {"ux": (times, ux), "uy": (times, uy), "drag": (force_times, drag),
                 "lift": (force_times, lift)}
    table = evaluate(test, histories, args.periods)
    print_table(test, table)
    print(f"{test} coupling iterations per step {iterations.mean():.2f} over {len(iterations)} "
          f"steps (t = {times[-1]:g} s)")
    table["iterations_per_step"] = float(iterations.mean())
    table["steps"] = int(len(iterations))
    (args.run / "post.json").write_text(json.dumps(table, indent=1) + "\n")
    plot(test, histories, args.plot or args.run / "turek-hron.png")


if __name__ == "__main__":
    main()
