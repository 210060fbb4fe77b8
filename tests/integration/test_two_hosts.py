#!/usr/bin/python3
"""Two hosts on one machine (issue 50, docs/clusters.md), ctest `two_hosts`: two network
namespaces joined by a veth pair, the coupler in one ("host A", 10.231.50.1), the tube's
structure solver started in the other ("host B", 10.231.50.2) by its wrapper's `launcher`
(`ip netns exec B`) and coupled over `transport: tcp`:

- the tube (examples/tube/flow_structure) coupled across gives the one-machine run's results
  to the bit;
- the link cut in the middle of a run (the veth deleted): the run stops with an error naming
  the solver and the lost connection within the keepalive's 20 s, the steps done so far stay
  readable, and no solver process is left;
- the structure started by hand in host B (`started_by: user`, the way a batch script starts
  it), from the channel file the coupler writes: the same results to the bit;
- a solver that cannot reach the coupler's address: a clear error, no hang;
- with --openfoam, examples/tube/openfoam_wedge on 2 MPI ranks (case_2_ranks.yaml) with the
  fluid in host B: mpirun and its ranks there, rank 0 coupled over TCP; the one-machine run's
  results to the bit.

Needs root (network namespaces); CI runs as root.

usage: test_two_hosts.py BIN_DIR SOURCE_DIR [--openfoam]
"""
import os
import shutil
import subprocess
import sys
import tempfile
import time

import h5py

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "support"))
from network_hosts import TwoHosts  # noqa: E402
from test_install import check, same_results  # noqa: E402

def write_case(directory, source, steps, structure_keys):
    """examples/tube/flow_structure in `directory`, `steps` steps, the structure's wrapper with
    `structure_keys` (YAML lines)."""
    shutil.copytree(os.path.join(source, "examples/tube/flow_structure"), directory,
                    ignore=shutil.ignore_patterns("results"))
    path = os.path.join(directory, "case.yaml")
    text = open(path).read().replace("number_of_timesteps: 100",
                                     f"number_of_timesteps: {steps}")
    text = text.replace("    working_directory: structure\n",
                        "    working_directory: structure\n" + structure_keys)
    open(path, "w").write(text)


def in_host(host, bin_dir, directory, timeout):
    """`cocopp run` in `host`: its result and how long it took."""
    start = time.monotonic()
    result = subprocess.run(["ip", "netns", "exec", host, os.path.join(bin_dir, "cocopp"),
                             "run", os.path.join(directory, "case.yaml")],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            timeout=timeout)
    return result, time.monotonic() - start


def solvers_left(directory):
    """Processes still running in `directory` (their working directory)."""
    left = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            if os.readlink(f"/proc/{pid}/cwd").startswith(directory):
                left.append(pid)
        except OSError:
            pass
    return left


def same_datasets(reference, other, label):
    """Every dataset of the interfaces, residuals and iterations equal to the bit."""
    with h5py.File(reference, "r") as a, h5py.File(other, "r") as b:
        names = []
        a.visititems(lambda name, item: names.append(name)
                     if isinstance(item, h5py.Dataset)
                     and name.split("/")[0] in ("x", "y", "residuals", "steps") else None)
        timings = ("steps/wall_time", "steps/coupler_time", "steps/solver_times")
        differ = [name for name in names if name not in timings
                  and (name not in b or not (a[name][()] == b[name][()]).all())]
        check(names and not differ,
              f"{label}: {len(names)} datasets equal to the bit (differ: {differ[:5]})")


def wedge_across(bin_dir, source, scratch, across, host_a):
    """The OpenFOAM wedge on 2 ranks, on one machine and with the fluid in host B."""
    runs = {}
    for name, keys in (("local", ""), ("remote", across)):
        directory = os.path.join(scratch, f"wedge_{name}")
        shutil.copytree(os.path.join(source, "examples/tube/openfoam_wedge"), directory,
                        ignore=shutil.ignore_patterns("results", "processor*"))
        subprocess.run(["blockMesh"], cwd=os.path.join(directory, "fluid"), check=True,
                       stdout=subprocess.DEVNULL, env=dict(os.environ,
                                                           WM_PROJECT_DIR="/usr/share/openfoam"))
        path = os.path.join(directory, "case_2_ranks.yaml")
        text = open(path).read()
        cores_line = "    cores: 2\n"
        assert text.count(cores_line) == 1
        open(path, "w").write(text.replace(cores_line, cores_line + keys))
        command = [os.path.join(bin_dir, "cocopp"), "run", "-q", path]
        if name == "remote":
            command = ["ip", "netns", "exec", host_a] + command
        result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True)
        if result.returncode not in (0, 3):
            print(result.stdout[-3000:])
        check(result.returncode in (0, 3), f"the OpenFOAM wedge on 2 ranks, {name}")
        runs[name] = os.path.join(directory, "results/case_2_ranks.h5")
    same_datasets(runs["local"], runs["remote"], "the OpenFOAM wedge with its fluid across")


