#!/usr/bin/python3
"""Write wall.inp: the wall of the 1D tube example (docs/tube-solvers.md) as a CalculiX model.

The tube wall (inner radius 5 mm, thickness 1 mm, length 50 mm, E 3e5 Pa, nu 0.3, rho 1200)
is axisymmetric. Debian's ccx 2.20 cannot restart axisymmetric (CAX) elements, so the wall is
a 1 degree sector of C3D20 elements (one through the thickness, AXIAL along the tube) with a
cylindrical *TRANSFORM and zero hoop displacement, centred on the y axis where the flow's
interface points (0, r0, z) lie. Both ends are clamped. Surface WALL (the bore, loads) and node
set WALLMID (bore nodes in the sector's mid-plane, x = 0: displacements) form the interface.
The step is dynamic, one coupling time step long, with the loads ramped over the step.

Full integration (C3D20, not C3D20R) and ALPHA=0 because ccx starts every step by solving for
the acceleration with the internal forces integrated at 27 points: with reduced-integration
elements a series of one-increment steps blows up; with ALPHA=0 the step start matches the
trapezoidal rule of the increments (docs/solver-wrappers-calculix.md, "Dynamic steps").

  /usr/bin/python3 make_wall.py [AXIAL]     # AXIAL elements along the tube (default 50)
"""
import math
import sys

R0, H, LENGTH = 0.005, 0.001, 0.05
E, NU, RHO = 3.0e5, 0.3, 1200.0
DELTA_T = 1.0e-4
ANGLE, CENTRE = 1.0, 90.0  # degrees

# C3D20 nodes in natural coordinates (radial, hoop, axial), 0..2 on the doubled grid.
LOCAL = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2),
         (1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 1, 2),
         (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1)]


def main():
    axial = int(sys.argv[1]) if len(sys.argv) > 1 else 50
    ni, nj, nk = 3, 3, 2 * axial + 1

    def node_id(i, j, k):
        return 1 + i + ni * (j + nj * k)

    def exists(i, j, k):
        return i % 2 + j % 2 + k % 2 <= 1

    # ccx reads numbers from 20-character fields: 13 significant digits fit.
    lines = ["** Tube wall of the 1D tube example: %g degree sector of C3D20 (make_wall.py)" % ANGLE,
             "*NODE, NSET=NALL"]
    for k in range(nk):
        z = -LENGTH / 2 + LENGTH * k / (nk - 1)
        for j in range(nj):
            theta = math.radians(CENTRE + ANGLE * (j - 1) / 2)
            for i in range(ni):
                if exists(i, j, k):
                    r = R0 + H * i / (ni - 1)
                    lines.append("%d, %.13g, %.13g, %.13g" % (node_id(i, j, k), r * math.cos(theta),
                                                              r * math.sin(theta), z))
    lines.append("*ELEMENT, TYPE=C3D20, ELSET=EALL")
    for q in range(axial):
        ids = [node_id(a, b, 2 * q + c) for a, b, c in LOCAL]
        lines.append("%d, %s," % (q + 1, ", ".join(map(str, ids[:15]))))
        lines.append(", ".join(map(str, ids[15:])))
    lines.append("*NSET, NSET=WALLMID")
    lines += ["%d," % node_id(0, 1, k) for k in range(0, nk, 2)]
    lines.append("*NSET, NSET=ENDS")
    lines += ["%d," % node_id(i, j, k) for k in (0, nk - 1) for j in range(nj) for i in range(ni)
              if exists(i, j, k)]
    lines.append("*SURFACE, NAME=WALL, TYPE=ELEMENT")  # the bore (radial xi = -1) is face S6
    lines += ["%d, S6" % (q + 1) for q in range(axial)]
    lines += ["*TRANSFORM, NSET=NALL, TYPE=C", "0., 0., 0., 0., 0., 1.",
              "*MATERIAL, NAME=WALL", "*ELASTIC", "%g, %g" % (E, NU), "*DENSITY", "%g" % RHO,
              "*SOLID SECTION, ELSET=EALL, MATERIAL=WALL",
              "** hoop displacement zero everywhere (axisymmetry); ends clamped",
              "*BOUNDARY", "NALL, 2, 2", "ENDS, 1, 3",
              "** One coupling time step; the coupler's loads are ramped over it (ccx keeps no",
              "** accelerations in its restart file: a step-amplitude load would jump)",
              "*STEP, AMPLITUDE=RAMP", "*DYNAMIC, DIRECT, ALPHA=0", "%g, %g" % (DELTA_T, DELTA_T),
              "*END STEP"]
    with open("wall.inp", "w") as out:
        out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
