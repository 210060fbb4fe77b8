#!/usr/bin/env bash
# One step from a fresh Debian 12 machine to a built cocopp: install packages, configure, build.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-dependencies.sh
scripts/build.sh
echo "setup: built build/bin/cocopp"
