#!/usr/bin/env bash
# Run the whole test suite: install what is missing, build, run ctest; then the same suite in
# an AddressSanitizer/UndefinedBehaviorSanitizer build (set COCOPP_SKIP_SANITIZE=1 to skip it
# locally), and a short run of the fuzz targets (COCOPP_SKIP_FUZZ=1 skips it). This is the
# command .ci/run calls.
#
# OpenFOAM and CalculiX are required (COCOPP_WITH_*=ON), so that a missing solver fails the
# configure step instead of silently skipping its tests; COCOPP_WITHOUT_OPENFOAM=1 and
# COCOPP_WITHOUT_CALCULIX=1 (as for install-dependencies) leave them out.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-dependencies.sh
solvers=(
  -DCOCOPP_WITH_OPENFOAM=$([ "${COCOPP_WITHOUT_OPENFOAM:-0}" = 1 ] && echo OFF || echo ON)
  -DCOCOPP_WITH_CALCULIX=$([ "${COCOPP_WITHOUT_CALCULIX:-0}" = 1 ] && echo OFF || echo ON)
)
scripts/build.sh -DCOCOPP_WERROR=ON "${solvers[@]}"
ctest --test-dir build --output-on-failure --timeout 300
if [ "${COCOPP_SKIP_SANITIZE:-0}" != 1 ]; then
  # -O1 -g1 (line tables only) rather than RelWithDebInfo's -O2 -g: the sanitizer build's
  # compile time is most of CI's time; its reports keep file and line.
  # No benchmarks here: no test runs them, and their compile time is CI time.
  BUILD_DIR=build-asan BUILD_TYPE=Sanitize scripts/build.sh -DCOCOPP_SANITIZE=ON \
    -DCOCOPP_BUILD_BENCHMARKS=OFF \
    -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -g1" -DCMAKE_C_FLAGS_SANITIZE="-O1 -g1" \
    -DCOCOPP_WERROR=ON "${solvers[@]}"
  # Whole example cases (label `long`: minutes of OpenFOAM and ccx time) ran in the Release
  # pass; the sanitizer pass covers cocopp's own code with the rest.
  ctest --test-dir build-asan --output-on-failure --timeout 600 --label-exclude long
fi
# The fuzz targets (clang, libFuzzer): 12 s each on their seed corpora (docs/reliability.md).
# The Release and sanitizer passes above replayed the corpora (ctest fuzz_replay_*).
if [ "${COCOPP_SKIP_FUZZ:-0}" != 1 ]; then
  scripts/fuzz.sh --seconds 12
fi
