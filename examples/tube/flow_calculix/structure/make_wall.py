#!/usr/bin/python3
"""Write the wall of the 1D tube example (docs/tube-solvers.md) as a CalculiX model.

The tube wall (inner radius 5 mm, thickness 1 mm, length 50 mm, E 3e5 Pa, nu 0.3, rho 1200)
is axisymmetric. Two models of it, with AXIAL elements along the tube and one through the
thickness, both ends clamped:
- wall.inp: a 1 degree sector of C3D20 elements with a cylindrical *TRANSFORM and zero hoop
  displacement, centred on the y axis where the flow's interface points (0, r0, z) lie. It runs
  with any ccx (Debian's crashes when it restarts CAX models). Node set WALLMID: the bore nodes
  in the sector's mid-plane (x = 0).
- wall_cax.inp (--axisymmetric): CAX8 elements in the x-y plane (x = radius, y = the tube's
  axis z), as an axisymmetric model is usually written; restarting it needs the ccx that
  scripts/install-calculix.sh builds. Node set WALLMID: the bore's corner nodes.
Surface WALL (the bore, loads) and node set WALLMID (displacements) form the interface. The
step is dynamic, one coupling time step long, with the loads ramped over the step.

Full integration (C3D20, not C3D20R) and ALPHA=0 because ccx starts every step by solving for
the acceleration with the internal forces integrated at 27 points: with reduced-integration
elements a series of one-increment steps blows up; with ALPHA=0 the step start matches the
trapezoidal rule of the increments (docs/solver-wrappers-calculix.md, "Dynamic steps").

  /usr/bin/python3 make_wall.py [--axisymmetric] [AXIAL]   # AXIAL: elements along (50)
"""
import math
import sys

from cocopp.calculix import Deck

R0, H, LENGTH = 0.005, 0.001, 0.05
E, NU, RHO = 3.0e5, 0.3, 1200.0
DELTA_T = 1.0e-4
ANGLE, CENTRE = 1.0, 90.0  # degrees

# C3D20 nodes in natural coordinates (radial, hoop, axial), 0..2 on the doubled grid.
LOCAL = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2),
         (1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 1, 2),
         (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1)]


def sector_mesh(axial):
    """A deck of the 1 degree C3D20 sector's nodes, elements, WALLMID, ENDS and WALL."""
    ni, nj, nk = 3, 3, 2 * axial + 1

    def node_id(i, j, k):
        return 1 + i + ni * (j + nj * k)

    def exists(i, j, k):
        return i % 2 + j % 2 + k % 2 <= 1

    deck = Deck("** Tube wall of the 1D tube example: %g degree sector of C3D20 (make_wall.py)"
                % ANGLE)

    def position(i, j, k):
        r, theta = R0 + H * i / (ni - 1), math.radians(CENTRE + ANGLE * (j - 1) / 2)
        return (node_id(i, j, k), r * math.cos(theta), r * math.sin(theta),
                -LENGTH / 2 + LENGTH * k / (nk - 1))

    deck.nodes(position(i, j, k) for k in range(nk) for j in range(nj) for i in range(ni)
               if exists(i, j, k))
    deck.elements("C3D20", ((q + 1, [node_id(a, b, 2 * q + c) for a, b, c in LOCAL])
                            for q in range(axial)))
    deck.node_set("WALLMID", [node_id(0, 1, k) for k in range(0, nk, 2)])
    deck.node_set("ENDS", [node_id(i, j, k) for k in (0, nk - 1) for j in range(nj)
                           for i in range(ni) if exists(i, j, k)])
    deck.surface("WALL", [(q + 1, "S6") for q in range(axial)])  # the bore (radial xi = -1)
    deck.add("*TRANSFORM, NSET=NALL, TYPE=C", "0., 0., 0., 0., 0., 1.")
    return deck


def axisymmetric_mesh(axial):
    """A deck of the CAX8 model's nodes, elements, WALLMID, ENDS and WALL (x radius, y axis)."""
    ni, nk = 3, 2 * axial + 1

    def node_id(i, k):
        return 1 + i + ni * k

    deck = Deck("** Tube wall of the 1D tube example: axisymmetric CAX8, x = radius, y = axis "
                "(make_wall.py --axisymmetric)")
    deck.nodes((node_id(i, k), R0 + H * i / (ni - 1), -LENGTH / 2 + LENGTH * k / (nk - 1), "0.")
               for k in range(nk) for i in range(ni) if i % 2 + k % 2 <= 1)
    # Corners counter-clockwise, then mid-sides.
    deck.elements("CAX8", ((q + 1, [node_id(0, 2 * q), node_id(2, 2 * q), node_id(2, 2 * q + 2),
                                    node_id(0, 2 * q + 2), node_id(1, 2 * q), node_id(2, 2 * q + 1),
                                    node_id(1, 2 * q + 2), node_id(0, 2 * q + 1)])
                           for q in range(axial)))
    deck.node_set("WALLMID", [node_id(0, k) for k in range(0, nk, 2)])
    deck.node_set("ENDS", [node_id(i, k) for k in (0, nk - 1) for i in range(ni)])
    deck.surface("WALL", [(q + 1, "S4") for q in range(axial)])  # the bore (nodes 4-1)
    return deck


def main():
    arguments = sys.argv[1:]
    axisymmetric = "--axisymmetric" in arguments
    arguments = [a for a in arguments if a != "--axisymmetric"]
    axial = int(arguments[0]) if arguments else 50
    deck = axisymmetric_mesh(axial) if axisymmetric else sector_mesh(axial)
    boundary = (["** ends clamped", "*BOUNDARY", "ENDS, 1, 2"] if axisymmetric else
                ["** hoop displacement zero everywhere (axisymmetry); ends clamped",
                 "*BOUNDARY", "NALL, 2, 2", "ENDS, 1, 3"])
    deck.add(*["*MATERIAL, NAME=WALL", "*ELASTIC", "%g, %g" % (E, NU), "*DENSITY", "%g" % RHO,
               "*SOLID SECTION, ELSET=EALL, MATERIAL=WALL"] + boundary + [
              "** One coupling time step; the coupler's loads are ramped over it (ccx keeps no",
              "** accelerations in its restart file: a step-amplitude load would jump)",
              "*STEP, AMPLITUDE=RAMP", "*DYNAMIC, DIRECT, ALPHA=0", "%g, %g" % (DELTA_T, DELTA_T),
              "*END STEP"])
    with open("wall_cax.inp" if axisymmetric else "wall.inp", "w") as out:
        out.write(deck.text())


if __name__ == "__main__":
    main()
