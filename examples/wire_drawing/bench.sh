#!/usr/bin/env bash
# Coupling algorithms on the first 20 steps of the wire drawing case (bench.yaml): writes the
# case into results/bench_case, meshes the film and runs `cocopp bench` (results/bench/).
#   examples/wire_drawing/bench.sh [make_case.py options, e.g. --set mesh.film_axial_cells=50]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
source "$root/scripts/lib/cocopp-bin.sh"
cocopp=$(cocopp_executable "$root")
case_dir="$here/results/bench_case"
rm -rf "$case_dir" "$here/results/bench"
/usr/bin/python3 "$here/make_case.py" --output "$case_dir" "$@"
for film in "$case_dir/fluid" "$case_dir/surrogate/fluid"; do  # the surrogate's: iqnism
  if [ -d "$film" ]; then "$film/Allmesh"; fi
done
exec "$cocopp" bench "$here/bench.yaml"
