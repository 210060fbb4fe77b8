#!/usr/bin/python3
"""Can ccx take the wire's step driven by displacement where it fails driven by load? A probe.

    displacement_probe.py [CASE_DIR] [--squeeze 0.55e-6 2e-6 5e-6] [--ccx PATH]

From a run's last converged state (CASE_DIR/structure/cocopp_converged.rout, as the calculix
wrapper restarts), solves the next step of the wire with the last coupling iteration's loads
(cocopp_loads.inp) except on the faces under the film (those with a pressure): there the
nodes' radial displacement is prescribed instead (*BOUNDARY), at their value after the last
converged step (its step_NNNNN.dat) minus `squeeze` (an inward move, in m). Prints, for each
squeeze, whether ccx converged, its increments and Newton iterations in the step, its time and
the summed radial reaction force on the prescribed nodes (ccx's units). This is the structure's
half of a displacement-driven coupling (docs/wire-drawing.md, "What would help"); a run whose
last step failed because ccx could not carry the film's loads is the interesting input.
Works in CASE_DIR/results/displacement_probe/ (one directory per squeeze) and writes the table
to CASE_DIR/results/displacement_probe.json. ccx: the patched one scripts/install-calculix.sh
built, in $COCOPP_DEPS_DIR or the checkout's build-deps/.
"""
import argparse
import json
import pathlib
import re
import time

from cocopp.calculix import dat_block, deck_elements
from cocopp.executable import patched_ccx
from wire_results import applied_loads, restart_ccx

HERE = pathlib.Path(__file__).resolve().parent
PRESSURE = re.compile(r"^(\d+), P2, (\S+)$")


def last_step_displacements(structure):
    """Radial displacement of the surface nodes after the last converged step."""
    dats = sorted((structure / "results").glob("step_*.dat"))
    if not dats:
        raise SystemExit(f"displacement_probe.py: no step_*.dat in {structure / 'results'}")
    rows = dat_block(dats[-1], "displacements")
    return {int(row[0]): row[1] for row in rows}, dats[-1].name


def deck(structure, prescribed, under_film):
    """The last iteration's deck with the loads under the film replaced by displacements."""
    head = (structure / "cocopp_iteration.inp").read_text().split("*INCLUDE")[0]
    lines = [head.rstrip("\n"), "*BOUNDARY"]
    lines += [f"{node}, 1, 1, {value:.12e}" for node, value in sorted(prescribed.items())]
    for line in (structure / "cocopp_loads.inp").read_text().splitlines():
        m = PRESSURE.match(line.strip())
        if not (m and int(m.group(1)) in under_film):
            lines.append(line)
    lines += ["*NODE PRINT, NSET=SURFACEN, GLOBAL=YES", "U",
              "*NODE PRINT, NSET=SURFACEN, TOTALS=NO", "RF", "*END STEP"]
    return "\n".join(lines) + "\n"


def increments(sta):
    """(increments, attempts cut back, Newton iterations) of the step in ccx's .sta file: an
    attempt whose ATT column ends in U did not converge and was retried with a smaller one."""
    rows = [line.split() for line in sta.read_text().splitlines()]
    rows = [r for r in rows if len(r) >= 7 and r[0].isdigit()]
    cut_back = sum(1 for r in rows if r[2].endswith("U"))
    return len(rows) - cut_back, cut_back, sum(int(r[3]) for r in rows)


def probe(structure, work, text, prescribed, ccx):
    work.mkdir(parents=True, exist_ok=True)
    (work / "cocopp_iteration.inp").write_text(text)
    start = time.perf_counter()
    status = restart_ccx(structure, work, ccx)
    seconds = time.perf_counter() - start
    forces = dat_block(work / "cocopp_iteration.dat", "forces") if status == 0 else None
    converged = status == 0 and forces is not None
    count, cut_back, newton = (increments(work / "cocopp_iteration.sta") if converged
                               else (0, 0, 0))
    reaction = sum(row[1] for row in forces if int(row[0]) in prescribed) if converged else None
    return {"converged": converged, "increments": count, "cut_back": cut_back,
            "newton_iterations": newton, "seconds": round(seconds, 2),
            "radial_reaction": reaction}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", nargs="?", default=str(HERE / "results" / "case"))
    parser.add_argument("--squeeze", type=float, nargs="+", default=[0.55e-6, 2e-6, 5e-6],
                        help="inward radial moves of the nodes under the film, m (default: "
                             "the die's closing per step, then 4 and 9 times that)")
    parser.add_argument("--ccx", default=str(patched_ccx()))
    args = parser.parse_args()
    structure = pathlib.Path(args.case) / "structure"
    for needed in ("cocopp_converged.rout", "cocopp_iteration.inp", "cocopp_loads.inp"):
        if not (structure / needed).exists():
            raise SystemExit(f"displacement_probe.py: {structure} holds no {needed} (run the "
                             "case for at least one step first)")
    if not pathlib.Path(args.ccx).is_file():
        raise SystemExit(f"displacement_probe.py: no ccx at {args.ccx} "
                         "(scripts/install-calculix.sh builds it; --ccx names another)")
    connectivity = deck_elements((structure / "wire.inp").read_text())
    pressures, _ = applied_loads(structure / "cocopp_loads.inp")
    under_film = {element for element, p in pressures.items() if p != 0.0}
    displacement, source = last_step_displacements(structure)
    # Face 2 of a CAX8 element: corner nodes 2 and 3 and the midside node 6.
    nodes = sorted({n for e in under_film for n in (connectivity[e][1], connectivity[e][2],
                                                    connectivity[e][5]) if n in displacement})
    print(f"{len(under_film)} faces under the film, {len(nodes)} nodes prescribed from {source}")
    results = []
    work = pathlib.Path(args.case) / "results" / "displacement_probe"
    for k, squeeze in enumerate(args.squeeze):
        prescribed = {n: displacement[n] - squeeze for n in nodes}
        outcome = probe(structure, work / f"squeeze_{k}", deck(structure, prescribed, under_film),
                        prescribed, args.ccx)
        results.append({"squeeze": squeeze, **outcome})
        reaction = outcome["radial_reaction"]
        print(f"squeeze {squeeze:.3g} m: " + (
            f"converged, {outcome['increments']} increments ({outcome['cut_back']} cut back), "
            f"{outcome['newton_iterations']} Newton iterations, {outcome['seconds']} s, "
            f"radial reaction {reaction:.4g}"
            if outcome["converged"] else f"ccx failed after {outcome['seconds']} s "
            f"(see {work / f'squeeze_{k}' / 'ccx.log'})"))
    (work.parent / "displacement_probe.json").write_text(json.dumps(results, indent=2) + "\n")


if __name__ == "__main__":
    main()
