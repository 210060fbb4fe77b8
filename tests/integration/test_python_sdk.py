#!/usr/bin/python3
"""The Python solver SDK (solvers/sdk/cocopp_sdk.py) against the coupler, ctest
`python_sdk`: examples/external_solver/ring_wall.py coupled to the built-in tube flow over the
pipe, file and tcp transports (the built-in ring model's results to the bit), solver-coupling
convergence reported by the solver (and refused by one that cannot), and what goes wrong on
the solver's side
reaching the user as the C++ SDK sends it: a rejected input, a wrong output size, an
exception, a start outside cocopp, --help. Substeps: the SDK drives a window of two substeps
as the C++ SDK does (the built-in ring model's results to the bit), and a solver that cannot
take substeps says so.

usage: test_python_sdk.py BIN_DIR SOURCE_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_install import check, same_results  # noqa: E402

# Solvers that go wrong, each a ring_wall.RingWall with one method changed.
FAULTS = {
    "wrong_size": """
    def solve(self, values):
        return super().solve(values)[:3]
""",
    "exception": """
    def initialize_step(self, step, time):
        if step == 2:
            raise RuntimeError("the wall cracked in step 2")
""",
    "converges_at_third": """
    def initialize_step(self, step, time):
        self.iteration = 0
    def solve(self, values):
        self.iteration += 1
        return super().solve(values)
    def start_reporting_convergence(self):
        pass
    def converged_at_first_iteration(self):
        return self.iteration == 3
""",
    "cannot_substep": """
    def can_substep(self):
        return False
""",
    "rejects_once": """
    rejected = False
    def solve(self, values):
        if self.step == 3 and not RingWall.rejected:
            RingWall.rejected = True
            raise sdk.InputRejected("this pressure would burst the wall")
        return super().solve(values)
    def initialize_step(self, step, time):
        self.step = step
""",
}


def cocopp_run(bin_dir, case_directory, case_file, env):
    return subprocess.run([os.path.join(bin_dir, "cocopp"), "run", case_file],
                          cwd=case_directory, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)


SOLVER_CONVERGENCE = """      - type: solver_coupling_convergence
        solver_index: 1
