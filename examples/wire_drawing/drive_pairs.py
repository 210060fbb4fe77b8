#!/usr/bin/python3
"""How well models of the interface's Jacobian predict what the coupled wire and film did: the
secant pairs of the displacement drive's lines (docs/wire-drawing.md, "Fewer coupling
iterations").

    /usr/bin/python3 examples/wire_drawing/drive_pairs.py examples/wire_drawing/results/from65_log

The run's wire must have logged its drive (`rewind.py ... --wire drive_log=drive.log`, the
calculix wrapper's `drive_log`) and have its surface compliance (`--compliance`). Between two
coupling iterations of a step with the same driven lines, the lines moved by dd and their
imbalance (the film's force minus the wire's reaction) changed by dF; a model K of the
stiffness predicts dF = -K dd. Printed per pair: ||dF + K dd|| / ||dF|| for
- the drive as it ships: per line, its area times (2 p / gap + surface_stiffness);
- the wire's elastic compliance between the lines (the others loaded) plus 2 p / gap per line;
- each alone;
and, for the pair --pair (default the step's first), dd, dF and what each model predicts per
line. 0 is a perfect model; 1 is no better than predicting nothing."""
import argparse
import pathlib
import re
import sys

import numpy as np


def read_log(path):
    """[(step, iteration, rows)] of the drive log; rows: node, axial, prescribed, force,
    weight, film stiffness, move."""
    blocks, rows = [], None
    for line in path.read_text().splitlines():
        header = re.match(r"# step (\d+) iteration (\d+)", line)
        if header:
            rows = []
            blocks.append((int(header.group(1)), int(header.group(2)), rows))
        elif line.strip():
            rows.append([float(v) for v in line.split()])
    return [(step, iteration, np.array(rows)) for step, iteration, rows in blocks]


def read_compliance(path):
    """{node: row} and the matrix of a surface compliance file."""
    text = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    count = int(text[0].split()[1])
    row_of = {int(node): row for row, line in enumerate(text[1:1 + count])
              for node in line.split()}
    matrix = np.array([[float(v) for v in line.split()]
                       for line in text[2 + count:2 + 2 * count]])
    return row_of, matrix


def models(rows, row_of, compliance, surface_stiffness):
    weight, film = rows[:, 4], rows[:, 5]
    lines = [row_of[int(node)] for node in rows[:, 0]]
    wire = np.linalg.inv(compliance[np.ix_(lines, lines)])
    local = np.diag(weight * film)
    return {"as it ships (2p/gap + K_s per line)": local + np.diag(weight * surface_stiffness),
            "elastic wire + 2p/gap": wire + local,
            "elastic wire alone": wire,
            "2p/gap alone": local}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("case", type=pathlib.Path, help="the run's case directory")
    parser.add_argument("--log", default="drive.log", help="the drive log in structure/")
    parser.add_argument("--pair", type=int, default=1,
                        help="the iteration whose pair with the next one is shown per line")
    args = parser.parse_args()
    structure = args.case / "structure"
    if not (structure / args.log).exists():
        sys.exit(f"drive_pairs.py: no {structure / args.log} (run with --wire drive_log=...)")
    stiffness = float(re.search(r"surface_stiffness:\s*([0-9.e+-]+)",
                                (args.case / "case.yaml").read_text()).group(1))
    row_of, compliance = read_compliance(structure / "surface_compliance.txt")
    blocks = read_log(structure / args.log)
    for step in sorted({b[0] for b in blocks}):
        its = [b for b in blocks if b[0] == step]
        errors, shown = {}, None
        for (_, k, a), (_, _, b) in zip(its, its[1:]):
            if a.shape != b.shape or not np.array_equal(a[:, 0], b[:, 0]):
                continue  # the driven lines changed
            dd, df = b[:, 2] - a[:, 2], b[:, 3] - a[:, 3]
            for name, k_model in models(a, row_of, compliance, stiffness).items():
                errors.setdefault(name, []).append(np.linalg.norm(df + k_model @ dd)
                                                   / np.linalg.norm(df))
            if k == args.pair:
                shown = (a, dd, df)
        print(f"step {step}: ||dF + K dd|| / ||dF|| for the pairs of iterations 1-2, 2-3, ...")
        for name, values in errors.items():
            print(f"  {name:38s} " + " ".join(f"{v:5.2f}" for v in values))
        if shown is not None:
            a, dd, df = shown
            predicted = {name: -k_model @ dd
                         for name, k_model in models(a, row_of, compliance, stiffness).items()}
            print(f"  iterations {args.pair}-{args.pair + 1} per line: axial position (mm), "
                  "dd (nm), dF (N), then -K dd (N) of the four models")
            for i in range(len(dd)):
                print(f"  {a[i, 1] * 1e3:8.3f} {dd[i] * 1e9:8.2f} {df[i]:8.4f} "
                      + " ".join(f"{p[i]:8.4f}" for p in predicted.values()))


if __name__ == "__main__":
    main()
