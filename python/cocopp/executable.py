"""The executables a script runs: cocopp, and the ccx that scripts/install-calculix.sh built.

cocopp is found in the order scripts/lib/cocopp-bin.sh finds it for the shell scripts
(tests/python compares the two):

1. $COCOPP_BIN_DIR/cocopp, if the variable is set (the tests set it);
2. the checkout's build, build/bin/cocopp, when this package is a checkout's python/cocopp;
3. the cocopp on PATH (an install).
"""
import os
import pathlib
import shutil

# python/cocopp/executable.py in a checkout: the checkout is two folders up from the package.
PACKAGE_CHECKOUT = pathlib.Path(__file__).resolve().parents[2]


def checkout_of_package():
    """The checkout this package is in, or None for an installed package."""
    is_checkout = (PACKAGE_CHECKOUT / "scripts" / "lib" / "cocopp-bin.sh").is_file()
    return PACKAGE_CHECKOUT if is_checkout else None


def find_cocopp(checkout=None):
    """The path of the cocopp executable: see the module's order; `checkout` (default: the one
    this package is in) is the checkout whose build/bin is tried. Exits saying what to do if
    there is none."""
    bin_dir = os.environ.get("COCOPP_BIN_DIR")
    if bin_dir:
        return pathlib.Path(bin_dir) / "cocopp"
    checkout = checkout or checkout_of_package()
    if checkout is not None:
        built = pathlib.Path(checkout) / "build" / "bin" / "cocopp"
        if os.access(built, os.X_OK):
            return built
    on_path = shutil.which("cocopp")
    if on_path:
        return pathlib.Path(on_path)
    raise SystemExit("no cocopp: build it (scripts/setup.sh) or put an installed one on PATH")


def patched_ccx():
    """Where scripts/install-calculix.sh puts the ccx it builds with cocopp's patches (restarts
    need them): $COCOPP_DEPS_DIR/calculix/bin/ccx, else the checkout's build-deps/. The path,
    whether or not ccx was built there."""
    deps = os.environ.get("COCOPP_DEPS_DIR") or PACKAGE_CHECKOUT / "build-deps"
    return pathlib.Path(deps) / "calculix" / "bin" / "ccx"
