#!/usr/bin/env bash
# Configure and build cocopp (Release) into ./build. Extra arguments go to cmake configure.
#   scripts/build.sh                       # build/bin/cocopp and the solver executables
#   BUILD_DIR=build-asan scripts/build.sh -DCOCOPP_SANITIZE=ON
# Compiles through ccache where it is installed (scripts/lib/compiler-cache.sh).
# Also puts the checkout's Python package on python3's path (scripts/lib/python-path.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck source=scripts/lib/python-path.sh
source scripts/lib/python-path.sh
put_package_on_python_path .
build_dir=${BUILD_DIR:-build}
# shellcheck source=scripts/lib/compiler-cache.sh
source scripts/lib/compiler-cache.sh
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-Release} "${compiler_cache[@]}" "$@" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
