#!/usr/bin/env bash
# Runs every libFuzzer target long (default 600 s each) and prints one line per target with its
# exec count: the long counterpart of CTest's short fuzz.* runs.
#   bench/fuzz_long.sh [SECONDS_EACH] [BUILD_DIR]
# BUILD_DIR (default build/fuzz) is configured and built here with -DHITL_FUZZ=ON and clang.
set -euo pipefail

seconds=${1:-600}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${2:-$root/build/fuzz}
jobs=${JOBS:-$(nproc)}
cmake -S "$root" -B "$build_dir" -DHITL_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build_dir" -j"$jobs" >/dev/null

status=0
summary=()
for target in frame_parser tlog config vehicle_files scenario board_replies adb_framing vio_server link_spec px4_console ulog campaign_file fault_text field_plot; do
  if line=$("$root/tests/fuzz/run.sh" "$build_dir" "$seconds" "$target" 2>&1 | tail -1); then
    summary+=("$line")
  else
    summary+=("$target: FINDING ($line)")
    status=1
  fi
done
printf '%s\n' "${summary[@]}"
exit $status
