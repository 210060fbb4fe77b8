#!/usr/bin/env bash
# Build the fuzz targets (tests/fuzz: libFuzzer with ASan/UBSan, clang) into build-fuzz and run
# each for a while on a copy of its seed corpus. A crash, a sanitizer report, a leak, a hang
# (over 10 s an input) or an allocation over 2 GiB fails the run; the input that caused it is
# kept in build-fuzz/artifacts/. The inputs the run found go to build-fuzz/corpus/<target>/,
# never into the repository's seed corpus.
#   scripts/fuzz.sh                       # every target, 12 s each (CI: scripts/test.sh)
#   scripts/fuzz.sh --seconds 600 case_file protocol
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=12
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) targets+=("$1"); shift ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=(case_file protocol calculix_deck calculix_dat openfoam_dictionary)

build_dir=${FUZZ_BUILD_DIR:-build-fuzz}
# shellcheck source=scripts/lib/compiler-cache.sh
source scripts/lib/compiler-cache.sh
CC=clang-14 CXX=clang++-14 cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Fuzz "${compiler_cache[@]}" \
  -DCMAKE_CXX_FLAGS_FUZZ="-O1 -g1" -DCMAKE_C_FLAGS_FUZZ="-O1 -g1" -DCOCOPP_FUZZ=ON \
  -DCOCOPP_BUILD_BENCHMARKS=OFF -DCOCOPP_WITH_OPENFOAM=OFF -DCOCOPP_WITH_CALCULIX=OFF >/dev/null
cmake --build "$build_dir" -j "$(nproc)" --target cocopp_fuzz_targets

mkdir -p "$build_dir/artifacts"
for target in "${targets[@]}"; do
  corpus="$build_dir/corpus/$target"
  log="$build_dir/fuzz_$target.log"
  mkdir -p "$corpus"
  echo "fuzz_$target: ${seconds} s"
  # -rss_limit_mb also bounds a single allocation (malloc_limit_mb defaults to it).
  status=0
  "$build_dir/tests/fuzz/fuzz_$target" "$corpus" "tests/fuzz/corpus/$target" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$build_dir/artifacts/$target-" >"$log" 2>&1 ||
    status=$?
  # The last progress line: executions, cov (code edges reached), ft (features), corpus size.
  grep -E "^#[0-9]+" "$log" | tail -n 1 || true
  if [ "$status" != 0 ]; then
    tail -n 40 "$log" >&2
    echo "fuzz_$target failed (exit $status): the input is in $build_dir/artifacts/," \
      "the log in $log" >&2
    exit 1
  fi
done
