#!/usr/bin/python3
"""Compare two runs of the wire drawing case step by step: how far apart the film's wall is
(the coupling's displacement x at the film's wall points) and the peak film pressure of each.
What the displacement-driven wire is checked with against the load-driven one
(docs/wire-drawing.md).

    /usr/bin/python3 examples/wire_drawing/compare_runs.py results/load_full results/drv_exact

Prints one line per time step both runs have; --steps 1,4,10 picks steps."""
import argparse
import sys
from pathlib import Path

import numpy as np

from cocopp.results import ResultsFile, results_path


def read(run):
    """Steps, the film's wall displacement (steps x points x 3) and pressure of a run."""
    path = results_path(Path(run) / "case.yaml")
    if not path.exists():
        sys.exit(f"compare_runs.py: {path}: no results (run the case first)")
    with ResultsFile(path, live=True) as results:  # a run still writing may be compared
        wall = results.model_parts("x")[0]
        faces = results.find_part("y", "pressure")
        return (results.steps, results.coordinates("x", wall),
                results.values("x", wall, "displacement"),
                results.values("y", faces, "pressure")[:, :, 0])


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("first")
    parser.add_argument("second")
    parser.add_argument("--steps", help="comma-separated steps to show (default: all)")
    args = parser.parse_args()
    steps_a, points_a, wall_a, p_a = read(args.first)
    steps_b, points_b, wall_b, p_b = read(args.second)
    if points_a.shape != points_b.shape or np.abs(points_a - points_b).max() > 1e-12:
        sys.exit("compare_runs.py: the two runs' films have different wall points (meshes)")
    wanted = ({int(s) for s in args.steps.split(",")} if args.steps
              else set(steps_a) & set(steps_b))
    axis = np.argmax(points_a.max(axis=0) - points_a.min(axis=0))  # the film's long direction
    print("step  wall difference (at, mm)  largest wall displacement  peak pressure (MPa)")
    for step in sorted(wanted & set(steps_a) & set(steps_b)):
        i, j = list(steps_a).index(step), list(steps_b).index(step)
        differences = np.linalg.norm(wall_a[i] - wall_b[j], axis=1)
        at = points_a[np.argmax(differences), axis]
        largest = np.linalg.norm(wall_a[i], axis=1).max()
        print(f"{step:4d}  {differences.max() * 1e6:10.4f} um ({at * 1e3:5.3f})  "
              f"{largest * 1e6:21.3f} um  "
              f"{p_a[i].max() / 1e6:9.1f} / {p_b[j].max() / 1e6:.1f}")


if __name__ == "__main__":
    main()
