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
in the flow: bottom, tip, top), WETN (their nodes) and POINTA (the tip node A). The deck is
cocopp.turek_hron's (python/cocopp), which the FSI tests' make_case.py writes too.
"""
import argparse

from cocopp import turek_hron


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", choices=turek_hron.TESTS)
    parser.add_argument("--nx", type=int, default=40, help="elements along the flag")
    parser.add_argument("--ny", type=int, default=4, help="elements through its thickness")
    parser.add_argument("--dt", type=float, default=0.005, help="dynamic tests: the time step (s)")
    parser.add_argument("--alpha", type=float, default=0.0,
                        help="dynamic tests: ccx's HHT alpha in [-1/3, 0] (0: no numerical damping)")
    parser.add_argument("--output", default="flag.inp")
    args = parser.parse_args()
    with open(args.output, "w") as out:
        out.write(turek_hron.flag_deck(args.case, args.nx, args.ny, args.dt, args.alpha))


if __name__ == "__main__":
    main()
