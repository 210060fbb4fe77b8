#!/usr/bin/env python3
"""scripts/check_layers.py finds what it is there to find: on a copy of the source tree it
passes, and it fails, naming the file and line, once an upward include or a misnamed component
is planted in the copy. Usage: test_check_layers.py <source root>"""
import pathlib
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(sys.argv[1]).resolve()
CHECKER = ROOT / "scripts" / "check_layers.py"
FOLDERS = ["core", "mappers", "solvers", "solver_wrappers", "coupler", "tests", "bench"]


def run(tree):
    result = subprocess.run([sys.executable, str(CHECKER), str(tree)], capture_output=True,
                            text=True)
    return result.returncode, result.stdout


def fresh_copy(base):
    tree = pathlib.Path(tempfile.mkdtemp(dir=base))
    for folder in FOLDERS:
        shutil.copytree(ROOT / folder, tree / folder,
                        ignore=shutil.ignore_patterns("*.h5", "results", "__pycache__"))
    return tree


def plant(tree, relative, line):
    file = tree / relative
    lines = file.read_text().splitlines()
    # After the first include, so that the planted one is an ordinary line of the file.
    first = next(i for i, text in enumerate(lines) if text.startswith("#include"))
    lines.insert(first + 1, line)
    file.write_text("\n".join(lines) + "\n")
    return first + 2  # 1-based line of the planted include


failures = []
passed = []


def expect(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    (passed if condition else failures).append(what)


with tempfile.TemporaryDirectory() as base:
    code, output = run(fresh_copy(base))
    expect(code == 0, f"the copy as it is passes (exit {code}): {output.strip()}")

    cases = [
        ("core/data/interface.cpp", '#include "coupler/app/run.hpp"', "layer app"),
        ("core/protocol/messages.hpp", '#include "solvers/sdk/solver_sdk.hpp"', "layer sdk"),
        ("solvers/sdk/solver_sdk.cpp", '#include "core/case/settings.hpp"', "layer core"),
        ("mappers/mapper.cpp", '#include "solver_wrappers/solver_wrapper.hpp"',
         "layer solver_wrappers"),
        ("bench/calculix_bench.hpp",
         '#include "tests/unit/solver_wrappers/calculix/calculix_test_helpers.hpp"',
         "layer tests"),
        # The process boundary, both ways: solver-side code never includes the coupler's ...
        ("solvers/tube/tube_flow.cpp", '#include "solver_wrappers/solver_wrapper.hpp"',
         "layer solver_wrappers"),
        ("solvers/calculix/coupled_ccx.cpp", '#include "mappers/mapper.hpp"', "layer mappers"),
        # ... nor another solver's ...
        ("solvers/tube/tube_flow.cpp", '#include "solvers/openfoam/patch_numbering.hpp"',
         "layer solver openfoam"),
        # ... and the coupler side never includes solver-side code, the SDK included.
        ("solver_wrappers/tube/tube.cpp", '#include "solvers/tube/tube_input.hpp"',
         "layer solver tube"),
        ("coupler/coupled_solvers/coupled_solver.cpp", '#include "solvers/sdk/solver_sdk.hpp"',
         "layer sdk"),
        # Written relative to the including file, as the compiler resolves it.
        ("core/data/interface.cpp", '#include "../../coupler/app/run.hpp"', "layer app"),
    ]
    for relative, include, layer in cases:
        tree = fresh_copy(base)
        line = plant(tree, relative, include)
        code, output = run(tree)
        expect(code == 1 and f"{relative}:{line}: includes" in output and layer in output,
               f"a forbidden include in {relative} is reported at line {line} ({layer})")

    tree = fresh_copy(base)
    line = plant(tree, "solvers/tube/tube_flow.cpp", '#include "tube_input.hpp"')
    code, output = run(tree)
    expect(code == 1 and f"solvers/tube/tube_flow.cpp:{line}: includes \"tube_input.hpp\" "
           "relative to itself" in output and '"solvers/tube/tube_input.hpp"' in output,
           "an include of a project header relative to the including file is reported")

    tree = fresh_copy(base)
    (tree / "coupler/predictors/linear.cpp").rename(tree / "coupler/predictors/extrapolate.cpp")
    code, output = run(tree)
    expect(code == 1 and "coupler/predictors/extrapolate.cpp" in output and "'linear'" in output,
           "a component in a file not named after its type is reported")

print(f"{len(passed)} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
