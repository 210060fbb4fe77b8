#!/usr/bin/python3
"""Benchmark: ccx's sparse direct solvers on the wire drawing case's own matrices.

Runs one coupling iteration of the wire as the calculix wrapper does (cocopp_iteration.inp
restarted from the run's cocopp_converged.rout, with the last iteration's loads) once per
solver, the *STATIC card given SOLVER=<solver>, and reports per solver: ccx's wall and CPU time,
ccx's own "Total CalculiX Time", the factorizations and solves with their CPU and wall time
(scripts/calculix/06-suitesparse-solver.patch prints them when COCOPP_CCX_SOLVER_TIMES is set,
SPOOLES's too; SuiteSparse's ordering and symbolic analysis counted apart and in the
factorization total), increments and Newton iterations (.sta), and the largest difference of
the displacements from the first solver's, relative to its largest displacement. The
displacements are read in full precision from the restart file ccx writes at the end
(cocopp_iteration.rout, the record vold: the .dat and .frd files have 6 to 7 digits only).

    /usr/bin/python3 bench/ccx_solver/run.py [STRUCTURE] [--threads 1] [--repeat 1]
        [--ccx build-deps/calculix/bin/ccx] [--solvers SPOOLES SUITESPARSE] [--work DIR]

STRUCTURE is the structure folder of a wire drawing run (default:
examples/wire_drawing/results/case/structure); nothing is written into it. --threads sets
OMP_NUM_THREADS and CCX_NPROC_* (ccx's own threads, SPOOLES's among them); CHOLMOD's OpenMP and
OpenBLAS get one thread, as the calculix wrapper gives them (docs/solver-wrappers-calculix.md).
CHOLMOD spends its time in the BLAS: when the system's libblas.so.3 is not OpenBLAS but
OpenBLAS is installed (libopenblas0-pthread), ccx runs with it through LD_LIBRARY_PATH (--blas
system keeps the system's). With --repeat N each solver runs N times and the fastest run is
reported (every run's times are printed).
"""
import argparse
import os
import re
import resource
import shutil
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent.parent
sys.path.insert(0, str(ROOT / "python"))
from cocopp.calculix import ccx_environment  # noqa: E402
OPENBLAS_DIR = Path("/usr/lib/x86_64-linux-gnu/openblas-pthread")
SYSTEM_BLAS = Path("/usr/lib/x86_64-linux-gnu/libblas.so.3")
TIME_LINE = re.compile(r"cocopp solver time: (\S+) (\S+) cpu (\S+) s wall (\S+) s")


def iteration_deck(text, solver):
    """The iteration deck with SOLVER=<solver> on its *STATIC card (any SOLVER= replaced)."""
    lines = text.splitlines()
    found = False
    for i, line in enumerate(lines):
        fields = [f.strip() for f in line.split(",")]
        if fields[0].upper() == "*STATIC":
            kept = [f for f in fields[1:] if f and not f.upper().startswith("SOLVER=")]
            lines[i] = ", ".join(["*STATIC", *kept, f"SOLVER={solver}"])
            found = True
    if not found:
        raise SystemExit("run.py: the iteration deck has no *STATIC card")
    return "\n".join(lines) + "\n"


def fortran_records(path):
    """(offset, length) of each record of a Fortran unformatted sequential file."""
    data = path.read_bytes()
    records, position = [], 0
    while position < len(data):
        (length,) = struct.unpack_from("<i", data, position)
        records.append((position + 4, length))
        position += 8 + length
    return data, records


