#!/usr/bin/env bash
# Run the whole test suite: install what is missing, build, run ctest; then the same suite in
# an AddressSanitizer/UndefinedBehaviorSanitizer build (set COCOPP_SKIP_SANITIZE=1 to skip it
# locally). This is the command .ci/run calls.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-dependencies.sh
scripts/build.sh -DCOCOPP_WERROR=ON
ctest --test-dir build --output-on-failure --timeout 300
if [ "${COCOPP_SKIP_SANITIZE:-0}" != 1 ]; then
  BUILD_DIR=build-asan BUILD_TYPE=RelWithDebInfo scripts/build.sh -DCOCOPP_SANITIZE=ON -DCOCOPP_WERROR=ON
  ctest --test-dir build-asan --output-on-failure --timeout 600
fi
