#!/usr/bin/python3
"""Are ccx's reaction forces at prescribed surface nodes the loads they stand for? A probe.

    reaction_probe.py [--ccx PATH]

A displacement-driven coupling of the wire (docs/design/displacement-driven-wire.md) needs,
at every node whose displacement it prescribes, the force the structure takes there (ccx's
RF), to balance it against the film's. This probe checks that on the tube wall's two decks
(examples/tube/flow_calculix/structure: the axisymmetric CAX8 ring and the 1-degree C3D20
sector of the same wall): solve with a uniform pressure on the inner surface, then prescribe
the radial displacement of that solution on the inner surface's nodes (the pressure still
applied: RF is the force the structure takes at a node, whatever is applied there) and compare each node's RF with the consistent
nodal force of the pressure (the integral of its shape function over the faces; 2 degrees of
the ring for the axisymmetric model, whose reactions ccx prints for the 2-degree wedge it
expands the model into). Prints per model the largest deviation and the total, whether a
*CLOAD on a prescribed direction enters its RF, and whether
*BOUNDARY, OP=NEW in a later step also removes the model definition's boundaries (a driven
node set that changes from step to step needs OP=NEW to release nodes). Exits with 1 if the
3D sector's RF is not the consistent force within 0.1 %, what the plan builds on. Writes
results/reaction_probe/ (the decks and ccx's output). ccx: the patched one
scripts/install-calculix.sh built, in $COCOPP_DEPS_DIR or the checkout's build-deps/, else
the ccx on PATH (Debian's; the probe needs no restart, so either will do).
"""
import argparse
import math
import pathlib
import re
import subprocess

from cocopp import calculix
from cocopp.executable import patched_ccx

HERE = pathlib.Path(__file__).resolve().parent
WALL = HERE.parents[0] / "tube" / "flow_calculix" / "structure"
PRESSURE = 1.0e5
# Face -> (corner, midside) local node numbers (ccx's numbering) and their weights in units
# of the face's area: a quadratic edge (CAX8, face S4 = nodes 4-1, midside 8) and a
# serendipity quad (C3D20, face S6 = nodes 4-8-5-1, midsides 20, 16, 17, 12).
FACES = {"CAX8": ("S4", {4: 1 / 6, 1: 1 / 6, 8: 2 / 3}),
         "C3D20": ("S6", {4: -1 / 12, 8: -1 / 12, 5: -1 / 12, 1: -1 / 12,
                          20: 1 / 3, 16: 1 / 3, 17: 1 / 3, 12: 1 / 3})}


def node_block(path, title):
    """{node: first value} of the last *NODE PRINT block whose header starts with `title`."""
    return {int(row[0]): row[1] for row in calculix.dat_block(path, title)}


def run(ccx, work, job, text):
    (work / f"{job}.inp").write_text(text)
    with open(work / f"{job}.log", "w") as log:
        subprocess.run([ccx, "-i", job], cwd=work, stdout=log, stderr=subprocess.STDOUT,
                       check=True)


