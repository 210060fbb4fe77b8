#!/usr/bin/env bash
# Coupling algorithms on the first 20 steps of the wire drawing case (bench.yaml): writes the
# case into results/bench_case, meshes the film and runs `cocopp bench` (results/bench/).
#   examples/wire_drawing/bench.sh [--bench FILE] [make_case.py options, e.g. --set mesh.film_axial_cells=50]
# --bench: the variants to compare (default bench.yaml; bench_load_driven.yaml for the paper's
# load-driven wire), a file in this directory.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
source "$root/scripts/lib/cocopp-bin.sh"
cocopp=$(cocopp_executable "$root")
case "${1:-}" in -h|--help) sed -n '2,6p' "$0"; exit 0 ;; esac
bench="bench.yaml"
if [ "${1:-}" = --bench ]; then bench="$2"; shift 2; fi
[ -f "$here/$bench" ] || { echo "bench.sh: no $here/$bench" >&2; exit 2; }
case_dir="$here/results/bench_case"
rm -rf "$case_dir" "$here/results/bench"
/usr/bin/python3 "$here/make_case.py" --output "$case_dir" "$@"
for film in "$case_dir/fluid" "$case_dir/surrogate/fluid"; do  # the surrogate's: iqnism
  if [ -d "$film" ]; then "$film/Allmesh"; fi
done
exec "$cocopp" bench "$here/$bench"
