#!/usr/bin/python3
"""Benchmark: the flow-structure tube example (100 steps) as a whole process.

Runs `cocopp run -q` on a fresh copy of examples/tube/flow_structure several times and reports
the whole-process wall time (start-up of the coupler and both solver processes included) and,
from the run summary, the coupler's own time per coupling iteration (time inside the time steps
not spent waiting for a solver: the coupling algorithm, predictor, convergence checks and data
copies; results I/O and start-up excluded) next to the total coupler time per iteration.

    /usr/bin/python3 bench/tube_run.py [--build build] [--repeat 10] [--case case.yaml]
        [--example examples/tube/flow_ringmodel] [--coupled-solver "{type: ibqn, ...}"]

Runs the cocopp of --build's bin/, by default the one the package cocopp finds
(cocopp.executable: $COCOPP_BIN_DIR, the checkout's build, or PATH).

--coupled-solver replaces the case's coupled solver (YAML, its predictor and convergence
criterion kept unless given), so that every coupled solver is timed on the same case.

--instructions also runs the coupler once under valgrind's callgrind (Debian's valgrind) and
reports the instructions it executes per coupling iteration in its time steps, outside the
calls into its solver wrappers: the work behind "coupler time per iteration", counted without
the noise of a shared machine, so that two builds compare on one run each.
"""
import argparse
import contextlib
import re
import shutil
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import yaml

from cocopp.case import read as read_case, write as write_case
from cocopp.executable import find_cocopp
from cocopp.results import read_summary, results_path

ROOT = Path(__file__).resolve().parent.parent


def replace_coupled_solver(case_file, coupled_solver):
    """The case with its coupled solver replaced, keeping predictor and criterion if not given."""
    case = read_case(case_file)
    replacement = yaml.safe_load(coupled_solver)
    for kept in ("predictor", "convergence_criterion"):
        replacement.setdefault(kept, case["coupled_solver"][kept])
    case["coupled_solver"] = replacement
    write_case(case_file, case)


@contextlib.contextmanager
def fresh_case(example, case, coupled_solver):
    """A temporary copy of the example (without earlier results), its coupled solver replaced
    if one is given; yields the copy's directory."""
    with tempfile.TemporaryDirectory(prefix="cocopp_bench_") as tmp:
        work = Path(tmp) / "case"
        shutil.copytree(example, work, ignore=shutil.ignore_patterns("results", "*.log", "output"))
        if coupled_solver:
            replace_coupled_solver(work / case, coupled_solver)
        yield work


def run_summary(work, case):
    return read_summary(results_path(work / case))


def run_once(cocopp, example, case, coupled_solver):
    with fresh_case(example, case, coupled_solver) as work:
        start = time.perf_counter()
        subprocess.run([str(cocopp), "run", "-q", str(work / case)], check=True,
                       stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - start
        return wall, run_summary(work, case)


# The calls of a time step that are the solvers' time (the coupler's timed() calls), for solvers
# that are process wrappers without mapping, as the tube's. A mapped or CalculiX wrapper calls
# these from its own, whose time (the mapping's too) the coupler counts as the solver's.
SOLVER_CALLS = re.compile(r"cocopp::ProcessSolverWrapper::(solve|initialize_step|finalize_step|"
                          r"output_step|complete_step_requests)\(")
OTHER_WRAPPERS = re.compile(r"cocopp::.*(MappedSolverWrapper|CalculixSolverWrapper)::")


def coupler_instructions(cocopp, example, case, coupled_solver):
    """Instructions per coupling iteration in CoupledSolver::solve_step outside solver calls."""
    if not shutil.which("valgrind"):
        raise SystemExit("--instructions needs valgrind (apt-get install valgrind)")
    with fresh_case(example, case, coupled_solver) as work:
        profile = work.parent / "callgrind.out"
        subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={profile}",
                        str(cocopp), "run", "-q", str(work / case)], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        summary = run_summary(work, case)
        listing = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100",
                                  str(profile)], check=True, capture_output=True, text=True).stdout
    step, solvers = None, 0
    for line in listing.splitlines():
        match = re.match(r"\s*([\d,]+) \(.*?\)\s+\S*?:(.*)", line)
        if not match:
            continue
        count, function = int(match.group(1).replace(",", "")), match.group(2)
        if other := OTHER_WRAPPERS.match(function):
            raise SystemExit("--instructions counts cases whose solvers are process wrappers "
                             f"without mapping; this one has a {other.group(1)}")
        if function.startswith("cocopp::CoupledSolver::solve_step("):
            step = count
        elif SOLVER_CALLS.match(function):
            solvers += count
    if step is None or solvers == 0:
        raise SystemExit("callgrind's listing has no CoupledSolver::solve_step or no call of a "
                         "ProcessSolverWrapper in it")
    return (step - solvers) / sum(summary["iterations_per_step"])


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", help="build directory (default: the cocopp cocopp.executable "
                                         "finds)")
    parser.add_argument("--repeat", type=int, default=10, help="number of runs")
    parser.add_argument("--example", default=str(ROOT / "examples/tube/flow_structure"))
    parser.add_argument("--case", default="case.yaml", help="case file inside the example")
    parser.add_argument("--coupled-solver", help="the coupled solver to use instead (YAML)")
    parser.add_argument("--instructions", action="store_true",
                        help="also count the coupler's instructions per iteration (callgrind)")
    args = parser.parse_args()

    cocopp = Path(args.build) / "bin" / "cocopp" if args.build else find_cocopp()
    run_once(cocopp, args.example, args.case, args.coupled_solver)  # warm the file cache
    walls, step_coupler, coupler, iterations = [], [], [], None
    for _ in range(args.repeat):
        wall, summary = run_once(cocopp, args.example, args.case, args.coupled_solver)
        walls.append(wall)
        step_coupler.append(summary["step_coupler_time_per_iteration"])
        coupler.append(summary["coupler_time_per_iteration"])
        iterations = sum(summary["iterations_per_step"])
        solver_times = summary["solver_times"]

    solver = f", coupled solver {args.coupled_solver}" if args.coupled_solver else ""
    print(f"case: {args.example}/{args.case}{solver}, {args.repeat} runs, "
          f"{iterations} coupling iterations per run")
    print(f"whole process wall time    : median {statistics.median(walls) * 1e3:8.1f} ms  "
          f"(min {min(walls) * 1e3:.1f}, max {max(walls) * 1e3:.1f})")
    print(f"coupler time per iteration : median {statistics.median(step_coupler) * 1e6:8.1f} us  "
          f"(inside the time steps)")
    print(f"  incl. start-up and I/O   : median {statistics.median(coupler) * 1e6:8.1f} us")
    print("solver time (last run)     : " +
          ", ".join(f"{name} {t * 1e3:.1f} ms" for name, t in solver_times.items()))
    if args.instructions:
        count = coupler_instructions(cocopp, args.example, args.case, args.coupled_solver)
        print(f"coupler instructions per iteration (callgrind, inside the time steps, outside "
              f"solver calls): {count / 1e3:.1f} k")


if __name__ == "__main__":
    main()
