#!/usr/bin/env python3
"""Check the shape of cocopp's code (run by ctest as check_layers):

1. Includes point down the layers only. Each source folder belongs to one layer, and a file may
   include the project's headers of its own layer and of the layers listed for it below; a
   library (CMake target) per layer links the same ones. The table is docs/architecture.md's.
2. A component's file is named after its type: every name registered with COCOPP_REGISTER (or
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
    "protocol": (["core/protocol/"], []),
    "core": (["core/case/", "core/data/"], ["protocol"]),
    "sdk": (["solver_wrappers/sdk/"], ["protocol"]),
    "mappers": (["mappers/"], ["core", "protocol"]),
    "solver_wrappers": (["solver_wrappers/"], ["sdk", "mappers", "core", "protocol"]),
    "coupling": (["coupler/"], ["solver_wrappers", "mappers", "core", "protocol"]),
    "app": (["coupler/app/"], ["coupling", "solver_wrappers", "mappers", "core", "protocol"]),
}
PRODUCT = list(LAYERS)
# On top, outside the product: fixtures shared by tests and benchmarks, the tests, the benchmarks.
LAYERS["test_support"] = (["tests/support/"], PRODUCT)
LAYERS["tests"] = (["tests/"], PRODUCT + ["test_support"])
LAYERS["bench"] = (["bench/"], PRODUCT + ["test_support"])

SOURCE_SUFFIXES = {".cpp", ".hpp", ".h", ".H", ".C"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
REGISTRATION = re.compile(r'(?:COCOPP_REGISTER\(\s*\w+\s*,|\bregister_\w+\()\s*"([^"]+)"')


def layer_of(relative):
    """The layer of a path relative to the root (longest matching folder), or None."""
    best, best_length = None, -1
    for layer, (folders, _) in LAYERS.items():
        for folder in folders:
            if relative.startswith(folder) and len(folder) > best_length:
                best, best_length = layer, len(folder)
    return best


def upward_includes(root, file, relative, layer):
    allowed = {layer, *LAYERS[layer][1]}
    for number, line in enumerate(file.read_text(errors="replace").splitlines(), 1):
        match = INCLUDE.match(line)
        if not match:
            continue
        target = match.group(1)
        # Project headers are included by their path from the root; anything else (OpenFOAM's
        # headers, a header next to the file) is not the project's layering.
        if not (root / target).is_file():
            continue
        target_layer = layer_of(target)
        if target_layer is None or target_layer in allowed:
            continue
        may = ", ".join(LAYERS[layer][1]) or "nothing but the standard library"
        yield (f"{relative}:{number}: includes {target} (layer {target_layer}), but layer "
               f"{layer} may include only its own headers and {may}: an include must point "
               f"down the layers (docs/architecture.md)")


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
    root = pathlib.Path(root)
    problems = []
    for file in sorted(root.rglob("*")):
        if file.suffix not in SOURCE_SUFFIXES or not file.is_file():
            continue
        relative = file.relative_to(root).as_posix()
        layer = layer_of(relative)
        if layer is None:
            continue
        problems += upward_includes(root, file, relative, layer)
        if layer in PRODUCT:
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
    print("check_layers: includes point down the layers; components are named after their types")
    return 0


if __name__ == "__main__":
    sys.exit(main())
