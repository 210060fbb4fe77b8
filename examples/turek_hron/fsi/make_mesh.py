#!/usr/bin/env python3
"""Write the Turek-Hron FSI channel as an OpenFOAM blockMeshDict (docs/validation-turek-hron.md).

    make_mesh.py [--level 1] [--depth 0.01] [--output system/blockMeshDict]

The channel 2.5 x 0.41 m with the cylinder (radius 0.05 m, centre (0.2, 0.2)) and the flag
(0.35 x 0.02 m, its tip centre A at (0.6, 0.2)) of S. Turek and J. Hron (2006), one cell thick
(z from 0 to --depth). 19 hexahedral blocks: an O-grid of five blocks around the cylinder
within the square [0.12, 0.28]^2, the flag's upper and lower blocks to x = 0.6, and strips to
the walls, the inlet and the outlet. --level L multiplies every block's cells by L in both
directions (level 1: 3144 cells; level 2: 12576).
Patches: inlet (x = 0), outlet (x = 2.5), walls (y = 0 and 0.41), cylinder, flag (the flag's
three wetted sides), frontAndBack (empty).
"""
import argparse
import math

from cocopp import openfoam

CENTRE, RADIUS = (0.2, 0.2), 0.05
LENGTH, HEIGHT = 2.5, 0.41
FLAG_END, FLAG_BOTTOM, FLAG_TOP = 0.6, 0.19, 0.21
# The lines of the block structure: x at the inlet, the square's sides, the flag's end, the
# outlet; y at the wall, the square's sides and the flag's sides, the top wall.
X = (0.0, 0.12, 0.28, FLAG_END, LENGTH)
Y = (0.0, 0.12, FLAG_BOTTOM, FLAG_TOP, 0.28, HEIGHT)
# Cells per block edge at level 1: the O-grid (arcs below/above the cylinder, its left arc,
# the arcs beside the flag's root, radially), along the flag, across its thickness behind the
# tip, left of the cylinder, downstream, and the strips to the walls.
CELLS = {"arc": 12, "left_arc": 12, "root_arc": 8, "radial": 10, "flag": 24, "tip": 4,
         "upstream": 8, "downstream": 40, "wall_strip": 8}


def on_cylinder(degrees):
    angle = math.radians(degrees)
    return (CENTRE[0] + RADIUS * math.cos(angle), CENTRE[1] + RADIUS * math.sin(angle))


def flag_root(y):
    return (CENTRE[0] + math.sqrt(RADIUS ** 2 - (y - CENTRE[1]) ** 2), y)


def vertices_2d():
    """Named points of the block structure: 'i,j' on the grid of X and Y; cylinder points by
    angle; the flag's root corners."""
    points = {f"{i},{j}": (X[i], Y[j]) for i in range(len(X)) for j in range(len(Y))}
    points.update({"R": on_cylinder(225), "S": on_cylinder(135), "Q": on_cylinder(300),
                   "Qt": on_cylinder(60), "Plo": flag_root(FLAG_BOTTOM),
                   "Phi": flag_root(FLAG_TOP)})
    return points


def angle_of(point):
    return math.degrees(math.atan2(point[1] - CENTRE[1], point[0] - CENTRE[0])) % 360


def expansion_for_first_cell(length, cells, first):
    """Total expansion ratio (last cell / first) of a geometric grading of `cells` cells over
    `length` whose first cell is `first` long (bisection on the cell-to-cell ratio)."""
    low, high = 1.0, 2.0
    for _ in range(200):
        ratio = 0.5 * (low + high)
        total = first * (ratio ** cells - 1) / (ratio - 1)
        low, high = (ratio, high) if total < length else (low, ratio)
    return ratio ** (cells - 1)


def blocks(level):
    """Each block: four named corners counter-clockwise (first edge along its first direction),
    cells along its two directions, grading along its first direction."""
    n = {key: value * level for key, value in CELLS.items()}
    flag_cell = (FLAG_END - X[2]) / n["flag"]
    outflow = expansion_for_first_cell(LENGTH - FLAG_END, n["downstream"], flag_cell)
    rows = [(0, "wall_strip"), (1, "root_arc"), (2, "tip"), (3, "root_arc"), (4, "wall_strip")]
    result = [
        # Upstream of the cylinder: below, beside and above the square.
        (("0,0", "1,0", "1,1", "0,1"), n["upstream"], n["wall_strip"], 1),
        (("0,1", "1,1", "1,4", "0,4"), n["upstream"], n["left_arc"], 1),
        (("0,4", "1,4", "1,5", "0,5"), n["upstream"], n["wall_strip"], 1),
        # Below and above the square.
        (("1,0", "2,0", "2,1", "1,1"), n["arc"], n["wall_strip"], 1),
        (("1,4", "2,4", "2,5", "1,5"), n["arc"], n["wall_strip"], 1),
        # The O-grid: the cylinder's arcs against the square's sides.
        (("R", "S", "1,4", "1,1"), n["left_arc"], n["radial"], 1),
        (("Q", "R", "1,1", "2,1"), n["arc"], n["radial"], 1),
        (("S", "Qt", "2,4", "1,4"), n["arc"], n["radial"], 1),
        (("Plo", "Q", "2,1", "2,2"), n["root_arc"], n["radial"], 1),
        (("Qt", "Phi", "2,3", "2,4"), n["root_arc"], n["radial"], 1),
        # Along the flag: wall strip, below, above, wall strip.
        (("2,0", "3,0", "3,1", "2,1"), n["flag"], n["wall_strip"], 1),
        (("2,1", "3,1", "3,2", "2,2"), n["flag"], n["root_arc"], 1),
        (("2,3", "3,3", "3,4", "2,4"), n["flag"], n["root_arc"], 1),
        (("2,4", "3,4", "3,5", "2,5"), n["flag"], n["wall_strip"], 1),
    ]
    # Downstream: five rows, the middle one behind the flag's tip.
    for j, cells in rows:
        result.append(((f"3,{j}", f"4,{j}", f"4,{j + 1}", f"3,{j + 1}"), n["downstream"],
                       n[cells], outflow))
    return result


