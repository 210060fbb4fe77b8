#!/usr/bin/env bash
# Configure and build cocopp (Release) into ./build. Extra arguments go to cmake configure.
#   scripts/build.sh                       # build/bin/cocopp and the solver executables
#   BUILD_DIR=build-asan scripts/build.sh -DCOCOPP_SANITIZE=ON
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-Release} "$@" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
