#!/usr/bin/env bash
# Install OpenFOAM for cocopp's OpenFOAM solver wrapper: Debian's `openfoam` package (ESI
# OpenFOAM v1912; binaries in /usr/bin, libraries in /usr/lib) plus what compiling a coupled
# OpenFOAM application against it needs. The binary package ships no headers and no wmake, so
# the matching Debian *source* package is fetched at set-up time into build-deps/ (outside git,
# never committed), wmake is built and the lnInclude header links are made.
#
# Idempotent: a second run finds the stamp file and returns in well under a second.
#   scripts/install-openfoam.sh              # into ./build-deps/openfoam
#   COCOPP_DEPS_DIR=/opt/deps scripts/install-openfoam.sh
# CMake finds the tree through the same default (option COCOPP_OPENFOAM_SOURCE).
set -euo pipefail
cd "$(dirname "$0")/.."
deps_dir=${COCOPP_DEPS_DIR:-$PWD/build-deps}
tree=$deps_dir/openfoam
stamp=$tree/.cocopp-ready

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
apt_get=("${sudo_cmd[@]}" apt-get -o DPkg::Lock::Timeout=600 -q)

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }

# 1. The binary package (and mpirun, which it pulls in through mpi-default-bin).
# dpkg-dev unpacks the source package.
missing=()
for p in openfoam dpkg-dev; do installed "$p" || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-openfoam: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${apt_get[@]}" update
  "${apt_get[@]}" install -y --no-install-recommends "${missing[@]}"
fi

binary_version=$(dpkg-query -W -f='${Version}' openfoam)
# A binary-only rebuild ("+b1") comes from the same source version.
source_version=${binary_version%+b*}
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$source_version" ]; then
  echo "install-openfoam: OpenFOAM $source_version and its headers in $tree are ready"
  exit 0
fi

start=$(date +%s)

# 2. The source package (headers, wmake), outside the machine's apt set-up.
# shellcheck source=scripts/lib/debian-source.sh
source scripts/lib/debian-source.sh
fetch_debian_source install-openfoam openfoam "$source_version" "$deps_dir" "$tree"

# 3. wmake and the lnInclude header links. OpenFOAM's bashrc reads unset variables and
# needs USER, so this runs in a subshell without `set -u`.
echo "install-openfoam: building wmake and the lnInclude header links"
(
  set +eu
  export USER=${USER:-$(id -un)}
  # shellcheck disable=SC1091
  source "$tree/etc/bashrc" WM_MPLIB=SYSTEMOPENMPI >/dev/null 2>&1
  set -e
  "$WM_PROJECT_DIR/wmake/src/Allmake"
  cd "$WM_PROJECT_DIR/src" && wmakeLnIncludeAll -j 2 .
) >"$deps_dir/openfoam-wmake.log" 2>&1 || {
  tail -20 "$deps_dir/openfoam-wmake.log"
  echo "install-openfoam: building wmake or the header links failed (log: $deps_dir/openfoam-wmake.log)" >&2
  exit 1
}
test -f "$tree/src/OpenFOAM/lnInclude/fvCFD.H" -o -f "$tree/src/finiteVolume/lnInclude/fvCFD.H" || {
  echo "install-openfoam: no fvCFD.H among the header links in $tree/src" >&2
  exit 1
}
echo "$source_version" >"$stamp"
echo "install-openfoam: OpenFOAM $source_version headers ready in $tree ($(($(date +%s) - start)) s)"