"""


def write_case(directory, name, command, transport="pipe", steps=100, solver_convergence=False,
               substeps=1):
    with open(os.path.join(directory, "case.yaml")) as original:
        text = original.read()
    if solver_convergence:  # the wall's report instead of the residual
        relative = "      - type: relative_norm\n        tolerance: 1.0e-6\n"
        check(relative in text, "case.yaml has the relative_norm criterion to replace")
        text = text.replace(relative, SOLVER_CONVERGENCE)
    if substeps > 1:  # with a window of two, one step of the 100 stalls at 2.4e-6
        text = text.replace("tolerance: 1.0e-6", "tolerance: 1.0e-5")
    text = text.replace("../build/ring-wall", command).replace("number_of_timesteps: 100",
                                                               f"number_of_timesteps: {steps}")
    text = text.replace("    working_directory: structure\n",
                        f"    working_directory: structure\n    transport: {transport}\n" +
                        (f"    substeps: {substeps}\n" if substeps > 1 else ""))
    with open(os.path.join(directory, name), "w") as case:
        case.write(text)


def started_by_user(bin_dir, project, env, reference_h5):
    """ring_wall.py started by hand (started_by: user) from the channel file the coupler
    writes: the built-in ring model's results to the bit."""
    with open(os.path.join(project, "tcp.yaml")) as tcp:
        text = tcp.read()
    command = ("    command: [python3, ../ring_wall.py, length=0.05, diameter=0.01, cells=100, "
               "rho_f=1000, e=3.0e5,\n              h=1.0e-3]\n")
    check(command in text, "the case's wall command, to replace")
    with open(os.path.join(project, "by_hand.yaml"), "w") as case:
        case.write(text.replace(command, "    started_by: user\n"))
    coupler = subprocess.Popen([os.path.join(bin_dir, "cocopp"), "run", "by_hand.yaml"],
                               cwd=project, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
    channel_file = os.path.join(project, "structure", "cocopp_channel_wall.env")
    for _ in range(600):
        if os.path.exists(channel_file) or coupler.poll() is not None:
            break
        time.sleep(0.05)
    solver_env = {key: value for key, value in env.items() if not key.startswith("COCOPP_")}
    solver_env["COCOPP_CHANNEL_FILE"] = channel_file
    solver = subprocess.run(["python3", "../ring_wall.py", "length=0.05", "diameter=0.01",
                             "cells=100", "rho_f=1000", "e=3.0e5", "h=1.0e-3"],
                            cwd=os.path.join(project, "structure"), env=solver_env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            timeout=120)
    output, _ = coupler.communicate(timeout=120)
    if coupler.returncode != 0 or solver.returncode != 0:
        print(output[-2000:], solver.stdout[-2000:])
    check(coupler.returncode == 0 and solver.returncode == 0,
          "ring_wall.py started by the user connects through COCOPP_CHANNEL_FILE")
    same_results(reference_h5, os.path.join(project, "results", "by_hand.h5"),
                 "ring_wall.py started by the user")


def main():
    bin_dir, source = sys.argv[1], sys.argv[2]
    env = dict(os.environ, COCOPP_BIN_DIR=bin_dir,
               PYTHONPATH=os.path.join(source, "solvers", "sdk"),
               PATH=f"/usr/bin:{os.environ.get('PATH', '')}")
    with tempfile.TemporaryDirectory(prefix="cocopp-python-sdk-") as scratch:
        reference = os.path.join(scratch, "flow_ringmodel")
        shutil.copytree(os.path.join(source, "examples/tube/flow_ringmodel"), reference,
                        ignore=shutil.ignore_patterns("results", "output", "*.log"))
        result = cocopp_run(bin_dir, reference, "case.yaml", env)
        check(result.returncode == 0, "the built-in ring model runs")
        reference_h5 = os.path.join(reference, "results", "case.h5")

        project = os.path.join(scratch, "external_solver")
        shutil.copytree(os.path.join(source, "examples/external_solver"), project,
                        ignore=shutil.ignore_patterns("results", "build", "*.log"))
        for transport in ("pipe", "file", "tcp"):
            write_case(project, f"{transport}.yaml", "python3, ../ring_wall.py", transport)
            result = cocopp_run(bin_dir, project, f"{transport}.yaml", env)
            check(result.returncode == 0, f"ring_wall.py runs over the {transport} transport")
            same_results(reference_h5, os.path.join(project, "results", f"{transport}.h5"),
                         f"ring_wall.py, {transport} transport")
        started_by_user(bin_dir, project, env, reference_h5)

        # Substeps: the SDK drives the window; the built-in ring model's results to the bit.
        substepped = os.path.join(scratch, "flow_ringmodel_substeps")
        shutil.copytree(reference, substepped, ignore=shutil.ignore_patterns("results"))
        with open(os.path.join(substepped, "case.yaml")) as case:
            text = case.read()
        with open(os.path.join(substepped, "case.yaml"), "w") as case:
            case.write(text.replace("    working_directory: structure\n",
                                    "    working_directory: structure\n    substeps: 2\n")
                       .replace("tolerance: 1.0e-6", "tolerance: 1.0e-5"))
        result = cocopp_run(bin_dir, substepped, "case.yaml", env)
        check(result.returncode == 0, "the built-in ring model runs with 2 substeps")
        write_case(project, "substeps.yaml", "python3, ../ring_wall.py", substeps=2)
        result = cocopp_run(bin_dir, project, "substeps.yaml", env)
        check(result.returncode == 0 and "2 substeps a time step" in result.stdout,
              "ring_wall.py runs with 2 substeps")
        same_results(os.path.join(substepped, "results", "case.h5"),
                     os.path.join(project, "results", "substeps.h5"), "ring_wall.py, 2 substeps")

        for fault, method in FAULTS.items():
            with open(os.path.join(project, f"{fault}.py"), "w") as script:
                script.write("import sys\nimport cocopp_sdk as sdk\nimport ring_wall\n\n"
                             "class RingWall(ring_wall.RingWall):" + method +
                             "\nring_wall.RingWall = RingWall\n"
                             "sys.exit(ring_wall.main(sys.argv))\n")
            write_case(project, f"{fault}.yaml", f"python3, ../{fault}.py", steps=5,
                       solver_convergence=fault == "converges_at_third",
                       substeps=2 if fault == "cannot_substep" else 1)
        write_case(project, "cannot_report.yaml", "python3, ../ring_wall.py", steps=5,
                   solver_convergence=True)
        env_faults = dict(env, PYTHONPATH=env["PYTHONPATH"] + os.pathsep + project)

        result = cocopp_run(bin_dir, project, "wrong_size.yaml", env_faults)
        check(result.returncode != 0 and "solver 'wall' reported an error: solve() returned 3 "
              "values; expected 300" in result.stdout,
              "a wrong output size is named in the coupler's error")
        result = cocopp_run(bin_dir, project, "exception.yaml", env_faults)
        check(result.returncode != 0 and "the wall cracked in step 2" in result.stdout
              and "after 1 time step" in result.stdout,
              "an exception in the solver stops the run with its text")
        with h5py.File(os.path.join(project, "results", "exception.h5"), "r") as results:
            check(np.array_equal(results["steps/step"][:], [1]), "the step before it is kept")
        result = cocopp_run(bin_dir, project, "converges_at_third.yaml", env_faults)
        with h5py.File(os.path.join(project, "results", "converges_at_third.h5"), "r") as results:
            check(result.returncode == 0 and
                  np.array_equal(results["steps/iterations"][:], [3] * 5),
                  "solver-coupling convergence: the wall's report ends every step at the "
                  "iteration it names")
        result = cocopp_run(bin_dir, project, "cannot_report.yaml", env)
        check(result.returncode != 0 and "solver 'wall' reported an error: this solver cannot "
              "report whether its own iterations converged" in result.stdout,
              "a solver that cannot report solver-coupling convergence says so")
        result = cocopp_run(bin_dir, project, "cannot_substep.yaml", env_faults)
        check(result.returncode != 0 and "solver 'wall' reported an error: the case asks this "
              "solver for 2 substeps per coupling time step, but it cannot take substeps"
              in result.stdout, "a solver that cannot take substeps says so")
        result = cocopp_run(bin_dir, project, "rejects_once.yaml", env_faults)
        with open(os.path.join(project, "results", "rejects_once.summary.json")) as summary:
            check(result.returncode == 0 and "step 3: solver 'wall' rejected the input of "
                  "iteration 1: the step from the last accepted input was shortened 1 time(s)"
                  in summary.read(), "a rejected input is retried and the run completes")
        with open(os.path.join(project, "structure", "wall.log")) as log:
            check("input rejected: this pressure would burst the wall" in log.read(),
                  "the reason is in the solver's log")

        plain = {key: value for key, value in env.items() if not key.startswith("COCOPP_")}
        script = os.path.join(project, "ring_wall.py")
        result = subprocess.run(["/usr/bin/python3", script, "length=1", "diameter=1", "cells=2",
                                 "rho_f=1", "e=1", "h=1"], env=plain, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
        check(result.returncode == 2 and "run it through `cocopp run case.yaml`" in result.stdout,
              "started outside cocopp: exit 2 and what to do")
        result = subprocess.run(["/usr/bin/python3", script, "--help"], env=plain,
                                stdout=subprocess.PIPE, text=True)
        check(result.returncode == 0 and "usage: ring_wall.py" in result.stdout, "--help")
    print("python_sdk: all checks passed")


if __name__ == "__main__":
    main()
