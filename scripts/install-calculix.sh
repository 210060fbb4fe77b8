#!/usr/bin/env bash
# Install CalculiX for cocopp's calculix wrapper: Debian's calculix-ccx package (/usr/bin/ccx)
# and, built from the same Debian source package at set-up time, a ccx with cocopp's changes
# (scripts/calculix/*.patch, applied in name order: restart files keep the material state
# variables, so a plastic model restarts exactly, and the axisymmetry flag, so that a CAX model
# restarts at all; a plastic NLGEOM stiffness assembled in a fraction of the time; SuiteSparse
# as a sparse direct solver, *STATIC, SOLVER=SUITESPARSE, with OpenBLAS). The source
# is fetched into build-deps/ (outside git, never committed); the binary goes to
# build-deps/calculix/bin/ccx, which CMake finds and the calculix wrapper uses by default
# (docs/solver-wrappers-calculix.md, "State reset").
#
# Idempotent: a second run finds the stamp file (source version + patch checksum) and returns
# at once. The build takes about two minutes on two cores.
#   scripts/install-calculix.sh              # into ./build-deps/calculix
#   COCOPP_DEPS_DIR=/opt/deps scripts/install-calculix.sh
#   COCOPP_BUILD_JOBS=1 nice -n 19 scripts/install-calculix.sh   # beside a running simulation
set -euo pipefail
cd "$(dirname "$0")/.."
deps_dir=${COCOPP_DEPS_DIR:-$PWD/build-deps}
prefix=$deps_dir/calculix
tree=$deps_dir/calculix-source
stamp=$prefix/.cocopp-ready
patches=(scripts/calculix/*.patch)

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }

# 1. The binary package and what building ccx needs (Build-Depends of calculix-ccx), and
# SuiteSparse for patch 06 with OpenBLAS, which CHOLMOD's supernodal factorization spends its
# time in (installing it makes it the system's libblas.so.3, Debian's alternative of highest
# priority; the reference BLAS makes CHOLMOD several times slower).
missing=()
for p in calculix-ccx dpkg-dev gfortran libspooles-dev libarpack2-dev liblapack-dev libblas-dev \
  libsuitesparse-dev libopenblas0-pthread; do
  installed "$p" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-calculix: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get -o DPkg::Lock::Timeout=600 -q update
  "${sudo_cmd[@]}" apt-get -o DPkg::Lock::Timeout=600 -q install -y --no-install-recommends "${missing[@]}"
fi

binary_version=$(dpkg-query -W -f='${Version}' calculix-ccx)
source_version=${binary_version%+b*}  # a binary-only rebuild comes from the same source
hooks=solvers/calculix/cocopp_ccx_hooks.h
wanted="$source_version $(cat "${patches[@]}" "$hooks" | sha256sum | cut -c1-16) ${COCOPP_CCX_OPTIMIZATION:--O3}"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$wanted" ] && [ -x "$prefix/bin/ccx" ] &&
  [ -f "$prefix/lib/libccx_cocopp.a" ]; then
  echo "install-calculix: ccx $source_version with cocopp's patches in $prefix/bin is ready"
  exit 0
fi

start=$(date +%s)
# shellcheck source=scripts/lib/debian-source.sh
source scripts/lib/debian-source.sh
fetch_debian_source install-calculix calculix-ccx "$source_version" "$deps_dir" "$tree"

# 2. cocopp's patches on top of Debian's (apt-get source applied those).
for patch_file in "${patches[@]}"; do
  patch -d "$tree" -p1 -s <"$patch_file" || {
    echo "install-calculix: $patch_file does not apply to calculix-ccx $source_version" >&2
    exit 1
  }
done

# 3. Build as Debian does (debian/rules: its flags, its Makefile patch), into build-deps.
src=$(find "$tree" -mindepth 2 -maxdepth 2 -type d -name src | head -1)
version=$(basename "$(dirname "$src")")  # ccx_2.20
# -O3 instead of Debian's -O2: a coupling iteration of the wire drawing case takes 10.7-11.6 s
# instead of 12.5 s, with the same results to 1e-11. -march=native would make it 10.3 s but
# lets the compiler fuse multiply-adds (stresses then differ by 3e-7) and ties the binary, which
# an install takes along, to this processor: COCOPP_CCX_OPTIMIZATION="-O3 -march=native".
optimization=${COCOPP_CCX_OPTIMIZATION:--O3}
echo "install-calculix: building $version with cocopp's patches, $optimization (log: $deps_dir/calculix-build.log)"
# The hooks header of patch 05 is cocopp's (solvers/calculix).
cflags="$optimization -w -I/usr/include/spooles -I/usr/include/suitesparse -I$PWD/solvers/calculix -DARCH=\"Linux\" -DSPOOLES -DSUITESPARSE -DARPACK -DMATRIXSTORAGE -DUSE_MT=1"
# Debian's Makefile's libraries and SuiteSparse's (patch 06); CMake links cocopp-ccx with the
# same (solvers/calculix/CMakeLists.txt).
libs="-lspooles -lpthread -larpack -lcholmod -lumfpack -lsuitesparseconfig -llapack -lblas -lm -lc"
make -C "$src" -j "${COCOPP_BUILD_JOBS:-$(nproc)}" \
  CFLAGS="$cflags" LIBS="$libs" \
  FFLAGS="$optimization -w -fallow-argument-mismatch" >"$deps_dir/calculix-build.log" 2>&1 || {
  tail -20 "$deps_dir/calculix-build.log"
  echo "install-calculix: building ccx failed (log: $deps_dir/calculix-build.log)" >&2
  exit 1
}
mkdir -p "$prefix/bin" "$prefix/lib"
cp "$src/$version" "$prefix/bin/ccx"
# The coupled ccx (cocopp-ccx, built by CMake) links ccx as a library: its objects, with main
# renamed so that cocopp's main can run it in a thread of its own.
(cd "$src" && eval "gcc $cflags -Dmain=cocopp_ccx_main -c $version.c -o cocopp_ccx_main.o" &&
  cp "$version.a" libccx_cocopp.a && ar r libccx_cocopp.a cocopp_ccx_main.o) >>"$deps_dir/calculix-build.log" 2>&1 || {
  echo "install-calculix: building ccx's library for cocopp-ccx failed (log: $deps_dir/calculix-build.log)" >&2
  exit 1
}
cp "$src/libccx_cocopp.a" "$prefix/lib/"
# `ccx -v` prints its version and exits with 201.
version_text=$("$prefix/bin/ccx" -v 2>&1 || true)
grep -q "cocopp: restart files keep the state variables and the axisymmetry flag" <<<"$version_text" || {
  echo "install-calculix: $prefix/bin/ccx does not report cocopp's patches" >&2
  exit 1
}
rm -rf "$tree"
echo "$wanted" >"$stamp"
echo "install-calculix: ccx $source_version with cocopp's patches ready in $prefix/bin ($(($(date +%s) - start)) s)"
