#!/usr/bin/python3
"""Compare the tube wall of this example (CalculiX sector) with examples/tube/flow_structure
(the built-in tube structure): radial wall displacement at three points over time, and along
the tube at three times, over the 35 steps of this example. Both runs must be done first:

  build/bin/cocopp run examples/tube/flow_structure/case.yaml
  build/bin/cocopp run examples/tube/flow_calculix/case.yaml
  /usr/bin/python3 examples/tube/flow_calculix/compare.py [-o docs/tube-flow-calculix.png]
"""
import argparse
import os

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
RUNS = {"CalculiX sector (flow_calculix)": os.path.join(HERE, "results", "case.h5"),
        "tube structure (flow_structure)": os.path.join(HERE, "..", "flow_structure", "results",
                                                        "case.h5")}


def load(path):
    with h5py.File(path, "r") as f:
        time = f["steps/time"][:]
        z = f["x/wall/coordinates"][:, 2]
        radial = f["x/wall/displacement"][:, :, 1]  # the flow's points: radial = y
    return time, z, radial


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--output", default=os.path.join(HERE, "comparison.png"))
    arguments = parser.parse_args()
    data = {label: load(path) for label, path in RUNS.items()}
    steps = min(len(time) for time, _, _ in data.values())
    data = {label: (time[:steps], z, radial[:steps]) for label, (time, z, radial) in data.items()}
    figure, (history, profile) = plt.subplots(1, 2, figsize=(12, 4.5))
    styles = ["-", "--"]
    for (label, (time, z, radial)), style in zip(data.items(), styles):
        for position, colour in zip([-0.015, 0.0, 0.015], ["C0", "C1", "C2"]):
            i = int(np.argmin(np.abs(z - position)))
            history.plot(time * 1e3, radial[:, i] * 1e6, style, color=colour,
                         label="%s, z = %.0f mm" % (label.split(" (")[0], z[i] * 1e3))
        for step, colour in zip([10, 20, 35], ["C3", "C4", "C5"]):
            row = int(np.flatnonzero(np.isclose(time, step * 1e-4))[0])
            profile.plot(z * 1e3, radial[row] * 1e6, style, color=colour,
                         label="%s, t = %.1f ms" % (label.split(" (")[0], time[row] * 1e3))
    history.set_xlabel("t (ms)")
    history.set_ylabel("radial wall displacement (µm)")
    history.legend(fontsize=7)
    history.set_title("wall displacement over time")
    profile.set_xlabel("z (mm)")
    profile.set_ylabel("radial wall displacement (µm)")
    profile.legend(fontsize=7)
    profile.set_title("along the tube (solid: CalculiX, dashed: tube structure)")
    figure.tight_layout()
    figure.savefig(arguments.output, dpi=110)
    (_, _, a), (_, _, b) = data.values()
    print("wrote %s; peak displacement: CalculiX %.3g m, tube structure %.3g m; "
          "RMS difference / RMS tube structure: %.3f"
          % (arguments.output, np.abs(a).max(), np.abs(b).max(),
             np.sqrt(np.mean((a - b) ** 2) / np.mean(b ** 2))))


if __name__ == "__main__":
    main()
