#!/usr/bin/python3
"""The wire's elastic surface compliance for the displacement drive's Newton step
(`surface_compliance` of the calculix wrapper, docs/solver-wrappers-calculix.md).

    /usr/bin/python3 examples/wire_drawing/surface_compliance.py examples/wire_drawing/results/case

Writes CASE_DIR/structure/surface_compliance.txt: for every hoop line of the sector's surface
(SURFACEALL's nodes at one axial position), the radial displacement of each line per newton of
radial force on another, the force spread over the line's nodes as a uniform traction's nodal
forces are. ccx computes it on the wire's deck made linear elastic (its *PLASTIC dropped, no
NLGEOM, no back force), for a unit force on two lines in the middle of the wire: a corner line
of the quadratic faces and the mid-side line next to it. The wire is uniform along its axis, so
every other line's column is one of the two shifted (the lines under the film are 8 mm or more
from the wire's ends, where this would not hold).

The drive then solves for each driven line's move with the structure's stiffness between the
lines (the inverse of the compliance of the driven lines, the others loaded) instead of one
stiffness per line, so that a smooth push of the wire, which it resists far less than a short
one, is corrected in one step (docs/wire-drawing.md, "Fewer coupling iterations")."""
import argparse
import pathlib
import re
import subprocess
import sys
import tempfile

import numpy as np

from cocopp.calculix import ccx_environment, dat_blocks, deck_nodes
from cocopp.executable import patched_ccx


def node_set(text, name):
    """The node ids of a deck's *NSET, NSET=name (numbers, one or more a line)."""
    match = re.search(rf"^\*NSET,\s*NSET={name}\s*$(.*?)^\*", text, re.M | re.S | re.I)
    if not match:
        sys.exit(f"surface_compliance.py: the deck has no *NSET, NSET={name}")
    return [int(v) for v in match.group(1).replace(",", " ").split()]


def hoop_lines(nodes, ids):
    """The surface's hoop lines along the axis (y): [(axial position, [nodes])], sorted."""
    lines = {}
    for node in ids:
        lines.setdefault(round(nodes[node][1], 12), []).append(node)
    return sorted(lines.items())


def line_shares(nodes, line):
    """Each node's share of a unit force on the line, as a uniform traction's nodal forces on
    quadratic (8-node) faces: a corner line's side nodes -1/2 each and its mid-hoop node 2 (the
    faces' corners take -1/12 and their mid-sides 1/3 of the area), a mid-side line's two
    nodes 1/2 each."""
    if len(line) == 2:
        return {node: 0.5 for node in line}
    if len(line) != 3:
        sys.exit(f"surface_compliance.py: a hoop line of {len(line)} nodes {line}: expected "
                 "the 2 or 3 of a sector one quadratic element thick")
    angle = {node: abs(np.arctan2(nodes[node][2], nodes[node][0])) for node in line}
    middle = sorted(line, key=lambda node: angle[node])[1]
    return {node: (2.0 if node == middle else -0.5) for node in line}


def elastic_deck(text, loaded):
    """The deck's model definition without *PLASTIC, then one linear step per loaded line
    (a unit radial force spread by line_shares), printing the surface's displacements."""
    model = text[:text.upper().index("*STEP")]
    model = re.sub(r"^\*PLASTIC.*?(?=^\*)", "", model, flags=re.M | re.S | re.I)
    steps = []
    for shares in loaded:
        steps.append("*STEP\n*STATIC\n*CLOAD, OP=NEW\n"
                     + "".join(f"{node}, 1, {share:.17g}\n" for node, share in shares.items())
                     + "*NODE PRINT, NSET=SURFACEALL, GLOBAL=YES\nU\n*END STEP\n")
    return model + "".join(steps)


def radial(nodes, rows):
    """Radial displacement per node id from *NODE PRINT rows [node, ux, uy, uz]."""
    result = {}
    for node, ux, _, uz in rows:
        x, _, z = nodes[int(node)]
        result[int(node)] = (ux * x + uz * z) / np.hypot(x, z)
    return result


