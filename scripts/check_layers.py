#!/usr/bin/env python3
"""Check the shape of cocopp's code (run by ctest as check_layers):

1. Includes point down the layers only. Each source folder belongs to one layer, and a file may
   include the project's headers of its own layer and of the layers listed for it below; a
   library (CMake target) per layer links the same ones. The table is docs/architecture.md's.
2. The process boundary holds: code that runs in a solver process (solvers/) includes only the
   protocol, the SDK, core's readers and its own solver's headers (each solvers/<solver>/ is a
   layer of its own); code that runs in cocopp never includes solver-side code.
3. Project headers are included by their path from the root. An include written relative to
   the including file is resolved as the compiler does and reported.
4. A component's file is named after its type: every name registered with COCOPP_REGISTER (or
   register_*("name", ...)) is the file's stem, the stem's start (calculix_solver_wrapper.cpp
   registers calculix) or starts with the stem (axisymmetric.cpp registers
   axisymmetric_2d_to_3d and axisymmetric_3d_to_2d).

Usage: check_layers.py [source root]   (exit 0: all good; 1: violations, one per line)
"""
import pathlib
import re
import sys

# layer: (folders, longest prefix wins; layers its files may include besides its own)
LAYERS = {
    # Below both kinds of process: what crosses between them, and core's readers.
    "protocol": (["core/protocol/"], []),
    "core": (["core/case/", "core/data/"], ["protocol"]),
    # The solver side (solver processes): the SDK; each solvers/<solver>/ (solver_layers()).
    "sdk": (["solvers/sdk/"], ["protocol"]),
    # The coupler side (the cocopp process).
    "mappers": (["mappers/"], ["core", "protocol"]),
    "solver_wrappers": (["solver_wrappers/"], ["mappers", "core", "protocol"]),
    "coupling": (["coupler/"], ["solver_wrappers", "mappers", "core", "protocol"]),
    "app": (["coupler/app/"], ["coupling", "solver_wrappers", "mappers", "core", "protocol"]),
}
SOLVER_MAY_INCLUDE = ["sdk", "core", "protocol"]


def solver_layers(root):
    """One layer per solvers/<solver>/ folder: a solver includes no other solver's headers."""
    solvers = pathlib.Path(root) / "solvers"
    folders = sorted(f.name for f in solvers.iterdir() if f.is_dir()) if solvers.is_dir() else []
    return {f"solver {name}": ([f"solvers/{name}/"], SOLVER_MAY_INCLUDE)
            for name in folders if name != "sdk"}


def all_layers(root):
    layers = dict(LAYERS)
    layers.update(solver_layers(root))
    product = list(layers)
    # On top, outside the product: fixtures shared by tests and benchmarks, the tests, the
    # benchmarks.
    layers["test_support"] = (["tests/support/"], product)
    layers["tests"] = (["tests/"], product + ["test_support"])
    layers["bench"] = (["bench/"], product + ["test_support"])
    return layers, product


SOURCE_SUFFIXES = {".cpp", ".hpp", ".h", ".H", ".C"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
REGISTRATION = re.compile(r'(?:COCOPP_REGISTER\(\s*\w+\s*,|\bregister_\w+\()\s*"([^"]+)"')


def layer_of(layers, relative):
    """The layer of a path relative to the root (longest matching folder), or None."""
    best, best_length = None, -1
    for layer, (folders, _) in layers.items():
        for folder in folders:
            if relative.startswith(folder) and len(folder) > best_length:
                best, best_length = layer, len(folder)
    return best


def project_header(root, file, target):
    """The project header an `#include "target"` in `file` names, relative to the root, and
    whether it was written relative to the including file; None for headers outside the
    project (OpenFOAM's, ccx's, the standard library's)."""
    beside = (file.parent / target).resolve()
    if beside.is_file() and beside.is_relative_to(root) and not (root / target).is_file():
        return beside.relative_to(root).as_posix(), True
    if (root / target).is_file():
        return target, False
    return None


def include_problems(root, layers, file, relative, layer):
    allowed = {layer, *layers[layer][1]}
    for number, line in enumerate(file.read_text(errors="replace").splitlines(), 1):
        match = INCLUDE.match(line)
        if not match:
            continue
        found = project_header(root, file, match.group(1))
        if found is None:
            continue
        target, written_relative = found
        if written_relative:
            yield (f"{relative}:{number}: includes \"{match.group(1)}\" relative to itself: "
                   f"include project headers by their path from the root (\"{target}\")")
        target_layer = layer_of(layers, target)
        if target_layer is None or target_layer in allowed:
            continue
        may = ", ".join(layers[layer][1]) or "nothing but the standard library"
        yield (f"{relative}:{number}: includes {target} (layer {target_layer}), but layer "
               f"{layer} may include only its own headers and {may}: an include must point "
               f"down the layers and never across the process boundary (docs/architecture.md)")


def misnamed_components(file, relative):
    stem = file.stem
    for number, line in enumerate(file.read_text(errors="replace").splitlines(), 1):
        match = REGISTRATION.search(line)
        if not match or line.lstrip().startswith(("//", "#")):  # docs and the macro itself
            continue
        name = match.group(1)
        if stem == name or stem.startswith(name + "_") or name.startswith(stem + "_"):
            continue
        yield (f"{relative}:{number}: registers type '{name}' in a file named {file.name}: a "
               f"component's file is named after its type ({name}.cpp)")


def check(root):
    root = pathlib.Path(root).resolve()
    layers, product = all_layers(root)
    problems = []
    for file in sorted(root.rglob("*")):
        if file.suffix not in SOURCE_SUFFIXES or not file.is_file():
            continue
        relative = file.relative_to(root).as_posix()
        layer = layer_of(layers, relative)
        if layer is None:
            continue
        problems += include_problems(root, layers, file, relative, layer)
        if layer in product:
            problems += misnamed_components(file, relative)
    return problems


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent
    problems = check(root)
    for problem in problems:
        print(problem)
    if problems:
        print(f"check_layers: {len(problems)} problem(s)")
        return 1
    print("check_layers: includes point down the layers and stay on their side of the process "
          "boundary; components are named after their types")
    return 0


if __name__ == "__main__":
    sys.exit(main())
