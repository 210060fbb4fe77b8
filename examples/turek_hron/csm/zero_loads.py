#!/usr/bin/env python3
"""zero_loads.py: the Turek-Hron CSM tests' partner, a cocopp solver (Python SDK) that loads
the flag with nothing: points along its upper edge take the displacement and give zero
pressure and traction. The flag then moves under its own weight alone, driven by the coupler.

usage: zero_loads.py [points=8]
Interface: model part `flag_top`, `points` points at y = 0.21 from x = 0.25 to 0.6, input
displacement, output pressure and traction (zeros)."""
import sys

import numpy as np

import cocopp_sdk as sdk


class ZeroLoads(sdk.Solver):
    def __init__(self, points):
        self.points = int(points)

    def initialize(self, run):
        x = np.linspace(0.25, 0.6, self.points)
        coordinates = np.column_stack([x, np.full(self.points, 0.21), np.zeros(self.points)])
        top = sdk.ModelPart("flag_top", ids=np.arange(self.points), coordinates=coordinates,
                            inputs=["displacement"], outputs=["pressure", "traction"])
        return sdk.Interface([top])

    def solve(self, values):
        return np.zeros(self.interface.output_size)


def main(argv):
    if sdk.wants_help(argv):
        print(__doc__)
        return 0
    parameters = dict(argument.split("=", 1) for argument in argv[1:])
    return sdk.serve(ZeroLoads(parameters.get("points", 8)), argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
