#!/usr/bin/env python3
"""Write the Turek-Hron CSM tests' flag as a CalculiX deck (docs/validation-turek-hron-csm.md).

    make_flag.py csm1|csm2|csm3|fsi1|fsi2|fsi3 [--nx 40] [--ny 4] [--dt 0.005] [--alpha 0]
                 [--output flag.inp]

The elastic flag of the Turek-Hron benchmark (S. Turek, J. Hron, "Proposal for numerical
benchmarking of fluid-structure interaction between an elastic object and laminar
incompressible flow", in: Fluid-Structure Interaction, LNCSE 53, Springer 2006, 371-385):
0.35 x 0.02 m behind the cylinder of radius 0.05 m centred at (0.2, 0.2), clamped where it
meets the cylinder (the left edge follows the circle), its tip centre A at (0.6, 0.2);
St. Venant-Kirchhoff (linear elastic with NLGEOM), rho 1000 kg/m3, nu 0.4, mu 0.5e6 Pa
(E = 1.4e6 Pa; csm2: mu 2.0e6 Pa, E = 5.6e6 Pa), under gravity 2 m/s2 in -y; plane strain
(CPE8, thickness 1 m). csm1, csm2: static (steady state); csm3: dynamic from rest (*DYNAMIC,
ALPHA=0, time step dt).
fsi1, fsi2, fsi3: the FSI tests' flag (examples/turek_hron/fsi): no gravity, dynamic;
rho 1000 kg/m3, mu 0.5e6 Pa (fsi2: rho 10000 kg/m3; fsi3: mu 2.0e6 Pa), nu 0.4.
Sets for the calculix wrapper: TOP (the upper edge's faces), WET (the faces of the three sides
in the flow: bottom, tip, top), WETN (their nodes) and POINTA (the tip node A).
"""
import argparse
import math

CENTRE, RADIUS = (0.2, 0.2), 0.05
LENGTH_END, HALF_THICKNESS = 0.6, 0.01
NU, GRAVITY = 0.4, 2.0
SHEAR_MODULUS = {"csm1": 0.5e6, "csm2": 2.0e6, "csm3": 0.5e6,
                 "fsi1": 0.5e6, "fsi2": 0.5e6, "fsi3": 2.0e6}
DENSITY = {"csm1": 1000.0, "csm2": 1000.0, "csm3": 1000.0,
           "fsi1": 1000.0, "fsi2": 10000.0, "fsi3": 1000.0}
CASES = list(SHEAR_MODULUS)


def node_grid(nx, ny):
    """Nodes of the doubled grid (CPE8: no node at an element's centre): (i, j) -> (id, x, y)."""
    nodes = {}
    for j in range(2 * ny + 1):
        y = CENTRE[1] - HALF_THICKNESS + 2 * HALF_THICKNESS * j / (2 * ny)
        x_left = CENTRE[0] + math.sqrt(RADIUS ** 2 - (y - CENTRE[1]) ** 2)
        for i in range(2 * nx + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue
            x = x_left + (LENGTH_END - x_left) * i / (2 * nx)
            nodes[(i, j)] = (len(nodes) + 1, x, y)
    return nodes


def deck(case, nx, ny, dt, alpha=0.0):
    nodes = node_grid(nx, ny)
    lines = [f"** Turek-Hron {case.upper()}: the flag, {nx} x {ny} CPE8 (make_flag.py)",
             "*NODE, NSET=NALL"]
    lines += [f"{n}, {x:.13g}, {y:.13g}" for (n, x, y) in sorted(nodes.values())]
    lines.append("*ELEMENT, TYPE=CPE8, ELSET=FLAG")
    top, wet = [], []
    for ey in range(ny):
        for ex in range(nx):
            i, j = 2 * ex, 2 * ey
            corner = [nodes[(i, j)][0], nodes[(i + 2, j)][0], nodes[(i + 2, j + 2)][0],
                      nodes[(i, j + 2)][0]]
            middle = [nodes[(i + 1, j)][0], nodes[(i + 2, j + 1)][0], nodes[(i + 1, j + 2)][0],
                      nodes[(i, j + 1)][0]]
            element = ey * nx + ex + 1
            lines.append(f"{element}, " + ", ".join(str(n) for n in corner + middle))
            if ey == 0:
                wet.append(f"{element}, S1")
            if ex == nx - 1:
                wet.append(f"{element}, S2")
            if ey == ny - 1:
                top.append(element)
                wet.append(f"{element}, S3")
    lines.append("*NSET, NSET=CLAMPED")
    lines += [f"{nodes[(0, j)][0]}," for j in range(2 * ny + 1)]
    lines.append("*NSET, NSET=POINTA")
    lines.append(f"{nodes[(2 * nx, ny)][0]},")
    lines.append("*SURFACE, NAME=TOP, TYPE=ELEMENT")
    lines += [f"{e}, S3" for e in top]
    lines.append("*SURFACE, NAME=WET, TYPE=ELEMENT")
    lines += wet
    lines.append("*NSET, NSET=WETN")
    lines += [f"{number}," for (i, j), (number, _, _) in sorted(nodes.items())
              if j in (0, 2 * ny) or i == 2 * nx]
    lines += ["*BOUNDARY", "CLAMPED, 1, 2",
              "*MATERIAL, NAME=FLAG", "*ELASTIC",
              f"{2 * SHEAR_MODULUS[case] * (1 + NU):.13g}, {NU}",
              "*DENSITY", f"{DENSITY[case]}",
              "*SOLID SECTION, ELSET=FLAG, MATERIAL=FLAG", "1."]
    if case in ("csm1", "csm2"):
        lines += ["*STEP, NLGEOM, INC=1000", "*STATIC", "0.1, 1.0, 1e-5, 0.1"]
    else:
        lines += ["*STEP, NLGEOM, INC=1000", f"*DYNAMIC, DIRECT, ALPHA={alpha:g}", f"{dt}, {dt}"]
    if case.startswith("csm"):
        lines += ["*DLOAD", f"FLAG, GRAV, {GRAVITY}, 0., -1., 0."]
    lines += ["*NODE FILE", "U", "*END STEP"]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", choices=CASES)
    parser.add_argument("--nx", type=int, default=40, help="elements along the flag")
    parser.add_argument("--ny", type=int, default=4, help="elements through its thickness")
    parser.add_argument("--dt", type=float, default=0.005, help="dynamic tests: the time step (s)")
    parser.add_argument("--alpha", type=float, default=0.0,
                        help="dynamic tests: ccx's HHT alpha in [-1/3, 0] (0: no numerical damping)")
    parser.add_argument("--output", default="flag.inp")
    args = parser.parse_args()
    with open(args.output, "w") as out:
        out.write(deck(args.case, args.nx, args.ny, args.dt, args.alpha))


if __name__ == "__main__":
    main()
