#!/usr/bin/env bash
# The spec's Verification, Phase 1 (host side only, no board needed): is the simulator's ODOMETRY
# arriving on UDP 14570 at ~250 Hz? It replaces the spec's Python listener with a measured
# check. Start the simulator first, sending to this machine (hitl sim, whose default target is
# 127.0.0.1, or the spec's hitl-gz-start.sh), then run this on the same machine:
#
#   phase1-check.sh [--port 14570] [--duration 5] [--rate 250] [--tolerance 5]
#
# Exit: 0 ODOMETRY arrived at the rate, 1 it did not (none, or off the rate), 2 bad usage or the
# check could not run (hitl missing, the port taken). HITL=/path/to/hitl picks the binary.
set -euo pipefail

hitl="${HITL:-hitl}"
port=14570
duration=5
rate=250
tolerance=5

usage() {
  sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'
}

need_value() {
  if [ "$#" -lt 2 ] || [ -z "$2" ]; then
    echo "phase1-check: $1 needs a value" >&2
    exit 2
  fi
}

while [ "$#" -gt 0 ]; do
  case "$1" in
    --port) need_value "$@"; port="$2"; shift 2 ;;
    --duration) need_value "$@"; duration="$2"; shift 2 ;;
    --rate) need_value "$@"; rate="$2"; shift 2 ;;
    --tolerance) need_value "$@"; tolerance="$2"; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "phase1-check: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

if ! command -v "$hitl" > /dev/null 2>&1; then
  echo "phase1-check: '$hitl' not found: install hitl, or set HITL=/path/to/hitl" >&2
  exit 2
fi

echo "Phase 1: listening for ODOMETRY on UDP port $port for $duration s (expecting $rate Hz, +-$tolerance %)"
status=0
"$hitl" inspect --port "$port" --duration "$duration" --expect "ODOMETRY=$rate" --tolerance "$tolerance" || status=$?

case "$status" in
  0) echo "Phase 1 PASS: the simulator's ODOMETRY reaches port $port at the rate the VIO server expects." ;;
  1) echo "Phase 1 FAIL: ODOMETRY is missing or off its rate on port $port. Is the simulator running, sending" \
          "to this machine (hitl sim -i 127.0.0.1, without --no-vio), and is nothing else bound to port $port?" >&2 ;;
  *) echo "Phase 1: the check could not run (hitl inspect exited $status): see its message above." >&2
     status=2 ;;
esac
exit "$status"