# Patch of each block edge that lies on the boundary (the others are inside).
PATCH_EDGES = {
    "inlet": [("0,0", "0,1"), ("0,1", "0,4"), ("0,4", "0,5")],
    "outlet": [(f"4,{j}", f"4,{j + 1}") for j in range(5)],
    "walls": [(f"{i},0", f"{i + 1},0") for i in range(4)] +
             [(f"{i},5", f"{i + 1},5") for i in range(4)],
    "cylinder": [("R", "S"), ("Q", "R"), ("S", "Qt"), ("Plo", "Q"), ("Qt", "Phi")],
    "flag": [("Plo", "2,2"), ("Phi", "2,3"), ("2,2", "3,2"), ("2,3", "3,3"), ("3,2", "3,3")],
}


def signed_area(points):
    return 0.5 * sum(a[0] * b[1] - b[0] * a[1]
                     for a, b in zip(points, points[1:] + points[:1]))


def block_mesh_dict(level, depth):
    points2d = vertices_2d()
    names = list(points2d)
    index = {name: k for k, name in enumerate(names)}
    count = len(names)

    def front(name):
        return index[name]

    def back(name):
        return index[name] + count

    lines = [f"// Turek-Hron FSI channel, level {level}, depth {depth} m (make_mesh.py).",
             "scale 1;", "", "vertices", "("]
    for z in (0.0, depth):
        lines += [f"    ({points2d[name][0]:.15g} {points2d[name][1]:.15g} {z:.15g})  // {name}"
                  for name in names]
    lines += [");", "", "blocks", "("]
    edge_cells = {}
    boundary = {patch: [] for patch in PATCH_EDGES}
    patch_of = {frozenset(edge): patch for patch, edges in PATCH_EDGES.items() for edge in edges}
    for corners, cells1, cells2, grading in blocks(level):
        if signed_area([points2d[c] for c in corners]) <= 0:
            raise SystemExit(f"make_mesh.py: block {corners} is not counter-clockwise")
        ids = [front(c) for c in corners] + [back(c) for c in corners]
        lines.append(f"    hex ({' '.join(map(str, ids))}) ({cells1} {cells2} 1) "
                     f"simpleGrading ({grading:.15g} 1 1)")
        for k in range(4):
            a, b = corners[k], corners[(k + 1) % 4]
            cells = cells1 if k % 2 == 0 else cells2
            previous = edge_cells.setdefault(frozenset((a, b)), cells)
            if previous != cells:
                raise SystemExit(f"make_mesh.py: edge {a}-{b} has {previous} and {cells} cells")
            if frozenset((a, b)) in patch_of:
                # From a to b with the block on the left: the face's normal points out.
                boundary[patch_of[frozenset((a, b))]].append(
                    f"({front(a)} {front(b)} {back(b)} {back(a)})")
    lines += [");", "", "edges", "("]
    for a, b in PATCH_EDGES["cylinder"]:
        start = angle_of(points2d[a])
        turn = (angle_of(points2d[b]) - start) % 360
        middle = on_cylinder(start + 0.5 * (turn - 360 if turn > 180 else turn))
        for z, at in ((0.0, front), (depth, back)):
            lines.append(f"    arc {at(a)} {at(b)} ({middle[0]:.15g} {middle[1]:.15g} {z:.15g})")
    lines += [");", "", "boundary", "("]
    kinds = {"inlet": "patch", "outlet": "patch", "walls": "wall", "cylinder": "wall",
             "flag": "wall"}
    for patch, faces in boundary.items():
        if len(faces) != len(PATCH_EDGES[patch]):
            raise SystemExit(f"make_mesh.py: patch {patch} has {len(faces)} faces of "
                             f"{len(PATCH_EDGES[patch])}")
        lines.append(f"    {patch}\n    {{\n        type {kinds[patch]};\n        faces\n"
                     f"        (\n            " + "\n            ".join(faces) +
                     "\n        );\n    }")
    lines += [");", "", "defaultPatch { name frontAndBack; type empty; }", ""]
    return openfoam.header("dictionary", "blockMeshDict") + "\n".join(lines)


def cell_count(level):
    return sum(cells1 * cells2 for _, cells1, cells2, _ in blocks(level))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--level", type=int, default=1, help="cells per block edge x level")
    parser.add_argument("--depth", type=float, default=0.01, help="thickness in z (m)")
    parser.add_argument("--output", default="system/blockMeshDict")
    args = parser.parse_args()
    if args.level < 1:
        parser.error("--level must be 1 or more")
    with open(args.output, "w") as out:
        out.write(block_mesh_dict(args.level, args.depth))
    print(f"make_mesh.py: {args.output}: level {args.level}, {cell_count(args.level)} cells")


if __name__ == "__main__":
    main()
