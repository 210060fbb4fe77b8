#!/usr/bin/env bash
# The wire drawing case under what makes it harder (docs/wire-drawing.md, "Stability"): the
# first 2 ms (10 steps held, 10 closing at the base time step) with the lubricant's viscosity
# x0.1 and x10, the die closing twice as far, and the time step x2 and x0.5. Each variant runs
# through run.sh into results/stability/<variant>/; stability.py tabulates how each ended.
#   examples/wire_drawing/stability.sh [--set KEY=VALUE ...] [variant ...]   # default: all
# --set options apply to every variant (e.g. coarser meshes, as docs/wire-drawing.md does).
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
declare -A variants=(
  [base]=""
  [viscosity_x0.1]="--set lubricant.viscosity=24.5"
  [viscosity_x10]="--set lubricant.viscosity=2450"
  [die_shrink_x2]="--set die.reduction=0.1948"
  [dt_x2]="--set time.delta_t=2.0e-4 --set time.steps=40 --set time.held_steps=5"
  [dt_x0.5]="--set time.delta_t=0.5e-4 --set time.steps=160 --set time.held_steps=20"
)
declare -A steps=([dt_x2]=10 [dt_x0.5]=40)
common=()
names=()
while [ $# -gt 0 ]; do
  case "$1" in
    --set) common+=("$1" "$2"); shift 2 ;;
    *) names+=("$1"); shift ;;
  esac
done
[ ${#names[@]} -gt 0 ] || names=(base viscosity_x0.1 viscosity_x10 die_shrink_x2 dt_x2 dt_x0.5)
for name in "${names[@]}"; do
  [ -n "${variants[$name]+set}" ] || { echo "stability.sh: no variant '$name'" >&2; exit 2; }
  echo "stability.sh: $name"
  # shellcheck disable=SC2086  # the options are words
  "$here/run.sh" --name "stability/$name" --steps "${steps[$name]:-20}" "${common[@]}" ${variants[$name]} \
    > "$here/results/stability-$name.log" 2>&1
  echo "stability.sh: $name exited with $? (log: results/stability-$name.log)"
done
/usr/bin/python3 "$here/stability.py" "$here/results/stability"
