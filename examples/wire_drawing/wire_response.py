#!/usr/bin/python3
"""How the wire (ccx) answers small changes of the film's load, from a run's last state.

    wire_response.py [CASE_DIR] [--scale 0.7] [--eps 1e-4] [--ccx PATH]

Runs ccx on CASE_DIR/structure's last coupling iteration deck, restarted from the last
converged step (cocopp_converged.rout, as the calculix wrapper does), with the interface loads
of the last coupling iteration (cocopp_loads.inp) scaled by scale, scale + eps, ..., scale + 4
eps, and once more at scale. Prints, for the surface nodes' radial displacement u:
- whether a repeated solve gives the same u (the coupling needs a deterministic map);
- the first differences |u(s + eps) - u(s)| (the response S per unit load scale: S eps);
- the second differences over the first: of order eps for a smooth map, of order 1 where the
  plastic state switches between the loads;
- S, and the Gauss-Seidel amplification 2 S / h it implies for a film of thickness h whose
  pressure goes as 1 / h^2 (a relative gap change dh / h changes the load by 2 dh / h): the
  number of coupling iterations a quasi-Newton method needs grows with the number of wall modes
  amplified above 1 (docs/wire-drawing.md).
Works in CASE_DIR/results/wire_response/ (one directory per load) and writes the numbers to
CASE_DIR/results/wire_response.json. ccx: the patched one scripts/install-calculix.sh built
(the restart needs it), in $COCOPP_DEPS_DIR or the checkout's build-deps/.
"""
import argparse
import json
import pathlib
import shutil

import numpy as np

from cocopp.calculix import dat_block
from cocopp.executable import patched_ccx
from wire_results import restart_ccx

HERE = pathlib.Path(__file__).resolve().parent


def scaled_loads(text, factor):
    """cocopp_loads.inp with every *DLOAD and *CLOAD value multiplied by factor."""
    out = []
    for line in text.splitlines():
        fields = [f.strip() for f in line.split(",")]
        if len(fields) == 3 and fields[0].isdigit():
            line = f"{fields[0]}, {fields[1]}, {float(fields[2]) * factor:.17g}"
        out.append(line)
    return "\n".join(out) + "\n"


def radial_displacements(dat_file):
    """The last NODE PRINT of the surface node set: u_x (the radius in CAX) of each node."""
    rows = dat_block(dat_file, "displacements")
    if not rows:
        raise SystemExit(f"wire_response.py: no displacements printed in {dat_file}")
    return np.array([row[1] for row in rows])


def solve(structure, work, factor, ccx):
    work.mkdir(parents=True, exist_ok=True)
    shutil.copy(structure / "cocopp_iteration.inp", work / "cocopp_iteration.inp")
    (work / "cocopp_loads.inp").write_text(
        scaled_loads((structure / "cocopp_loads.inp").read_text(), factor))
    status = restart_ccx(structure, work, ccx)
    if status != 0:
        raise SystemExit(f"wire_response.py: ccx failed ({status}) at load scale {factor}; "
                         f"see {work / 'ccx.log'} (a smaller --scale keeps the loads carriable)")
    return radial_displacements(work / "cocopp_iteration.dat")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", nargs="?", default=str(HERE / "results" / "case"))
    parser.add_argument("--scale", type=float, default=0.7,
                        help="load scale about which to probe (default 0.7: the last iteration's "
                             "loads of a stalled step may be more than the wire can carry)")
    parser.add_argument("--eps", type=float, default=1e-4, help="load scale increment")
    parser.add_argument("--ccx", default=str(patched_ccx()))
    args = parser.parse_args()
    structure = pathlib.Path(args.case) / "structure"
    if not (structure / "cocopp_converged.rout").exists():
        raise SystemExit(f"wire_response.py: {structure} holds no converged ccx restart "
                         "(run the case for at least one step first)")
    if not pathlib.Path(args.ccx).is_file():
        raise SystemExit(f"wire_response.py: no ccx at {args.ccx} (scripts/install-calculix.sh "
                         "builds it; --ccx names another)")
    work = pathlib.Path(args.case) / "results" / "wire_response"
    scales = [args.scale + k * args.eps for k in range(5)]
    u = [solve(structure, work / f"scale_{k}", s, args.ccx) for k, s in enumerate(scales)]
    repeat = solve(structure, work / "repeat", args.scale, args.ccx)
    first = [np.linalg.norm(u[k + 1] - u[k]) for k in range(4)]
    second = [np.linalg.norm(u[k + 2] - 2 * u[k + 1] + u[k]) / first[0] for k in range(3)]
    sensitivity = first[0] / args.eps
    print(f"loads of {structure / 'cocopp_loads.inp'} x {args.scale} + k {args.eps:g}, "
          f"{len(u[0])} surface nodes, largest |u_r| {np.abs(u[0]).max():.3e} m")
    print(f"repeated solve: largest difference {np.abs(repeat - u[0]).max():.3e} m")
    print("first differences |du|: " + ", ".join(f"{d:.3e}" for d in first) + " m")
    print("second differences / first: " + ", ".join(f"{d:.2e}" for d in second))
    print(f"S = |du| / d(scale) = {sensitivity:.3e} m per unit load scale")
    for h in (10e-6, 5e-6, 3e-6):
        print(f"  Gauss-Seidel amplification 2 S / h for a film of {h * 1e6:g} um: "
              f"{2 * sensitivity / h:.0f}")
    (work.parent / "wire_response.json").write_text(json.dumps({
        "scale": args.scale, "eps": args.eps,
        "repeat_difference": float(np.abs(repeat - u[0]).max()),
        "first_differences": first, "second_over_first": second,
        "sensitivity": sensitivity}, indent=2) + "\n")


if __name__ == "__main__":
    main()
