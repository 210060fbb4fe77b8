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

R0, H, LENGTH = 0.005, 0.001, 0.05
E, NU, RHO = 3.0e5, 0.3, 1200.0
DELTA_T = 1.0e-4
ANGLE, CENTRE = 1.0, 90.0  # degrees

# C3D20 nodes in natural coordinates (radial, hoop, axial), 0..2 on the doubled grid.
LOCAL = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2),
         (1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 1, 2),
         (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1)]


def sector_mesh(axial):
    """Nodes, elements, WALLMID, ENDS and WALL of the 1 degree C3D20 sector."""
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
    lines += ["*TRANSFORM, NSET=NALL, TYPE=C", "0., 0., 0., 0., 0., 1."]
    return lines


def axisymmetric_mesh(axial):
    """Nodes, elements, WALLMID, ENDS and WALL of the CAX8 model (x radius, y axis)."""
    ni, nk = 3, 2 * axial + 1

    def node_id(i, k):
        return 1 + i + ni * k

    lines = ["** Tube wall of the 1D tube example: axisymmetric CAX8, x = radius, y = axis "
             "(make_wall.py --axisymmetric)", "*NODE, NSET=NALL"]
    for k in range(nk):
        for i in range(ni):
            if i % 2 + k % 2 <= 1:
                lines.append("%d, %.13g, %.13g, 0." % (node_id(i, k), R0 + H * i / (ni - 1),
                                                        -LENGTH / 2 + LENGTH * k / (nk - 1)))
    lines.append("*ELEMENT, TYPE=CAX8, ELSET=EALL")  # corners counter-clockwise, then mid-sides
    for q in range(axial):
        k = 2 * q
        ids = [node_id(0, k), node_id(2, k), node_id(2, k + 2), node_id(0, k + 2),
               node_id(1, k), node_id(2, k + 1), node_id(1, k + 2), node_id(0, k + 1)]
        lines.append("%d, %s" % (q + 1, ", ".join(map(str, ids))))
    lines.append("*NSET, NSET=WALLMID")
    lines += ["%d," % node_id(0, k) for k in range(0, nk, 2)]
    lines.append("*NSET, NSET=ENDS")
    lines += ["%d," % node_id(i, k) for k in (0, nk - 1) for i in range(ni)]
    lines.append("*SURFACE, NAME=WALL, TYPE=ELEMENT")  # the bore (nodes 4-1) is edge S4
    lines += ["%d, S4" % (q + 1) for q in range(axial)]
    return lines


def main():
    arguments = sys.argv[1:]
    axisymmetric = "--axisymmetric" in arguments
    arguments = [a for a in arguments if a != "--axisymmetric"]
    axial = int(arguments[0]) if arguments else 50
    lines = axisymmetric_mesh(axial) if axisymmetric else sector_mesh(axial)
    boundary = (["** ends clamped", "*BOUNDARY", "ENDS, 1, 2"] if axisymmetric else
                ["** hoop displacement zero everywhere (axisymmetry); ends clamped",
                 "*BOUNDARY", "NALL, 2, 2", "ENDS, 1, 3"])
    lines += ["*MATERIAL, NAME=WALL", "*ELASTIC", "%g, %g" % (E, NU), "*DENSITY", "%g" % RHO,
              "*SOLID SECTION, ELSET=EALL, MATERIAL=WALL"] + boundary + [
              "** One coupling time step; the coupler's loads are ramped over it (ccx keeps no",
              "** accelerations in its restart file: a step-amplitude load would jump)",
              "*STEP, AMPLITUDE=RAMP", "*DYNAMIC, DIRECT, ALPHA=0", "%g, %g" % (DELTA_T, DELTA_T),
              "*END STEP"]
    with open("wall_cax.inp" if axisymmetric else "wall.inp", "w") as out:
        out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
