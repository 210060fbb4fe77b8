#!/usr/bin/env bash
# Install the Debian 12 packages cocopp needs to build, test and plot, and the external solver
# the tests run (calculix-ccx: the CalculiX structural solver, /usr/bin/ccx). Idempotent: does
# nothing when everything is there already. Run as root (or with sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libyaml-cpp-dev libhdf5-dev hdf5-tools
  libcli11-dev libfmt-dev nlohmann-json3-dev libnanoflann-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  python3-h5py python3-matplotlib python3-numpy
  clang-format
  calculix-ccx
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "install-dependencies: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get -o DPkg::Lock::Timeout=600 update -q
"${sudo_cmd[@]}" apt-get -o DPkg::Lock::Timeout=600 install -y -q --no-install-recommends "${missing[@]}"