def compliance(text, nodes, ccx):
    """The hoop lines, their compliance matrix, and the two computed columns with their
    lines, of the deck `text` (its nodes `nodes`), by ccx."""
    lines = hoop_lines(nodes, node_set(text, "SURFACEALL"))
    middle = len(lines) // 2
    corner = middle if len(lines[middle][1]) == 3 else middle + 1
    sources = [corner, corner + 1]
    shares = [line_shares(nodes, lines[k][1]) for k in sources]
    with tempfile.TemporaryDirectory() as work:
        work = pathlib.Path(work)
        (work / "elastic.inp").write_text(elastic_deck(text, shares))
        run = subprocess.run([str(ccx), "-i", "elastic"], cwd=work, capture_output=True,
                             text=True, env=ccx_environment(2))
        blocks = dat_blocks(work / "elastic.dat", "displacements")
        if run.returncode != 0 or len(blocks) != 2:
            sys.exit(f"surface_compliance.py: ccx failed on the elastic wire:\n{run.stdout[-2000:]}")
        responses = [radial(nodes, block) for block in blocks]
    # A line's displacement: its nodes' mean (they move alike: the load is axisymmetric).
    column = [np.array([np.mean([response[n] for n in line]) for _, line in lines])
              for response in responses]
    count = len(lines)
    matrix = np.zeros((count, count))
    for j in range(count):
        source = sources[(j - corner) % 2]
        kernel = column[(j - corner) % 2]
        for i in range(count):
            k = source + (i - j)
            if 0 <= k < count:
                matrix[i, j] = kernel[k]
    return lines, 0.5 * (matrix + matrix.T), column, sources


def uniform_pressure_check(text, nodes, lines, matrix):
    """The compliance's answer to a uniform radial pressure of 1 Pa at the middle line, against
    a long solid cylinder's u = p R (1 - nu) / E (free to stretch, so plane stress along the
    axis): its relative difference. The pressure's line forces are its uniform traction's: a
    mid-side line 2/3 of its element's area, a corner line 1/3 of one element's (1/6 of each of
    its two)."""
    young, poisson = [float(v) for v in re.search(r"^\*ELASTIC\s*\n([^\n]+)", text,
                                                  re.M | re.I).group(1).split(",")[:2]]
    first = lines[0][1][0]
    radius = np.hypot(nodes[first][0], nodes[first][2])
    angle = max(abs(np.arctan2(nodes[n][2], nodes[n][0])) for _, line in lines for n in line)
    element = 2 * (lines[1][0] - lines[0][0])  # axial length of an element (uniform)
    area = element * radius * angle
    weight = np.array([area / 3 if len(line) == 3 else 2 * area / 3 for _, line in lines])
    middle = len(lines) // 2
    expected = radius * (1 - poisson) / young
    return (matrix[middle] @ weight - expected) / expected


def write(path, lines, matrix):
    with open(path, "w") as out:
        out.write("# cocopp surface compliance (docs/solver-wrappers-calculix.md): the driven\n"
                  "# direction's displacement of each line per unit force on another, the\n"
                  "# force spread over the line's nodes as a uniform traction's (m/N).\n"
                  "# Written by examples/wire_drawing/surface_compliance.py from wire.inp.\n")
        out.write(f"lines {len(lines)}\n")
        for _, line in lines:
            out.write(" ".join(str(node) for node in line) + "\n")
        out.write(f"compliance {len(lines)}\n")
        for row in matrix:
            out.write(" ".join(f"{value:.6e}" for value in row) + "\n")


def write_checked(structure, ccx):
    """Computes the compliance of structure/wire.inp, checks it against a uniform pressure
    (exits if it misses by 1 %) and writes structure/surface_compliance.txt; returns what
    compliance() does."""
    text = (structure / "wire.inp").read_text()
    nodes = deck_nodes(text)
    lines, matrix, column, sources = compliance(text, nodes, ccx)
    check = uniform_pressure_check(text, nodes, lines, matrix)
    print(f"uniform pressure: the compliance's answer {check:+.2e} from the solid cylinder's "
          "p R (1 - nu) / E")
    if abs(check) > 1e-2:
        sys.exit("surface_compliance.py: the compliance misses a uniform pressure's answer by "
                 "more than 1 %: not written")
    write(structure / "surface_compliance.txt", lines, matrix)
    return lines, matrix, column, sources


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("case", type=pathlib.Path, help="the case directory (make_case.py's)")
    parser.add_argument("--ccx", type=pathlib.Path, default=None, help="ccx (default: patched)")
    args = parser.parse_args()
    structure = args.case / "structure"
    lines, _, column, sources = write_checked(structure, args.ccx or patched_ccx())
    pitch = lines[1][0] - lines[0][0]
    for kind, source, values in zip(("corner", "mid-side"), sources, column):
        near = values[source - 3:source + 4]
        print(f"{kind} line at y = {lines[source][0] * 1e3:.4f} mm: "
              f"{values[source]:.4e} m/N; neighbours {np.array2string(near, precision=3)}")
    print(f"{structure / 'surface_compliance.txt'}: {len(lines)} lines, pitch {pitch * 1e6:.1f} um")


if __name__ == "__main__":
    main()
