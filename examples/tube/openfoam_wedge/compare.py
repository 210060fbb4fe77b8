#!/usr/bin/env python3
"""Compare the OpenFOAM wedge tube with the 1D flow-structure tube: the pressure at mid-tube
(z = 0) over time. The pulse must arrive at the same time within 10 % (arrival: the first time
the pressure reaches half of its peak) with a similar peak. Exit code 1 if the arrival times
differ by more than 10 %.

    /usr/bin/python3 compare.py results/case.h5 results/flow_structure_1d/results/case.h5 [--plot out.png]
"""
import argparse
import sys

import numpy as np

from cocopp.results import ResultsFile


def mid_tube_pressure(results_file):
    """Time and the pressure at z = 0 (linear between the two nearest points), from the fluid's
    output model part (the only one in y)."""
    with ResultsFile(results_file) as results:
        part = results.model_parts("y")[0]
        z = results.coordinates("y", part)[:, 2]
        pressure = results.values("y", part, "pressure")[:, :, 0]
        time = results.times
    order = np.argsort(z)
    at_mid = np.array([np.interp(0.0, z[order], row[order]) for row in pressure])
    return np.concatenate([[0.0], time]), np.concatenate([[0.0], at_mid])


def arrival(time, pressure):
    """First time the pressure reaches half of its peak (linear between steps)."""
    half = 0.5 * pressure.max()
    k = int(np.argmax(pressure >= half))
    return time[k - 1] + (half - pressure[k - 1]) / (pressure[k] - pressure[k - 1]) * (time[k] - time[k - 1])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("wedge", help="results of the OpenFOAM wedge run (HDF5)")
    parser.add_argument("reference", help="results of the 1D flow-structure run (HDF5)")
    parser.add_argument("--plot", help="write the comparison plot to this file")
    parser.add_argument("--names", nargs=2, default=["wedge", "1D"], help="short names of the two runs")
    args = parser.parse_args()
    a, b = args.names

    runs = {"OpenFOAM wedge + 1D structure": mid_tube_pressure(args.wedge),
            "1D flow + 1D structure": mid_tube_pressure(args.reference)}
    (t_w, p_w), (t_r, p_r) = runs.values()
    arrival_w, arrival_r = arrival(t_w, p_w), arrival(t_r, p_r)
    arrival_error = abs(arrival_w - arrival_r) / arrival_r
    print(f"arrival at mid-tube (half peak): {a} {arrival_w * 1e3:.3f} ms, {b} {arrival_r * 1e3:.3f} ms, "
          f"difference {100 * arrival_error:.1f} %")
    print(f"peak pressure at mid-tube: {a} {p_w.max():.1f} Pa at {t_w[p_w.argmax()] * 1e3:.2f} ms, "
          f"{b} {p_r.max():.1f} Pa at {t_r[p_r.argmax()] * 1e3:.2f} ms, ratio {p_w.max() / p_r.max():.3f}")
    print(f"largest difference of the mid-tube pressure: {np.abs(np.interp(t_r, t_w, p_w) - p_r).max():.3g} Pa")

    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4))
        for label, (t, p) in runs.items():
            ax.plot(t * 1e3, p, label=label)
        ax.axvline(arrival_w * 1e3, color="C0", linestyle=":", linewidth=1)
        ax.axvline(arrival_r * 1e3, color="C1", linestyle=":", linewidth=1)
        ax.set_xlabel("time (ms)")
        ax.set_ylabel("pressure at mid-tube (Pa)")
        ax.set_title(f"Pressure pulse at z = 0: arrival differs by {100 * arrival_error:.1f} %, "
                     f"peak ratio {p_w.max() / p_r.max():.2f}", fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"plot: {args.plot}")
    return 0 if arrival_error <= 0.10 else 1


if __name__ == "__main__":
    sys.exit(main())
