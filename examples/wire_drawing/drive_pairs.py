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
line. 0 is a perfect model; 1 is no better than predicting nothing.

With --probe FILE (the film's own sensitivity: cocoppPimpleFoam run with
COCOPP_SENSITIVITY_PROBE, sensitivity_probe.cpp) the film's stiffness between the lines from
those finite differences is held against the pairs as well, with each model of the wire: the
film's traction change at each line per move of each film hoop line, the lines' moves carried to
the film's lines by linear interpolation along the axis. The film's axial frame is found by
matching the film's 2 p / gap with the log's."""
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


def read_probe(path):
    """The film's faces (axial position, radius, area, gap, radial and axial force) and its
    traction change per face (Pa per m) for each probed hoop line (axial positions)."""
    text = path.read_text().splitlines()
    at = next(k for k, line in enumerate(text) if line.startswith("# faces "))
    count = int(text[at].split()[2].rstrip(":"))
    faces = np.array([[float(v) for v in line.split()] for line in text[at + 1:at + 1 + count]])
    at += 1 + count
    lines = int(text[at].split()[2].rstrip(":"))
    rows = np.array([[float(v) for v in line.split()] for line in text[at + 1:at + 1 + lines]])
    return faces, rows[:, 0], rows[:, 1:1 + count] / faces[:, 2]


def film_offset(rows, faces):
    """The film's axial position of the wire's reference axial position 0: where the film's
    own 2 p / gap matches the log's per line best."""
    covered = faces[:, 3] > 0
    local = 2 * (-faces[covered, 4] / faces[covered, 2]) / faces[covered, 3]
    z_faces = faces[covered, 0]

    def misfit(offset):
        film = np.interp(rows[:, 1] + offset, z_faces, local, left=0, right=0)
        return np.linalg.norm(film - rows[:, 5])

    span = z_faces.max() - z_faces.min()
    coarse = min(np.linspace(-2 * span, 2 * span, 4001) + (z_faces.min() - rows[:, 1].min()),
                 key=misfit)
    step = 4 * span / 4000
    return min(np.linspace(coarse - step, coarse + step, 201), key=misfit)


def probed_film(rows, probe, offset):
    """The film's stiffness between the driven lines from the probe (N per m of move)."""
    faces, z_probed, traction = probe
    z = rows[:, 1] + offset
    at_lines = np.array([np.interp(z, faces[:, 0], column) for column in traction])  # (J, L)
    order = np.argsort(z)
    carried = np.zeros((len(z_probed), len(z)))  # a film line's move per move of a line
    for m in range(len(z)):
        unit = np.zeros(len(z))
        unit[m] = 1.0
        carried[:, m] = np.interp(z_probed, z[order], unit[order], left=0, right=0)
    return -rows[:, 4][:, None] * (at_lines.T @ carried)


def models(rows, row_of, compliance, surface_stiffness, probe=None, offset=0.0):
    weight, film = rows[:, 4], rows[:, 5]
    lines = [row_of[int(node)] for node in rows[:, 0]]
    wire = np.linalg.inv(compliance[np.ix_(lines, lines)])
    local = np.diag(weight * film)
    shipped = np.diag(weight * surface_stiffness)
    result = {"as it ships (2p/gap + K_s per line)": local + shipped,
              "elastic wire + 2p/gap": wire + local,
              "elastic wire alone": wire,
              "2p/gap alone": local}
    if probe is not None:
        probed = probed_film(rows, probe, offset)
        result.update({"film probed + K_s per line": probed + shipped,
                       "film probed + elastic wire": probed + wire,
                       "film probed alone": probed})
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("case", type=pathlib.Path, help="the run's case directory")
    parser.add_argument("--log", default="drive.log", help="the drive log in structure/")
    parser.add_argument("--pair", type=int, default=1,
                        help="the iteration whose pair with the next one is shown per line")
    parser.add_argument("--probe", type=pathlib.Path,
                        help="the film's sensitivity probe (COCOPP_SENSITIVITY_PROBE's file)")
    args = parser.parse_args()
    structure = args.case / "structure"
    if not (structure / args.log).exists():
        sys.exit(f"drive_pairs.py: no {structure / args.log} (run with --wire drive_log=...)")
    stiffness = float(re.search(r"surface_stiffness:\s*([0-9.e+-]+)",
                                (args.case / "case.yaml").read_text()).group(1))
    row_of, compliance = read_compliance(structure / "surface_compliance.txt")
    blocks = read_log(structure / args.log)
    probe = read_probe(args.probe) if args.probe else None

    def model_set(rows):
        return models(rows, row_of, compliance, stiffness, probe, offset)

    for step in sorted({b[0] for b in blocks}):
        its = [b for b in blocks if b[0] == step]
        errors, shown = {}, None
        # The wire slides along the film: its frame moves a step's travel each step.
        offset = film_offset(its[0][2], probe[0]) if probe is not None else 0.0
        for (_, k, a), (_, _, b) in zip(its, its[1:]):
            if a.shape != b.shape or not np.array_equal(a[:, 0], b[:, 0]):
                continue  # the driven lines changed
            dd, df = b[:, 2] - a[:, 2], b[:, 3] - a[:, 3]
            for name, k_model in model_set(a).items():
                errors.setdefault(name, []).append(np.linalg.norm(df + k_model @ dd)
                                                   / np.linalg.norm(df))
            if k == args.pair:
                shown = (a, dd, df)
        print(f"step {step}: ||dF + K dd|| / ||dF|| for the pairs of iterations 1-2, 2-3, ..."
              + (f" (the film's axial position of the wire's 0: {offset * 1e3:.4f} mm)"
                 if probe is not None else ""))
        for name, values in errors.items():
            print(f"  {name:40s} " + " ".join(f"{v:5.2f}" for v in values))
        if shown is not None:
            a, dd, df = shown
            predicted = {name: -k_model @ dd
                         for name, k_model in model_set(a).items()}
            print(f"  iterations {args.pair}-{args.pair + 1} per line: axial position (mm), "
                  "dd (nm), dF (N), then -K dd (N) of each model")
            for i in range(len(dd)):
                print(f"  {a[i, 1] * 1e3:8.3f} {dd[i] * 1e9:8.2f} {df[i]:8.4f} "
                      + " ".join(f"{p[i]:8.4f}" for p in predicted.values()))


if __name__ == "__main__":
    main()
