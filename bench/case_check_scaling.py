#!/usr/bin/env python3
"""`cocopp check` time against the length of a list in the case file (issue 17, defect 9:
80k list entries took 22 s, quadratic). Writes cases with n convergence criteria under
bench/results/case_check_scaling/ and prints the time of `cocopp check` for each n and the
ratio to the previous n (2 for linear time, 4 for quadratic).

  /usr/bin/python3 bench/case_check_scaling.py [--cocopp build/bin/cocopp]

--cocopp defaults to the one the package cocopp finds (cocopp.executable).
"""
import argparse
import pathlib
import shutil
import subprocess
import time

from cocopp import case as case_files
from cocopp.executable import find_cocopp

ROOT = pathlib.Path(__file__).resolve().parent.parent


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cocopp", help="the cocopp to time (default: cocopp.executable's)")
    parser.add_argument("--sizes", type=int, nargs="+", default=[10000, 20000, 40000, 80000])
    args = parser.parse_args()
    cocopp = args.cocopp or find_cocopp()
    out = ROOT / "bench" / "results" / "case_check_scaling"
    shutil.rmtree(out, ignore_errors=True)
    shutil.copytree(ROOT / "examples" / "tube" / "flow_structure", out,
                    ignore=shutil.ignore_patterns("results"))
    original = case_files.read(out / "case.yaml")
    criteria = original["coupled_solver"]["convergence_criterion"]["criteria"]
    previous = None
    print(f"{'entries':>8} {'check time':>11} {'ratio':>6}")
    for n in args.sizes:
        limits = [case_files.flow({"type": "iteration_limit", "maximum": i + 20})
                  for i in range(n)]
        original["coupled_solver"]["convergence_criterion"]["criteria"] = limits + criteria
        case = out / f"case_{n}.yaml"
        case_files.write(case, original)
        start = time.perf_counter()
        subprocess.run([cocopp, "check", str(case)], check=True, stdout=subprocess.DEVNULL)
        elapsed = time.perf_counter() - start
        ratio = f"{elapsed / previous:6.2f}" if previous else ""
        print(f"{n:>8} {elapsed:>9.2f} s {ratio:>6}")
        previous = elapsed


if __name__ == "__main__":
    main()
