#!/usr/bin/env bash
# The OpenFOAM wedge tube and its comparison with the 1D tube: make the mesh, run this case and
# a copy of the 1D flow-structure example (examples/tube/flow_structure, run under
# results/flow_structure_1d), compare the pressure at mid-tube and plot it
# (results/openfoam_wedge_vs_1d.png); then the same case on 2 MPI ranks (case_2_ranks.yaml),
# compared with the serial run. Writes under results/ only (and the mesh into fluid/, as
# OpenFOAM does). Needs cocopp and cocoppPimpleFoam (scripts/setup.sh with OpenFOAM installed).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
source "$root/scripts/lib/cocopp-bin.sh"
cocopp=$(cocopp_executable "$root")
cd "$here"
(cd fluid && WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} blockMesh >log.blockMesh 2>&1) || {
  echo "blockMesh failed: see fluid/log.blockMesh" >&2
  exit 1
}
"$cocopp" run case.yaml || [ $? -eq 3 ]  # 3: stalled (steps at the iteration limit), still a result
rm -rf results/flow_structure_1d
mkdir -p results
cp -r ../flow_structure results/flow_structure_1d
rm -rf results/flow_structure_1d/results results/flow_structure_1d/*/output
"$cocopp" run results/flow_structure_1d/case.yaml || [ $? -eq 3 ]
/usr/bin/python3 compare.py results/case.h5 results/flow_structure_1d/results/case.h5 \
  --plot results/openfoam_wedge_vs_1d.png
"$cocopp" run case_2_ranks.yaml || [ $? -eq 3 ]
/usr/bin/python3 compare.py results/case_2_ranks.h5 results/case.h5 --names "2 ranks" serial