def main():
    bin_dir, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    with TwoHosts() as hosts, tempfile.TemporaryDirectory() as scratch:
        across = (f"    transport: tcp\n    host: {hosts.address_a}\n"
                  f"    launcher: [ip, netns, exec, {hosts.b}]\n")
        local = os.path.join(scratch, "local")
        write_case(local, source, 100, "")
        result = subprocess.run([os.path.join(bin_dir, "cocopp"), "run", "-q",
                                 os.path.join(local, "case.yaml")],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(result.returncode == 0, "the tube on one machine over pipes")

        remote = os.path.join(scratch, "remote")
        write_case(remote, source, 100, across)
        result, _ = in_host(hosts.a, bin_dir, remote, 120)
        if result.returncode != 0:
            print(result.stdout[-3000:])
        check(result.returncode == 0, "the tube across two hosts over TCP")
        same_results(os.path.join(local, "results/case.h5"),
                     os.path.join(remote, "results/case.h5"), "across two hosts")

        by_hand = os.path.join(scratch, "by_hand")
        write_case(by_hand, source, 100, f"    transport: tcp\n    host: {hosts.address_a}\n"
                                         "    started_by: user\n    startup_timeout: 60\n")
        coupler = subprocess.Popen(["ip", "netns", "exec", hosts.a,
                                    os.path.join(bin_dir, "cocopp"), "run", "-q",
                                    os.path.join(by_hand, "case.yaml")],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        channel_file = os.path.join(by_hand, "structure", "cocopp_channel_structure.env")
        for _ in range(600):
            if os.path.exists(channel_file) or coupler.poll() is not None:
                break
            time.sleep(0.05)
        check(os.path.exists(channel_file)
              and os.stat(channel_file).st_mode & 0o777 == 0o600,
              "started by the user: the coupler wrote the channel file, for the user only")
        solver = subprocess.run(["ip", "netns", "exec", hosts.b, "env",
                                 f"COCOPP_CHANNEL_FILE={channel_file}",
                                 os.path.join(bin_dir, "cocopp-tube-structure"),
                                 "tube_structure.yaml"],
                                cwd=os.path.join(by_hand, "structure"), stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True, timeout=120)
        output, _ = coupler.communicate(timeout=120)
        if coupler.returncode != 0 or solver.returncode != 0:
            print(output[-3000:], solver.stdout[-2000:])
        check(coupler.returncode == 0 and solver.returncode == 0
              and not os.path.exists(channel_file),
              "the structure started by hand in host B: both ended well, the file removed")
        same_results(os.path.join(local, "results/case.h5"),
                     os.path.join(by_hand, "results/case.h5"), "started by hand in host B")

        unreachable = os.path.join(scratch, "unreachable")
        write_case(unreachable, source, 10,
                   f"    transport: tcp\n    host: 127.0.0.1\n    startup_timeout: 5\n"
                   f"    launcher: [ip, netns, exec, {hosts.b}]\n")
        result, took = in_host(hosts.a, bin_dir, unreachable, 60)
        check(result.returncode != 0 and "structure" in result.stdout and took < 30,
              f"a solver that cannot reach the coupler's address: an error in {took:.1f} s\n"
              + result.stdout[-600:])

        if "--openfoam" in sys.argv:
            wedge_across(bin_dir, source, scratch, across, hosts.a)

        cut = os.path.join(scratch, "cut")
        write_case(cut, source, 10**7, across)
        text = open(os.path.join(cut, "case.yaml")).read()
        open(os.path.join(cut, "case.yaml"), "w").write(
            text.replace("results_write_interval: 1.0", "results_write_interval: 0.2"))
        run = subprocess.Popen(["ip", "netns", "exec", hosts.a, os.path.join(bin_dir, "cocopp"),
                                "run", os.path.join(cut, "case.yaml")],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        time.sleep(3)
        cut_at = time.monotonic()
        hosts.cut()
        try:
            output, _ = run.communicate(timeout=90)
        except subprocess.TimeoutExpired:
            run.kill()
            sys.exit("FAILED: the run did not stop within 90 s of the cut link")
        took = time.monotonic() - cut_at
        check(run.returncode not in (0, 3) and "structure" in output
              and ("lost" in output or "closed" in output or "timed out" in output),
              f"the link cut: the run stopped in {took:.1f} s naming the solver\n"
              + output[-800:])
        with h5py.File(os.path.join(cut, "results/case.h5"), "r") as results:
            steps = len(results["steps/iterations"])
            check(steps > 0, f"the link cut: the {steps} steps written before it are readable")
        time.sleep(1)
        check(not solvers_left(cut), "the link cut: no solver process left")


if __name__ == "__main__":
    main()
