#!/usr/bin/python3
"""The Debian package (docs/install.md), ctest `debian_package`: `cpack -G DEB` from the build;
its dependencies are Debian packages, installed here; unpacked (not installed: the test must
not change the machine), its cocopp runs the tube example copied from its examples and gives
the build tree's results, and its Python SDK imports.

usage: test_debian_package.py --build BUILD_DIR
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_install import check, library_directory, run, user_environment  # noqa: E402


def installed(package):
    result = subprocess.run(["dpkg-query", "-W", "-f=${Status}", package],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    return "install ok installed" in result.stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", required=True)
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="cocopp-deb-") as scratch:
        run(["cpack", "--config", os.path.join(args.build, "CPackConfig.cmake"), "-B", scratch])
        packages = glob.glob(os.path.join(scratch, "cocopp_*_amd64.deb"))
        check(len(packages) == 1, f"cpack made one package ({[os.path.basename(p) for p in packages]})")
        package = packages[0]

        depends = run(["dpkg-deb", "-f", package, "Depends"]).strip()
        # HDF5 is linked from its static archive (CMakeLists.txt): its compression libraries
        # remain, libhdf5 itself does not.
        for needed in ["libyaml-cpp", "libsz2", "zlib1g", "libfmt", "python3-numpy"]:
            check(needed in depends, f"Depends names {needed}")
        for clause in depends.split(","):
            names = [re.sub(r"\(.*\)", "", alternative).strip()
                     for alternative in clause.split("|")]
            check(any(installed(name) for name in names if ".so" not in name),
                  f"dependency '{clause.strip()}' is an installed Debian package")

        root = os.path.join(scratch, "root")
        run(["dpkg-deb", "-x", package, root])
        prefix = os.path.join(root, "usr")
        env = user_environment(prefix)
        check(os.path.isfile(os.path.join(prefix, library_directory(), "libcocopp_sdk.a")),
              f"the libraries under usr/{library_directory()} (Debian's multiarch directory)")
        # No path of the build machine in what the package runs (the sources' and the build's
        # directory: a fallback into build-deps/ was one).
        build = os.path.abspath(args.build)
        source = run(["sed", "-n", "s/^CMAKE_HOME_DIRECTORY:INTERNAL=//p",
                      os.path.join(build, "CMakeCache.txt")]).strip()
        for binary in glob.glob(os.path.join(prefix, "bin", "*")) + \
                glob.glob(os.path.join(prefix, "libexec", "cocopp", "*")):
            data = open(binary, "rb").read()
            check(build.encode() not in data and (source + "/").encode() not in data,
                  f"no build machine's path in {os.path.relpath(binary, root)}")
        helped = run([os.path.join(prefix, "bin", "cocopp"), "--help"], env=env)
        check(f"{prefix}/share/doc/cocopp/case-file.md" in helped
              and os.path.isfile(os.path.join(prefix, "share/doc/cocopp/case-file.md")),
              "the help points to the packaged docs")
        example = os.path.join(scratch, "flow_structure")
        shutil.copytree(os.path.join(prefix, "share/cocopp/examples/tube/flow_structure"), example)
        run([os.path.join(prefix, "bin", "cocopp"), "run", "case.yaml"], cwd=example, env=env)
        reference = os.path.join(scratch, "reference")
        shutil.copytree(os.path.join(prefix, "share/cocopp/examples/tube/flow_structure"),
                        reference)
        run([os.path.join(args.build, "bin", "cocopp"), "run", "case.yaml"], cwd=reference,
            env=dict(env, COCOPP_BIN_DIR=os.path.join(args.build, "bin")))
        with h5py.File(os.path.join(example, "results", "case.h5"), "r") as a, \
                h5py.File(os.path.join(reference, "results", "case.h5"), "r") as b:
            check(a.attrs["status"] == "completed", "the packaged cocopp runs the tube example")
            check(np.array_equal(a["steps/iterations"][:], b["steps/iterations"][:])
                  and np.array_equal(a["x/wall/displacement"][:], b["x/wall/displacement"][:]),
                  "with the build tree's results to the bit")
        version = run(["/usr/bin/python3", "-c",
                       "import cocopp_sdk; print(cocopp_sdk.PROTOCOL_VERSION)"], env=env)
        check(version.strip() == "1", "the packaged Python SDK imports")
        imported = run(["/usr/bin/python3", "-c", "import cocopp.results, cocopp.case; "
                        "print(cocopp.results.__file__)"], env=env)
        check(imported.strip().startswith(prefix), "the packaged package cocopp imports")
    print("debian_package: all checks passed")


if __name__ == "__main__":
    main()
