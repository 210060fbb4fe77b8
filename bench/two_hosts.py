#!/usr/bin/python3
"""Benchmark: what the TCP transport costs, on loopback and between two "hosts" (two network
namespaces joined by a veth pair, tests/support/network_hosts.py), against the pipes.

    sudo /usr/bin/python3 bench/two_hosts.py [--build build] [--repeat 5] [--openfoam]

1. bench_protocol_roundtrip: one SOLVE of 300 doubles and its DATA reply, over the pipes and
   TCP on loopback, then over TCP across the veth pair (the echo solver in the other host).
2. The flow-structure tube (examples/tube/flow_structure, 100 steps) as a whole process,
   --repeat times each: over the pipes; the structure over TCP on loopback; the coupler in
   host A and the structure in host B (`launcher: [ip, netns, exec, B]`). Median wall time,
   and the structure's time per coupling iteration from the run's summary (the link's cost is
   counted there: it is spent waiting for the solver).
3. With --openfoam, the same for the OpenFOAM wedge on 2 ranks (case_2_ranks.yaml), the fluid
   local or in host B.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests" / "support"))
from network_hosts import TwoHosts  # noqa: E402


def prepare(example, scratch, name, case_name, solver_line, keys):
    """A copy of `example` in scratch/name, `keys` (YAML lines) added after `solver_line`."""
    directory = Path(scratch) / name
    shutil.copytree(ROOT / example, directory, ignore=shutil.ignore_patterns("results",
                                                                          "processor*"))
    fluid = directory / "fluid"
    if (fluid / "system" / "blockMeshDict").exists():
        subprocess.run(["blockMesh"], cwd=fluid, check=True, stdout=subprocess.DEVNULL,
                       env=dict(os.environ, WM_PROJECT_DIR="/usr/share/openfoam"))
    case = directory / case_name
    text = case.read_text()
    assert text.count(solver_line) == 1, solver_line
    case.write_text(text.replace(solver_line, solver_line + keys))
    return case


def timed_run(cocopp, case, host, solver):
    """One `cocopp run`: wall time (s) and `solver`'s time per coupling iteration (ms)."""
    command = [cocopp, "run", "-q", str(case)]
    if host:
        command = ["ip", "netns", "exec", host] + command
    start = time.monotonic()
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.monotonic() - start
    if result.returncode not in (0, 3):
        sys.exit(f"{' '.join(command)} failed:\n{result.stdout[-2000:]}")
    summary = json.loads((case.parent / "results" / (case.stem + ".summary.json")).read_text())
    iterations = sum(summary["iterations_per_step"])
    return wall, 1e3 * summary["solver_times"][solver] / iterations


def compare(cocopp, variants, repeat, solver):
    for label, case, host in variants:
        runs = [timed_run(cocopp, case, host, solver) for _ in range(repeat)]
        walls, per_iteration = zip(*runs)
        print(f"  {label:<38} wall {statistics.median(walls):7.3f} s (median of {repeat}), "
              f"{solver} {statistics.median(per_iteration):8.3f} ms a coupling iteration")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--openfoam", action="store_true")
    args = parser.parse_args()
    bin_dir = Path(args.build) / "bin"
    cocopp = str(bin_dir / "cocopp")
    with TwoHosts() as hosts, tempfile.TemporaryDirectory(prefix="cocopp_bench_") as scratch:
        print("bench_protocol_roundtrip, 300 doubles, on this host:")
        subprocess.run([str(bin_dir / "bench_protocol_roundtrip"), "300", "2000"], check=True)
        print("bench_protocol_roundtrip, 300 doubles, the solver in the other host (veth):")
        subprocess.run(["ip", "netns", "exec", hosts.a, str(bin_dir / "bench_protocol_roundtrip"),
                        "300", "2000", hosts.address_a, hosts.b], check=True)

        loopback = "    transport: tcp\n"
        across = (f"    transport: tcp\n    host: {hosts.address_a}\n"
                  f"    launcher: [ip, netns, exec, {hosts.b}]\n")
        tube = "examples/tube/flow_structure"
        line = "    working_directory: structure\n"
        print("the tube, 100 steps, whole process:")
        compare(cocopp, [
            ("pipes", prepare(tube, scratch, "pipe", "case.yaml", line, ""), None),
            ("structure over tcp, loopback", prepare(tube, scratch, "tcp", "case.yaml", line,
                                                     loopback), None),
            ("structure in host B, tcp over veth", prepare(tube, scratch, "across", "case.yaml",
                                                           line, across), hosts.a),
        ], args.repeat, "structure")
        if args.openfoam:
            wedge = "examples/tube/openfoam_wedge"
            line = "    cores: 2\n"
            print("the OpenFOAM wedge on 2 ranks, 100 steps, whole process:")
            compare(cocopp, [
                ("pipes", prepare(wedge, scratch, "wedge_pipe", "case_2_ranks.yaml", line, ""),
                 None),
                ("fluid in host B, tcp over veth",
                 prepare(wedge, scratch, "wedge_across", "case_2_ranks.yaml", line, across),
                 hosts.a),
            ], max(1, args.repeat // 2), "fluid")


if __name__ == "__main__":
    main()
