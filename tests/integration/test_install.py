#!/usr/bin/python3
"""The install as a user outside the tree meets it (docs/install.md), ctest `install`:

1. `cmake --install` into a temporary prefix, then the prefix moved elsewhere (relocatable);
2. the installed cocopp finds its own solvers, its ccx and its scripts in the moved tree;
3. examples/external_solver built against the moved install with find_package(cocopp) and with
   pkg-config, and its Python twin run on the installed Python SDK: each couples to the
   built-in tube flow and gives the built-in ring model's results to the bit (iterations,
   residuals, displacements), the installed tube example run alongside as the reference.

usage: test_install.py --build BUILD_DIR --source SOURCE_DIR [--openfoam] [--patched-ccx]
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np


def run(command, cwd=None, env=None, accepted=(0,)):
    result = subprocess.run(command, cwd=cwd, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    if result.returncode not in accepted:
        sys.exit(f"FAILED ({result.returncode}): {' '.join(map(str, command))}\n{result.stdout}")
    return result.stdout


def check(condition, message):
    if not condition:
        sys.exit(f"FAILED: {message}")
    print(f"ok: {message}")


def library_directory():
    """lib/<multiarch>, where the install puts libraries on Debian (lib/x86_64-linux-gnu)."""
    multiarch = subprocess.run(["gcc", "-print-multiarch"], stdout=subprocess.PIPE, text=True)
    return f"lib/{multiarch.stdout.strip()}" if multiarch.stdout.strip() else "lib"


def user_environment(prefix):
    """A user's shell: no test variables, Debian's python3 first, the moved install's Python SDK
    on PYTHONPATH (a /usr install needs none)."""
    env = {key: value for key, value in os.environ.items() if not key.startswith("COCOPP_")}
    env["PATH"] = f"{prefix}/bin:/usr/bin:{env.get('PATH', '')}"
    env["PYTHONPATH"] = f"{prefix}/lib/python3/dist-packages"
    env["PKG_CONFIG_PATH"] = f"{prefix}/{library_directory()}/pkgconfig"
    return env


def same_results(reference, other, label):
    with h5py.File(reference, "r") as a, h5py.File(other, "r") as b:
        check(a.attrs["status"] == "completed" and b.attrs["status"] == "completed",
              f"{label}: both runs completed")
        check(np.array_equal(a["steps/iterations"][:], b["steps/iterations"][:]),
              f"{label}: the same iterations in every step ({a['steps/iterations'][:].sum()})")
        check(np.array_equal(a["residuals/norms"][:], b["residuals/norms"][:]),
              f"{label}: the same residuals to the bit")
        for interface, variable in (("x", "displacement"), ("y", "pressure")):
            check(np.array_equal(a[f"{interface}/wall/{variable}"][:],
                                 b[f"{interface}/wall/{variable}"][:]),
                  f"{label}: the same {variable} to the bit")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--openfoam", action="store_true", help="cocoppPimpleFoam was built")
    parser.add_argument("--patched-ccx", action="store_true", help="the patched ccx was built")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="cocopp-install-") as scratch:
        staged = os.path.join(scratch, "staged")
        run(["cmake", "--install", args.build, "--prefix", staged])
        prefix = os.path.join(scratch, "moved", "cocopp")
        os.makedirs(os.path.dirname(prefix))
        shutil.move(staged, prefix)
        env = user_environment(prefix)
        cocopp = os.path.join(prefix, "bin", "cocopp")

        # What the install holds, and that the moved cocopp finds its parts in it.
        for part in ["bin/cocopp-tube-flow", "bin/cocopp-tube-structure",
                     "bin/cocopp-tube-ringmodel", "share/cocopp/plot_bench.py",
                     "share/cocopp/plot_results.py", f"{library_directory()}/libcocopp_sdk.a",
                     f"{library_directory()}/cmake/cocopp/cocoppConfig.cmake",
                     f"{library_directory()}/pkgconfig/cocopp-sdk.pc",
                     "share/doc/cocopp/case-file.md", "share/doc/cocopp/images/stability.png",
                     "lib/python3/dist-packages/cocopp_sdk.py",
                     "lib/python3/dist-packages/cocopp/results.py",
                     "lib/python3/dist-packages/cocopp/plot/bench.py",
                     "include/cocopp/solvers/sdk/solver_sdk.hpp"]:
            check(os.path.isfile(os.path.join(prefix, part)), f"installed {part}")
        check("cocopp" in run([cocopp, "--help"], env=env), "the moved cocopp runs")
        if args.patched_ccx:
            output = run([cocopp, "check",
                          f"{args.source}/examples/tube/flow_calculix/case.yaml"], env=env)
            # The example runs persistent, in the installed cocopp-ccx (built from the same
            # patched ccx, which the per-iteration mode runs).
            check(f"{prefix}/libexec/cocopp/cocopp-ccx -i" in output,
                  "the moved cocopp runs its own cocopp-ccx")
            check(os.path.isfile(os.path.join(prefix, "libexec/cocopp/ccx")),
                  "installed libexec/cocopp/ccx")
        if args.openfoam:
            wedge = os.path.join(scratch, "openfoam_wedge")
            shutil.copytree(f"{args.source}/examples/tube/openfoam_wedge", wedge,
                            ignore=shutil.ignore_patterns("results", "[0-9]*.[0-9]*", "*.log"))
            run(["blockMesh"], cwd=os.path.join(wedge, "fluid"),
                env=dict(env, WM_PROJECT_DIR="/usr/share/openfoam"))
            output = run([cocopp, "check", "case.yaml"], cwd=wedge, env=env)
            check(f"{prefix}/bin/cocoppPimpleFoam" in output,
                  "the moved cocopp runs its own cocoppPimpleFoam")

        # The examples as they ship: nothing that runs in the developer's tree left behind.
        leftovers = [os.path.join(d, f) for d, dirs, files in os.walk(
            os.path.join(prefix, "share", "cocopp", "examples")) for f in dirs + files
            if f in ("results", "output", "restart", ".cocopp.lock", "build") or
            f.endswith((".log", ".fifo"))]
        check(not leftovers, f"the installed examples hold no run products {leftovers[:3]}")

        # The reference: the installed tube example (flow + built-in ring model), copied out.
        examples = os.path.join(prefix, "share", "cocopp", "examples")
        reference = os.path.join(scratch, "flow_ringmodel")
        shutil.copytree(os.path.join(examples, "tube", "flow_ringmodel"), reference)
        run([cocopp, "run", "case.yaml"], cwd=reference, env=env)
        reference_h5 = os.path.join(reference, "results", "case.h5")
        # The installed plot script finds the installed package beside it, without PYTHONPATH
        # (as cocopp bench runs plot_bench.py) and without a checkout's (a HOME of its own: no
        # .pth file of scripts/build.sh).
        bare = {k: v for k, v in env.items() if k != "PYTHONPATH"}
        plotted = run(["/usr/bin/python3", os.path.join(prefix, "share/cocopp/plot_results.py"),
                       reference_h5], env=dict(bare, HOME=scratch))
        check(f"wrote {reference_h5[:-3]}.png" in plotted,
              "the installed plot_results.py draws with the installed package")

        # The solver project outside the tree, built with CMake's find_package(cocopp).
        project = os.path.join(scratch, "external_solver")
        shutil.copytree(os.path.join(examples, "external_solver"), project)
        run(["cmake", "-S", ".", "-B", "build", f"-DCMAKE_PREFIX_PATH={prefix}"], cwd=project,
            env=env)
        run(["cmake", "--build", "build"], cwd=project, env=env)
        run([cocopp, "run", "case.yaml"], cwd=project, env=env)
        same_results(reference_h5, os.path.join(project, "results", "case.h5"),
                     "C++ solver built with find_package(cocopp)")

        # The same solver built with pkg-config instead of CMake.
        flags = run(["pkg-config", "--cflags", "--libs", "cocopp-sdk"], env=env).split()
        run(["g++", "ring_wall.cpp", "-o", "build/ring-wall"] + flags, cwd=project, env=env)
        os.rename(os.path.join(project, "results"), os.path.join(project, "results_cmake"))
        run([cocopp, "run", "case.yaml"], cwd=project, env=env)
        same_results(reference_h5, os.path.join(project, "results", "case.h5"),
                     "C++ solver built with pkg-config")

        # The Python twin on the installed Python SDK.
        run([cocopp, "run", "case_python.yaml"], cwd=project, env=env)
        same_results(reference_h5, os.path.join(project, "results", "case_python.h5"),
                     "Python solver on cocopp_sdk")
    print("install: all checks passed")


if __name__ == "__main__":
    main()
