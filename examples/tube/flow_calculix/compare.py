#!/usr/bin/python3
"""Compare the tube wall of this example (CalculiX sector) with the 1D tube structure: radial
wall displacement at three points over time, and along the tube at three times.

Two references: equivalent_tube/ (the tube structure with the thick wall's Lame stiffness and
the trapezoidal rule ccx uses; the one that should agree) and examples/tube/flow_structure (the
thin-ring tube structure with backward Euler). The runs must be done first:

  cocopp run examples/tube/flow_calculix/case.yaml
  cocopp run examples/tube/flow_calculix/equivalent_tube/case.yaml
  cocopp run examples/tube/flow_structure/case.yaml
  /usr/bin/python3 examples/tube/flow_calculix/compare.py [-o results/tube-flow-calculix.png]

If case_axisymmetric.yaml (the same wall as CAX8 elements) has run too, its difference from the
sector is printed.
"""
import argparse
import os

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from cocopp.results import ResultsFile, results_path  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
RUNS = [("CalculiX sector", "-", os.path.join(HERE, "case.yaml")),
        ("equivalent tube structure", "--", os.path.join(HERE, "equivalent_tube", "case.yaml")),
        ("thin-ring tube structure (flow_structure)", ":",
         os.path.join(HERE, "..", "flow_structure", "case.yaml"))]


def load(case_file):
    """Time, z of the wall's points and their radial displacement, from a run of `case_file`."""
    with ResultsFile(results_path(case_file)) as results:
        z = results.coordinates("x", "wall")[:, 2]
        radial = results.values("x", "wall", "displacement")[:, :, 1]  # flow's points: radial = y
        return results.times, z, radial


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output",
                        default=os.path.join(HERE, "results", "tube-flow-calculix.png"))
    arguments = parser.parse_args()
    data = [(label, style) + load(path) for label, style, path in RUNS]
    steps = min(len(time) for _, _, time, _, _ in data)
    figure, (history, profile) = plt.subplots(1, 2, figsize=(13, 5))
    for label, style, time, z, radial in data:
        time, radial = time[:steps], radial[:steps]
        short = label.split(" (")[0]
        for position, colour in zip([-0.015, 0.0, 0.015], ["C0", "C1", "C2"]):
            i = int(np.argmin(np.abs(z - position)))
            history.plot(time * 1e3, radial[:, i] * 1e6, style, color=colour,
                         label="%s, z = %.0f mm" % (short, round(z[i] * 1e3) + 0.0))  # no "-0"
        for step, colour in zip([20, 50, steps], ["C3", "C4", "C5"]):
            row = step - 1
            profile.plot(z * 1e3, radial[row] * 1e6, style, color=colour,
                         label="%s, t = %.1f ms" % (short, time[row] * 1e3))
    history.set_xlabel("t (ms)")
    history.set_ylabel("radial wall displacement (µm)")
    history.legend(fontsize=6)
    history.set_title("wall displacement over time")
    profile.set_xlabel("z (mm)")
    profile.set_ylabel("radial wall displacement (µm)")
    profile.legend(fontsize=6)
    profile.set_title("along the tube (solid: CalculiX, dashed: equivalent, dotted: thin ring)")
    figure.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(arguments.output)), exist_ok=True)
    figure.savefig(arguments.output, dpi=110)
    calculix = data[0][4][:steps]
    print("wrote %s over %d steps; peak displacement of the CalculiX sector %.3g m"
          % (arguments.output, steps, np.abs(calculix).max()))
    for label, _, _, _, radial in data[1:]:
        radial = radial[:steps]
        print("  %s: peak %.3g m, RMS difference / RMS of it: %.3f"
              % (label, np.abs(radial).max(),
                 np.sqrt(np.mean((calculix - radial) ** 2) / np.mean(radial ** 2))))
    axisymmetric = os.path.join(HERE, "case_axisymmetric.yaml")
    if results_path(axisymmetric).exists():
        radial = load(axisymmetric)[2][:steps]
        print("  CalculiX CAX8 (case_axisymmetric): peak %.4g m, largest difference from the "
              "sector / peak: %.1e" % (np.abs(radial).max(),
                                       np.abs(calculix - radial).max() / np.abs(calculix).max()))


if __name__ == "__main__":
    main()
