"""The elastic flag of the Turek-Hron benchmark as a CalculiX deck, shared by the CSM tests
(examples/turek_hron/csm/make_flag.py, docs/validation-turek-hron-csm.md) and the FSI tests
(examples/turek_hron/fsi/make_case.py, docs/validation-turek-hron.md).

S. Turek, J. Hron, "Proposal for numerical benchmarking of fluid-structure interaction between
an elastic object and laminar incompressible flow", in: Fluid-Structure Interaction, LNCSE 53,
Springer 2006, 371-385: the flag is 0.35 x 0.02 m behind the cylinder of radius 0.05 m centred
at (0.2, 0.2), clamped where it meets the cylinder (the left edge follows the circle), its tip
centre A at (0.6, 0.2); St. Venant-Kirchhoff (linear elastic with NLGEOM), nu 0.4; plane strain
(CPE8, thickness 1 m). csm1, csm2: static under gravity 2 m/s2 in -y; csm3: dynamic from rest
under gravity; fsi1, fsi2, fsi3: dynamic, no gravity.
"""
import math

from cocopp.calculix import Deck

CENTRE, RADIUS = (0.2, 0.2), 0.05
LENGTH_END, HALF_THICKNESS = 0.6, 0.01
NU, GRAVITY = 0.4, 2.0
SHEAR_MODULUS = {"csm1": 0.5e6, "csm2": 2.0e6, "csm3": 0.5e6,
                 "fsi1": 0.5e6, "fsi2": 0.5e6, "fsi3": 2.0e6}
DENSITY = {"csm1": 1000.0, "csm2": 1000.0, "csm3": 1000.0,
           "fsi1": 1000.0, "fsi2": 10000.0, "fsi3": 1000.0}
TESTS = list(SHEAR_MODULUS)


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


def flag_elements(nodes, nx, ny):
    """[(element, its 8 nodes)], the upper edge's elements and the wetted faces (bottom S1, tip
    S2, top S3) in element order."""
    elements, top, wet = [], [], []
    for ey in range(ny):
        for ex in range(nx):
            i, j = 2 * ex, 2 * ey
            corners = [(i, j), (i + 2, j), (i + 2, j + 2), (i, j + 2)]
            middles = [(i + 1, j), (i + 2, j + 1), (i + 1, j + 2), (i, j + 1)]
            element = ey * nx + ex + 1
            elements.append((element, [nodes[ij][0] for ij in corners + middles]))
            if ey == 0:
                wet.append((element, "S1"))
            if ex == nx - 1:
                wet.append((element, "S2"))
            if ey == ny - 1:
                top.append(element)
                wet.append((element, "S3"))
    return elements, top, wet


def flag_deck(test, nx, ny, dt, alpha=0.0):
    """The flag of `test` (csm1..3, fsi1..3), nx x ny CPE8 elements, as a deck: sets CLAMPED,
    POINTA (the tip node A), TOP (the upper edge's faces), WET (the faces of the three sides in
    the flow: bottom, tip, top) and WETN (their nodes); dynamic tests with time step dt and
    ccx's HHT alpha."""
    nodes = node_grid(nx, ny)
    deck = Deck(f"** Turek-Hron {test.upper()}: the flag, {nx} x {ny} CPE8 (make_flag.py)")
    deck.nodes(sorted(nodes.values()))
    elements, top, wet = flag_elements(nodes, nx, ny)
    deck.elements("CPE8", elements, elset="FLAG")
    deck.node_set("CLAMPED", [nodes[(0, j)][0] for j in range(2 * ny + 1)])
    deck.node_set("POINTA", [nodes[(2 * nx, ny)][0]])
    deck.surface("TOP", [(element, "S3") for element in top])
    deck.surface("WET", wet)
    deck.node_set("WETN", [number for (i, j), (number, _, _) in sorted(nodes.items())
                           if j in (0, 2 * ny) or i == 2 * nx])
    deck.add("*BOUNDARY", "CLAMPED, 1, 2",
             "*MATERIAL, NAME=FLAG", "*ELASTIC",
             f"{2 * SHEAR_MODULUS[test] * (1 + NU):.13g}, {NU}",
             "*DENSITY", f"{DENSITY[test]}",
             "*SOLID SECTION, ELSET=FLAG, MATERIAL=FLAG", "1.")
    if test in ("csm1", "csm2"):
        deck.add("*STEP, NLGEOM, INC=1000", "*STATIC", "0.1, 1.0, 1e-5, 0.1")
    else:
        deck.add("*STEP, NLGEOM, INC=1000", f"*DYNAMIC, DIRECT, ALPHA={alpha:g}", f"{dt}, {dt}")
    if test.startswith("csm"):
        deck.add("*DLOAD", f"FLAG, GRAV, {GRAVITY}, 0., -1., 0.")
    deck.add("*NODE FILE", "U", "*END STEP")
    return deck.text()
