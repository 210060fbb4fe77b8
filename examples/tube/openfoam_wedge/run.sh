#!/usr/bin/env bash
# The OpenFOAM wedge tube and its comparison with the 1D tube: make the mesh, run this case and
# the 1D flow-structure example (examples/tube/flow_structure), compare the pressure at
# mid-tube and plot it (docs/images/openfoam_wedge_vs_1d.png); then the same case on 2 MPI
# ranks (case_2_ranks.yaml), compared with the serial run. Needs build/bin/cocopp and
# build/bin/cocoppPimpleFoam (scripts/setup.sh with OpenFOAM installed).
set -euo pipefail
cd "$(dirname "$0")"
bin=${COCOPP_BIN_DIR:-../../../build/bin}
(cd fluid && WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} blockMesh >log.blockMesh 2>&1) || {
  echo "blockMesh failed: see fluid/log.blockMesh" >&2
  exit 1
}
"$bin/cocopp" run case.yaml
"$bin/cocopp" run ../flow_structure/case.yaml
/usr/bin/python3 compare.py results/case.h5 ../flow_structure/results/case.h5 \
  --plot ../../../docs/images/openfoam_wedge_vs_1d.png
"$bin/cocopp" run case_2_ranks.yaml
/usr/bin/python3 compare.py results/case_2_ranks.h5 results/case.h5 --names "2 ranks" serial
