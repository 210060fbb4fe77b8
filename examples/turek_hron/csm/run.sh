#!/usr/bin/env bash
# Run a Turek-Hron CSM test through the coupler (docs/validation-turek-hron-csm.md):
#   examples/turek_hron/csm/run.sh csm1|csm2|csm3 [make_flag.py options, e.g. --nx 40 --ny 4]
# writes results/<test>/ (the flag's deck, the case, cocopp's results) and prints the tip's
# displacement against the published values (tip.py).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
source "$root/scripts/lib/cocopp-bin.sh"
cocopp=$(cocopp_executable "$root")
test=${1:-}
case "$test" in
  csm1 | csm2) dt=1.0 kind=static ;;
  csm3) dt=0.01 kind=dynamic ;;
  *) echo "usage: $0 csm1|csm2|csm3 [make_flag.py options]" >&2; exit 2 ;;
esac
shift
run="$here/results/$test"
rm -rf "$run"
mkdir -p "$run/flag"
/usr/bin/python3 "$here/make_flag.py" "$test" --dt "$dt" --output "$run/flag/flag.inp" "$@"
cp "$here/case_$kind.yaml" "$run/case.yaml"
# The partner runs on the Python SDK: the checkout's, unless one is installed.
export PYTHONPATH="$root/solvers/sdk${PYTHONPATH:+:$PYTHONPATH}"
"$cocopp" run "$run/case.yaml" || [ $? -eq 3 ]  # 3: stalled, still a result
/usr/bin/python3 "$here/tip.py" "$test" "$run/results/case.h5"