def displacements(rout, nodes):
    """The displacements (nodes x 3, rows by node id 1..nodes) in ccx's restart file: vold,
    (temperature, u1, u2, u3) per node, the first of two records of equal length (vold and
    veold, restartwrite.f) of 32 bytes per node, for at least the deck's nodes (ccx adds nodes
    of its own after them)."""
    data, records = fortran_records(rout)
    for (offset, length), (_, following) in zip(records, records[1:]):
        if length == following and length % 32 == 0 and length >= 32 * nodes:
            vold = np.frombuffer(data, dtype="<f8", count=length // 8, offset=offset)
            return vold.reshape(-1, 4)[:nodes, 1:]
    raise SystemExit(f"run.py: no displacement record found in {rout}")


def largest_node_id(deck):
    largest, in_nodes = 0, False
    for line in deck.read_text().splitlines():
        if line.startswith("*"):
            in_nodes = line.upper().replace(" ", "").startswith("*NODE,") or line.upper() == "*NODE"
            in_nodes = in_nodes and "PRINT" not in line.upper() and "FILE" not in line.upper()
            continue
        if in_nodes and line.strip() and not line.startswith("**"):
            largest = max(largest, int(line.split(",")[0]))
    return largest


def sta_counts(sta):
    """(increments, attempts, Newton iterations) of the .sta file's summary lines."""
    increments, attempts, iterations = set(), 0, 0
    for line in sta.read_text().splitlines():
        fields = line.split()
        if len(fields) >= 7 and fields[0].isdigit() and fields[1].isdigit():
            increments.add(int(fields[1]))
            attempts += 1
            iterations += int(fields[3])
    return len(increments), attempts, iterations


def run_once(structure, work, ccx, solver, threads, use_openblas):
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    for name in ("cocopp_model.inp", "cocopp_loads.inp"):
        if (structure / name).exists():
            shutil.copy(structure / name, work / name)
    shutil.copy(structure / "cocopp_converged.rout", work / "cocopp_iteration.rin")
    (work / "cocopp_iteration.inp").write_text(
        iteration_deck((structure / "cocopp_iteration.inp").read_text(), solver))
    env = dict(ccx_environment(threads), COCOPP_CCX_SOLVER_TIMES="1")
    if use_openblas:
        env["LD_LIBRARY_PATH"] = f"{OPENBLAS_DIR}:{env.get('LD_LIBRARY_PATH', '')}".rstrip(":")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    with open(work / "ccx.log", "w") as log:
        status = subprocess.run([str(ccx), "-i", "cocopp_iteration"], cwd=work, stdout=log,
                                stderr=subprocess.STDOUT, env=env).returncode
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    text = (work / "ccx.log").read_text(errors="replace")
    if status != 0 or "*ERROR" in text or "unknown solver" in text:
        tail = "\n".join(text.splitlines()[-15:])
        raise SystemExit(f"run.py: ccx with SOLVER={solver} failed (exit {status}) in {work}:\n"
                         f"{tail}")
    phases = {}
    for name, phase, cpu, phase_wall in TIME_LINE.findall(text):
        entry = phases.setdefault(phase, {"count": 0, "cpu": 0.0, "wall": 0.0, "by": set()})
        entry["count"] += 1
        entry["cpu"] += float(cpu)
        entry["wall"] += float(phase_wall)
        entry["by"].add(name)
    total = re.search(r"Total CalculiX Time:\s*(\S+)", text)
    matrices = sorted(set(re.findall(r"Factoring the system of equations using the (\S+)", text)))
    size = re.findall(r"cocopp solver matrix: (.*)", text)
    return {
        "matrices": matrices,
        "size": size[-1] if size else "",
        "wall": wall,
        "cpu": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
        "ccx_total": float(total.group(1)) if total else float("nan"),
        "phases": phases,
        "sta": sta_counts(work / "cocopp_iteration.sta"),
        "work": work,
    }


def phase(result, name, key):
    entry = result["phases"].get(name)
    return entry[key] if entry else 0.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("structure", nargs="?", type=Path,
                        default=ROOT / "examples/wire_drawing/results/case/structure")
    parser.add_argument("--ccx", type=Path, default=Path(os.environ.get(
        "COCOPP_DEPS_DIR", ROOT / "build-deps")) / "calculix/bin/ccx")
    parser.add_argument("--solvers", nargs="+", default=["SPOOLES", "SUITESPARSE"])
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--blas", choices=["openblas", "system"], default="openblas")
    parser.add_argument("--work", type=Path,
                        help="keep the runs here (default: a temporary folder)")
    args = parser.parse_args()
    structure = args.structure.resolve()
    for name in ("cocopp_iteration.inp", "cocopp_converged.rout", "cocopp_model.inp"):
        if not (structure / name).exists():
            raise SystemExit(f"run.py: {structure} has no {name} "
                             "(a wire drawing run's structure folder)")
    if not args.ccx.exists():
        raise SystemExit(f"run.py: no ccx at {args.ccx} (scripts/install-calculix.sh builds it)")

    system_blas = SYSTEM_BLAS.resolve()
    use_openblas = (args.blas == "openblas" and OPENBLAS_DIR.exists()
                    and OPENBLAS_DIR not in system_blas.parents)
    blas = OPENBLAS_DIR if use_openblas else system_blas.parent
    nodes = largest_node_id(structure / "cocopp_model.inp")
    print(f"ccx {args.ccx}\nstructure {structure} ({nodes} nodes)\n"
          f"threads {args.threads}, BLAS {blas}"
          f"{' (by LD_LIBRARY_PATH)' if use_openblas else ''}, repeat {args.repeat}, "
          f"load {os.getloadavg()[0]:.2f} at the start")

    with tempfile.TemporaryDirectory(prefix="ccx_solver_bench_") as temporary:
        work = args.work.resolve() if args.work else Path(temporary)
        best = {}
        for solver in args.solvers:
            for k in range(args.repeat):
                result = run_once(structure, work / f"{solver}-{k}", args.ccx, solver,
                                  args.threads, use_openblas)
                factor = phase(result, "analysis", "cpu") + phase(result, "factorization", "cpu")
                print(f"  {solver} run {k + 1}: wall {result['wall']:.2f} s, cpu "
                      f"{result['cpu']:.2f} s, factorization cpu {factor:.2f} s", flush=True)
                if solver not in best or result["cpu"] < best[solver]["cpu"]:
                    best[solver] = result
            best[solver]["u"] = displacements(best[solver]["work"] / "cocopp_iteration.rout", nodes)

        print()
        header = (f"{'solver':<12} {'wall s':>7} {'cpu s':>7} {'ccx s':>7} {'incs':>4} {'its':>4} "
                  f"{'factorizations':>14} {'analysis cpu':>12} {'factor cpu':>10} "
                  f"{'factor wall':>11} {'solve cpu':>9} {'solve wall':>10} "
                  f"{'max |du|/max |u|':>16}")
        print(header)
        reference = best[args.solvers[0]]["u"]
        largest = np.abs(reference).max()
        for solver in args.solvers:
            r = best[solver]
            difference = np.abs(r["u"] - reference).max() / largest
            increments, _, iterations = r["sta"]
            factor_cpu = phase(r, "analysis", "cpu") + phase(r, "factorization", "cpu")
            factor_wall = phase(r, "analysis", "wall") + phase(r, "factorization", "wall")
            print(f"{solver:<12} {r['wall']:7.2f} {r['cpu']:7.2f} {r['ccx_total']:7.2f} "
                  f"{increments:4d} {iterations:4d} {int(phase(r, 'factorization', 'count')):14d} "
                  f"{phase(r, 'analysis', 'cpu'):12.3f} {factor_cpu:10.3f} {factor_wall:11.3f} "
                  f"{phase(r, 'solve', 'cpu'):9.3f} {phase(r, 'solve', 'wall'):10.3f} "
                  f"{difference:16.2e}")
            used = sorted(set().union(*(e["by"] for e in r["phases"].values())))
            print(f"{'':<12} factored by {', '.join(used)}; matrices "
                  f"{' and '.join(r['matrices'])}; {int(phase(r, 'analysis', 'count'))} analyses")
            if r["size"]:
                print(f"{'':<12} {r['size']}")
        print(f"\nlargest displacement {largest:.6e} m ({args.solvers[0]}); the factorization "
              "columns include SuiteSparse's ordering and symbolic analysis")
        print("times on a busy machine compare by CPU; wall times with threads need an idle one. "
              "Again:\n  /usr/bin/python3 bench/ccx_solver/run.py "
              f"{structure} --ccx {args.ccx.resolve()} --threads {args.threads} "
              f"--repeat {args.repeat} --blas {args.blas} --solvers {' '.join(args.solvers)}")


if __name__ == "__main__":
    main()