def probe(ccx, deck, element, work):
    text = (WALL / deck).read_text()
    model = text.split("*STEP")[0]
    nodes = calculix.deck_nodes(text)
    radius = lambda n: math.hypot(nodes[n][0], nodes[n][2] if element == "CAX8" else nodes[n][1])
    face, weights = FACES[element]
    # The consistent nodal force of the pressure on the inner faces (r is constant there).
    expected = {}
    for ids in calculix.deck_elements(text).values():
        corners = [ids[k - 1] for k in weights if k <= 8]
        width = max(abs(nodes[a][1 if element == "CAX8" else 2] - nodes[b][1 if element ==
                    "CAX8" else 2]) for a in corners for b in corners)
        r = radius(ids[list(weights)[0] - 1])
        area = width * r * (math.pi / 90 if element == "CAX8" else math.pi / 180)
        for k, w in weights.items():
            expected[ids[k - 1]] = expected.get(ids[k - 1], 0.0) + w * area * PRESSURE
    ends = {int(v) for v in re.findall(r"\d+", text.split("NSET=ENDS")[1].split("*")[0])}
    inner = sorted(n for n in expected if n not in ends)
    nset = "*NSET, NSET=INNER\n" + "".join(f"{n},\n" for n in inner)
    load = f"*DLOAD\nEALL, P{face[1]}, {PRESSURE}\n"
    run(ccx, work, "loaded", model + nset + "*STEP\n*STATIC\n" + load +
        "*NODE PRINT, NSET=INNER\nU\n*END STEP\n")
    u = node_block(work / "loaded.dat", "displacements")
    prescribed = "*BOUNDARY\n" + "".join(f"{n}, 1, 1, {u[n]:.12e}\n" for n in inner)
    run(ccx, work, "driven", model + nset + "*STEP\n*STATIC\n" + prescribed + load +
        "*NODE PRINT, NSET=INNER\nRF\n*END STEP\n")
    rf = node_block(work / "driven.dat", "forces")
    # The same with a force on the first node's prescribed direction: does RF change?
    extra = f"*CLOAD\n{inner[0]}, 1, {expected[inner[0]]:.12e}\n"
    run(ccx, work, "driven_cload", model + nset + "*STEP\n*STATIC\n" + prescribed + load + extra +
        "*NODE PRINT, NSET=INNER\nRF\n*END STEP\n")
    cload_changes_rf = abs(node_block(work / "driven_cload.dat", "forces")[inner[0]] -
                           rf[inner[0]]) > 1e-6 * abs(rf[inner[0]])
    deviation = max(abs(rf[n] / expected[n] - 1) for n in inner)
    total = sum(rf[n] for n in inner) / sum(expected[n] for n in inner) - 1
    return len(inner), deviation, total, cload_changes_rf


def op_new_drops_model_boundaries(ccx, work):
    """Whether *BOUNDARY, OP=NEW in a later step also removes the model definition's
    *BOUNDARY (the wall's clamped ends): then an end node moves in the second step."""
    text = (WALL / "wall_cax.inp").read_text()
    ends = [int(v) for v in re.findall(r"\d+", text.split("NSET=ENDS")[1].split("*")[0])]
    inner = sorted(n for n, xyz in calculix.deck_nodes(text).items()
                   if abs(xyz[0] - 0.005) < 1e-12)
    free = [n for n in inner if n not in ends]
    step = "*STEP\n*STATIC\n*BOUNDARY{}\n{}, 1, 1, 1e-6\n*NODE PRINT, NSET=ENDS\nU\n*END STEP\n"
    run(ccx, work, "op_new", text.split("*STEP")[0] + step.format("", free[0]) +
        step.format(", OP=NEW", free[1]))
    return max(abs(v) for v in node_block(work / "op_new.dat", "displacements").values()) > 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    patched = patched_ccx()
    parser.add_argument("--ccx", default=str(patched) if patched.is_file() else "ccx")
    args = parser.parse_args()
    exact = True
    for deck, element in (("wall_cax.inp", "CAX8"), ("wall.inp", "C3D20")):
        work = HERE / "results" / "reaction_probe" / element
        work.mkdir(parents=True, exist_ok=True)
        count, deviation, total, cload_changes_rf = probe(args.ccx, deck, element, work)
        print(f"{element:6s} ({deck}): {count} prescribed nodes; RF against the consistent nodal "
              f"force: largest deviation {100 * deviation:.3g} %, total {100 * total:+.3g} %; "
              f"a *CLOAD on a prescribed direction {'changes' if cload_changes_rf else 'leaves'} "
              "its RF")
        if element == "C3D20":
            exact = deviation < 1e-3 and not cload_changes_rf
    moved = op_new_drops_model_boundaries(args.ccx, HERE / "results" / "reaction_probe" / "CAX8")
    print("*BOUNDARY, OP=NEW in a later step " +
          ("also removes" if moved else "keeps") + " the model definition's *BOUNDARY")
    if not exact:  # what docs/design/displacement-driven-wire.md builds on
        raise SystemExit("reaction_probe.py: the 3D sector's RF is not the consistent nodal force "
                         "within 0.1 %, or a *CLOAD enters it: the plan's force balance fails")


if __name__ == "__main__":
    main()
