#!/usr/bin/env bash
# Install the Debian 12 packages cocopp needs to build, test and plot, and the external solvers
# the tests run: CalculiX (Debian's calculix-ccx and a ccx built from its source with cocopp's
# restart patch, scripts/install-calculix.sh) and OpenFOAM with the headers cocoppPimpleFoam
# compiles against (scripts/install-openfoam.sh). Idempotent: does nothing when everything is
# there already. Run as root (or with sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  ccache  # CI compiles a fresh clone: unchanged files come from the cache (scripts/lib/compiler-cache.sh)
  dpkg-dev  # dpkg-shlibdeps, for the Debian package (cpack)
  libeigen3-dev libyaml-cpp-dev libhdf5-dev hdf5-tools
  libcli11-dev libfmt-dev nlohmann-json3-dev libnanoflann-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  python3-h5py python3-matplotlib python3-numpy python3-yaml python3-pil
  python3-vtk9  # a real VTK reader for the ParaView output's test
  clang-format
  valgrind  # bench/tube_run.py --instructions counts the coupler's instructions (callgrind)
  clang-14 libclang-rt-14-dev  # libFuzzer for the fuzz targets (scripts/fuzz.sh)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: all ${#packages[@]} packages present"
else
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  echo "install-dependencies: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get -o DPkg::Lock::Timeout=600 update -q
  "${sudo_cmd[@]}" apt-get -o DPkg::Lock::Timeout=600 install -y -q --no-install-recommends "${missing[@]}"
fi

# CalculiX: Debian's ccx and cocopp's patched build of it (skip with COCOPP_WITHOUT_CALCULIX=1:
# CMake then says that the CalculiX tests are disabled).
if [ "${COCOPP_WITHOUT_CALCULIX:-0}" != 1 ]; then
  "$(dirname "$0")/install-calculix.sh"
fi

# OpenFOAM and the headers cocoppPimpleFoam compiles against (skip with COCOPP_WITHOUT_OPENFOAM=1:
# CMake then says that the OpenFOAM parts are disabled).
if [ "${COCOPP_WITHOUT_OPENFOAM:-0}" != 1 ]; then
  "$(dirname "$0")/install-openfoam.sh"
fi
