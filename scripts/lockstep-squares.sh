#!/usr/bin/env bash
# Flies docs/examples/square.json N times in a row (default 50), each a new `hitl sim --lockstep
# --speed 0` against one `hitl target --lockstep` (issue 18.3 board reuse, issue 20 landings), and
# prints one line per square and the totals: squares done, landings with one touchdown and no
# rebound over 5 cm, IMU samples clipped. Loopback only. Exit 1 when any square failed.
#   scripts/lockstep-squares.sh [N] [HITL_BINARY]
set -u
n="${1:-50}"
hitl="${2:-$(dirname "$0")/../build/cli/hitl}"
root="$(cd "$(dirname "$0")/.." && pwd)"
[ -x "$hitl" ] || { echo "lockstep-squares: no hitl binary at $hitl (build it, or pass its path)" >&2; exit 2; }
command -v jq >/dev/null || { echo "lockstep-squares: needs jq" >&2; exit 2; }
case "$n" in ''|*[!0-9]*) echo "lockstep-squares: N must be a positive integer (got '$n')" >&2; exit 2;; esac

hil=24560; gcs=24558; local_port=24561
log="$(mktemp -d)"
"$hitl" target --bind 127.0.0.1 --hil-port "$hil" --gcs-port "$gcs" --vio-port 0 --lockstep >"$log/target.out" 2>"$log/target.err" &
target=$!
trap 'kill -INT "$target" 2>/dev/null; wait "$target" 2>/dev/null' EXIT
sleep 1

done_ok=0 clean=0 clipped=0
for i in $(seq 1 "$n"); do
  start=$(date +%s.%N)
  "$hitl" --json sim -i 127.0.0.1 --hil-port "$hil" --local-port "$local_port" --no-vio --clients 0 \
    --lockstep --speed 0 -t "$root/docs/examples/square.json" >"$log/sim$i.out" 2>"$log/sim$i.err"
  rc=$?
  wall=$(echo "$(date +%s.%N) - $start" | bc)
  summary="$(tail -n 1 "$log/sim$i.out")"
  end=$(jq -r '.end // "none"' <<<"$summary" 2>/dev/null || echo none)
  td=$(jq -r '.landing.touchdowns // -1' <<<"$summary" 2>/dev/null || echo -1)
  rb=$(jq -r '.landing.max_rebound_m // -1' <<<"$summary" 2>/dev/null || echo -1)
  pk=$(jq -r '(.landing.peak_accel_m_s2 // 0) / 9.80665' <<<"$summary" 2>/dev/null || echo 0)
  sat=$(jq -r '(.imu_saturated.accel // 0) + (.imu_saturated.gyro // 0)' <<<"$summary" 2>/dev/null || echo 0)
  printf 'square %3d: exit %d, %s, %s touchdown(s), rebound %.3f m, peak %.1f g, IMU clipped %s, %.1f s wall\n' \
    "$i" "$rc" "$end" "$td" "$rb" "$pk" "$sat" "$wall"
  [ "$rc" = 0 ] && [ "$end" = trajectory_done ] && done_ok=$((done_ok + 1))
  [ "$td" = 1 ] && awk "BEGIN{exit !($rb <= 0.05)}" && clean=$((clean + 1))
  clipped=$((clipped + sat))
done
echo "lockstep squares: $done_ok of $n done, $clean of $n landed with one touchdown and rebound <= 5 cm, IMU samples clipped: $clipped"
echo "target: $(grep -c 'a new simulator session' "$log/target.err") new sessions noticed; logs in $log"
[ "$done_ok" = "$n" ] && [ "$clean" = "$n" ]
