#!/usr/bin/env bash
# The dry wire drawing case (docs/wire-drawing.md) in one command, after scripts/setup.sh:
# writes the film and the wire from parameters.yaml into results/<name>/, meshes the film and
# runs the coupled case there.
#   examples/wire_drawing/run.sh                     # the paper's case, 80 steps
#   examples/wire_drawing/run.sh --refine            # twice the cells in each direction
#   examples/wire_drawing/run.sh --steps 12          # only the first 12 time steps
#   examples/wire_drawing/run.sh --set lubricant.viscosity=122.5 --name half_viscosity
# Options other than --steps and --name go to make_case.py (--help lists them).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
source "$root/scripts/lib/cocopp-bin.sh"
cocopp=$(cocopp_executable "$root")
name=case
steps=
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --steps) steps="$2"; shift 2 ;;
    --name) name="$2"; shift 2 ;;
    --refine) args+=("$1"); [ "$name" = case ] && name=refined; shift ;;
    -h|--help) sed -n '2,8p' "$0"; /usr/bin/python3 "$here/make_case.py" --help; exit 0 ;;
    *) args+=("$1"); shift ;;
  esac
done
case_dir="$here/results/$name"
rm -rf "$case_dir"
/usr/bin/python3 "$here/make_case.py" --output "$case_dir" "${args[@]}"
for film in "$case_dir/fluid" "$case_dir/surrogate/fluid"; do  # the surrogate's: iqnism
  if [ -d "$film" ]; then "$film/Allmesh"; fi
done
if [ -n "$steps" ]; then
  sed -i "s/^  number_of_timesteps: .*/  number_of_timesteps: $steps/" "$case_dir/case.yaml"
fi
exec "$cocopp" run "$case_dir/case.yaml"
