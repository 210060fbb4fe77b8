#!/usr/bin/env python3
"""ring_wall.py: the wall of a 1D flexible tube as independent massless rings (a tube law),
a cocopp solver in Python on the Python SDK (cocopp_sdk, docs/install.md). The same model as
ring_wall.cpp and cocopp's built-in tube_ringmodel.

usage: ring_wall.py length=0.05 diameter=0.01 cells=100 rho_f=1000 e=3e5 h=1e-3
Interface: model part `wall` (one point per cell centre), input pressure and traction
(ignored), output displacement (0, radial, 0)."""
import sys

import numpy as np

import cocopp_sdk as sdk


class RingWall(sdk.Solver):
    """Tube law r = r0 * 2 / (2 - p / (rho_f c0^2)), c0^2 = e h / (rho_f d)."""

    def __init__(self, length, diameter, cells, rho_f, e, h):
        self.length, self.diameter, self.cells = length, diameter, int(cells)
        self.radius = 0.5 * diameter
        self.rho_f = rho_f
        self.c02 = e * h / (rho_f * diameter)  # Moens-Korteweg wave speed squared

    def initialize(self, run):
        dz = self.length / self.cells
        z = -self.length / 2.0 + dz / 2.0 + np.arange(self.cells) * dz
        points = np.column_stack([np.zeros(self.cells), np.full(self.cells, self.radius), z])
        wall = sdk.ModelPart("wall", ids=np.arange(self.cells), coordinates=points,
                             inputs=["pressure", "traction"], outputs=["displacement"])
        return sdk.Interface([wall])  # initial output: zeros, the undeformed wall

    def solve(self, values):
        p = self.interface.split_input(values)["wall", "pressure"][:, 0] / self.rho_f
        if np.any(p >= 2 * self.c02):
            raise RuntimeError("unphysical pressure: the tube law has no area")
        displacement = np.zeros((self.cells, 3))
        # In the order of operations of cocopp's tube_ringmodel: the same results to the bit.
        ratio = 2.0 / (2.0 + (0.0 - p) / self.c02)
        area = np.pi * self.diameter * self.diameter / 4.0 * ratio * ratio
        displacement[:, 1] = np.sqrt(area / np.pi) - self.radius
        return self.interface.join_output({("wall", "displacement"): displacement})

    def can_substep(self):
        """Massless rings hold no state between steps: nothing to keep for substeps."""
        return True


def main(argv):
    if sdk.wants_help(argv):
        print(__doc__)
        return 0
    try:
        parameters = dict(argument.split("=", 1) for argument in argv[1:])
        wall = RingWall(**{key: float(value) for key, value in parameters.items()})
    except (ValueError, TypeError) as error:
        print(f"ring_wall.py: {error}\n\n{__doc__}", file=sys.stderr)
        return 2
    return sdk.serve(wall, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
