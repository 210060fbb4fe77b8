#!/usr/bin/env bash
# Run a Turek-Hron FSI test (docs/validation-turek-hron.md):
#   examples/turek_hron/fsi/run.sh fsi1|fsi2|fsi3|cfd3 [--name NAME] [make_case.py options, e.g. --level 2]
# writes results/<NAME, default the test>/: the OpenFOAM channel (fluid/), the CalculiX flag
# (flag/), the case (case.yaml), cocopp's results (results/), then post.py's table against the
# published values (post.json) and the time histories (turek-hron.png). cfd3 is the fluid alone
# with the flag rigid, run by OpenFOAM's pimpleFoam (fluid/Allrun), no coupler.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
source "$root/scripts/lib/cocopp-bin.sh"
cocopp=$(cocopp_executable "$root")
test=${1:-}
usage="usage: $0 fsi1|fsi2|fsi3|cfd3 [--name NAME] [make_case.py options] (make_case.py --help lists them)"
case "$test" in
  fsi1 | fsi2 | fsi3 | cfd3) ;;
  -h | --help) echo "$usage"; exit 0 ;;
  *) echo "$usage" >&2; exit 2 ;;
esac
shift
name=$test
if [ "${1:-}" = "--name" ]; then name=$2; shift 2; fi
run="$here/results/$name"
rm -rf "$run"
/usr/bin/python3 "$here/make_case.py" "$test" "$run" "$@"
if [ "$test" = cfd3 ]; then
  "$run/fluid/Allrun"
else
  "$run/fluid/Allmesh"
  "$cocopp" run "$run/case.yaml" || [ $? -eq 3 ]  # 3: stalled, still a result
fi
/usr/bin/python3 "$here/post.py" "$run"
