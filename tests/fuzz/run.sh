#!/usr/bin/env bash
# Runs one libFuzzer target (default: the MAVLink frame parser) for SECONDS on a temporary copy of
# its seed corpus (tests/fuzz/corpus/TARGET, when there is one) and prints its exec count.
#   tests/fuzz/run.sh BUILD_DIR SECONDS [TARGET]   (BUILD_DIR configured with -DHITL_FUZZ=ON, clang)
# TARGET: frame_parser, tlog, config, vehicle_files, scenario, board_replies, adb_framing, vio_server,
# link_spec, px4_console, ulog, campaign_file.
# Exits non-zero on any finding (crash, sanitizer report, trapped invariant, leak, timeout,
# out-of-memory); the reproducer is kept in BUILD_DIR/fuzz-artifacts/.
set -euo pipefail

if [[ $# -lt 2 || $# -gt 3 ]]; then
  echo "usage: $0 BUILD_DIR SECONDS [TARGET]" >&2
  exit 2
fi
build_dir=$1
seconds=$2
target=${3:-frame_parser}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
fuzzer="$build_dir/tests/fuzz/${target}_fuzz"
max_len=4096  # files: a few KB reach every branch
[[ $target == frame_parser ]] && max_len=1024
if [[ ! -x "$fuzzer" ]]; then
  echo "$0: $fuzzer not found; build it: cmake -S <src> -B $build_dir -DHITL_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++ && cmake --build $build_dir" >&2
  exit 2
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/hitl-fuzz.XXXXXX")
trap 'rm -rf "$work"' EXIT
if [[ -d "$here/corpus/$target" ]]; then cp -r "$here/corpus/$target" "$work/corpus"; else mkdir "$work/corpus"; fi
artifacts="$build_dir/fuzz-artifacts"
mkdir -p "$artifacts"

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

status=0
"$fuzzer" "$work/corpus" \
  -max_total_time="$seconds" -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$artifacts/" 2>&1 | tee "$work/log" || status=$?
# libFuzzer exits 0 when time runs out without a finding; anything else is a finding.
if [[ $status -ne 0 ]] || grep -qE "ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:|SUMMARY: " "$work/log"; then
  echo "$0: the fuzzer found a problem (status $status); reproducer in $artifacts/" >&2
  exit 1
fi
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log" | tail -1)
echo "$0: $target: no findings in ${seconds}s, ${execs:-?} executions"
