#!/usr/bin/env bash
# fault_matrix.sh: what the emulated board (hitl target, NOT PX4) does under each hitl sim fault.
#
# For a no-fault baseline and each of the 42 faults `hitl sim --help` and docs/faults.md list
# (one representative argument set each), starts a fresh `hitl target --lockstep`, flies docs/examples/square.json
# against it with `hitl sim --lockstep --speed 0 --fault SPEC --json --record`, reads the
# board's own frames (sysid 1) back from the recording with `hitl inspect --tlog --json`, and
# prints one markdown row per fault: the board's STATUSTEXTs not said in the baseline, its mode
# changes, its ESTIMATOR_STATUS flags around the fault, and the flight's outcome (end, trajectory
# state, tracking RMS/max, touchdowns, armed at the end).
#
# Every process gets explicit, non-default ports (the defaults 14550-14600 belong to CI):
# board HIL 25560, GCS 25558, VIO 25570; simulator local port 25561; no client port.
# Each run is bounded: --duration 120 s simulated, 90 s of wall time, --lockstep-timeout 0.05 s
# (LOCKSTEP_TIMEOUT=; a dropped HIL_SENSOR costs that much wall time).
#
# Run:   bench/faults/fault_matrix.sh [OUT.md]     (HITL=path/to/hitl, default build/cli/hitl;
#        WORK=dir for the raw logs, default a mktemp dir; ONLY=regex to run some faults)
# Needs: jq. Runs serially (one board at a time on the same ports); about 1-3 minutes.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
HITL=${HITL:-$ROOT/build/cli/hitl}
TRAJ=${TRAJ:-$ROOT/docs/examples/square.json}
OUT=${1:-/dev/stdout}
WORK=${WORK:-$(mktemp -d /tmp/fault_matrix.XXXXXX)}
ONLY=${ONLY:-.}
HIL_PORT=25560 GCS_PORT=25558 VIO_PORT=25570 LOCAL_PORT=25561
SIM_DURATION=120 WALL_TIMEOUT=90 LOCKSTEP_TIMEOUT=${LOCKSTEP_TIMEOUT:-0.05}

# One representative argument set per fault; the square arms at about 8 s and flies until about 40 s.
# The commas are the faults' arguments, not array separators.
# shellcheck disable=SC2054
FAULTS=(
  none
  gps-loss@12+8 gps-jump:20,0@12+15 gps-degrade:2,4,5@12+15 imu-bias:0.3,0,0@12+15
  gyro-bias:0.05,0,0@12+15 mag-offset:0.3,0,0@12+15 baro-drift:5@12+15 motor:2,0.75@12+15
  vio-loss@12+15 hil-drop:0.1@12+15 hil-delay:15@12+3 imu-noise:5@12+15 imu-stuck@12+3
  imu-clip:20,2@12+15 imu-vibration:5,80@12+15 mag-stuck@12+15 mag-scale:1.5@12+15
  baro-offset:100@12+15 baro-stuck@12+15 gps-drift:0.5,0@12+15 gps-noise:5@12+15
  prop-damage:1,0.85,2@12+15 payload:0.5@12+15 wind:5,0@12+15 gust:5,0@12+6 turbulence:1@12+15
  actuators-stale@12+3 vio-drift:0.1,0,0@12+15 vio-jump:5,0,0@12+15 vio-quality:10@12+15
  hil-burst:0.02,0.25@12+15 hil-jitter:5@12+3 hil-reorder:0.1@12+15 hil-dup:0.1@12+15
  hil-rate:20@12+5 vio-drop:0.5@12+15 vio-delay:20@12+15 vio-burst:0.02,0.25@12+15
  vio-jitter:10@12+15 vio-reorder:0.1@12+15 vio-dup:0.1@12+15 vio-rate:10@12+15
)

# One run: $1 the fault spec (or none), $2 the file name stem. Leaves STEM.sim.json, STEM.board.json.
run_one() {
  local spec=$1 stem=$2 tpid rc=0
  local -a fault_args=()
  [[ $spec == none ]] || fault_args=(--fault "$spec")
  "$HITL" target --lockstep --hil-port "$HIL_PORT" --gcs-port "$GCS_PORT" --vio-port "$VIO_PORT" \
    --duration $((SIM_DURATION + 60)) >"$stem.target.out" 2>"$stem.target.err" &
  tpid=$!
  sleep 0.3
  timeout "$WALL_TIMEOUT" "$HITL" sim --lockstep --speed 0 --lockstep-timeout "$LOCKSTEP_TIMEOUT" \
    -t "$TRAJ" --hil-port "$HIL_PORT" --local-port "$LOCAL_PORT" --vio-port "$VIO_PORT" \
    --clients 0 --duration "$SIM_DURATION" --json --record "$stem.tlog" "${fault_args[@]}" \
    >"$stem.sim.json" 2>"$stem.sim.err" || rc=$?
  kill "$tpid" 2>/dev/null || true
  wait "$tpid" 2>/dev/null || true
  echo "$rc" >"$stem.rc"
  "$HITL" inspect --tlog "$stem.tlog" --show STATUSTEXT,HEARTBEAT,ESTIMATOR_STATUS --follow --json \
    2>/dev/null | jq -c 'select(.type == "frame" and .sysid == 1)' >"$stem.board.json" || true
  rm -f "$stem.tlog"
}

# A row of the table from a run's files: $1 spec, $2 stem, $3 the baseline's board texts (JSON array).
row() {
  local spec=$1 stem=$2 base_texts=$3 t0=-1 t1=-1 win
  if [[ $spec == *@* ]]; then
    win=${spec#*@}
    t0=${win%%+*}
    if [[ $win == *+* ]]; then t1=$(jq -n "$t0 + ${win#*+}"); else t1=1e9; fi
  fi
  local board sim
  board=$(jq -s -c --argjson t0 "$t0" --argjson t1 "$t1" --argjson base "$base_texts" '
    def mode: {"196608":"Position","50593792":"Hold","33816576":"Takeoff","100925440":"Land"}[tostring] // (. | tostring);
    def dedup: reduce .[] as $x ([]; if length > 0 and .[-1] == $x then . else . + [$x] end);
    ([.[] | select(.name == "STATUSTEXT") | .fields.text
      | select(startswith("hitl target:") | not)] | unique) as $texts
    | ([.[] | select(.name == "HEARTBEAT" and .fields.autopilot == 12)
        | (.fields.custom_mode | mode) + (if .fields.base_mode >= 128 then "*" else "" end)] | dedup) as $modes
    | [.[] | select(.name == "ESTIMATOR_STATUS")] as $est
    | {texts: ($texts - $base), all_texts: $texts, modes: ($modes | join("→")),
       flags_before: ([$est[] | select(.fields.time_usec < $t0 * 1e6) | .fields.flags] | last),
       flags_during: ([$est[] | select($t0 >= 0 and .fields.time_usec >= $t0 * 1e6
                        and .fields.time_usec <= ($t1 + 5) * 1e6) | .fields.flags] | dedup | join("→")),
       flags_end: ([$est[] | .fields.flags] | last)}' "$stem.board.json")
  sim=$(jq -s -c '[.[] | select(.type == "summary")] | last // {}
    | {end: (.end // "none"), state: (.trajectory.state // "?"), failure: (.trajectory.failure // ""),
       rms: (.trajectory.rms_m // null), max: (.trajectory.max_m // null),
       touchdowns: (.landing.touchdowns // null), armed: (.armed // null),
       sim_s: (.sim_time_s // null), wall_s: (.wall_time_s // null),
       fallbacks: (.lockstep.fallbacks // null)}' "$stem.sim.json")
  jq -n -r --arg spec "$spec" --argjson b "$board" --argjson s "$sim" --arg rc "$(cat "$stem.rc")" '
    def f2: if . == null then "-" else (. * 100 | round / 100 | tostring) end;
    def txt(a): if (a | length) == 0 then "none new" else (a | map("\"" + . + "\"") | join("; ")) end;
    "| `\($spec)` | \(if $spec == "none" then txt($b.all_texts) else txt($b.texts) end) | \($b.modes) | "
    + "\($b.flags_before // "-") / \(if $b.flags_during == "" then "-" else $b.flags_during end) / \($b.flags_end // "-") | "
    + "\($s.end), \($s.state)\(if $s.failure != "" then " (" + $s.failure + ")" else "" end)"
    + ", \($s.touchdowns // "-") touchdown(s), \(if $s.armed then "armed" else "disarmed" end) at end"
    + "\(if $rc != "0" then ", exit " + $rc else "" end)"
    + "\(if ($s.fallbacks // 0) > 0 then ", " + ($s.fallbacks | tostring) + " lockstep fallbacks" else "" end) | "
    + "\($s.rms | f2) / \($s.max | f2) | \($s.sim_s | f2) / \($s.wall_s | f2) |"'
}

command -v jq >/dev/null || { echo "fault_matrix.sh: needs jq" >&2; exit 2; }
[[ -x $HITL ]] || { echo "fault_matrix.sh: no hitl at $HITL (set HITL=)" >&2; exit 2; }
mkdir -p "$WORK"
echo "fault_matrix.sh: raw logs in $WORK" >&2

{
  echo "| fault | board STATUSTEXT (not in the baseline) | board modes (\`*\` armed) | ESTIMATOR_STATUS flags before / in the fault (+5 s) / at the end | end, trajectory, landing | RMS / max (m) | sim / wall (s) |"
  echo "|---|---|---|---|---|---|---|"
  base_texts='[]'
  i=0
  for spec in "${FAULTS[@]}"; do
    [[ $spec == none || $spec =~ $ONLY ]] || continue
    stem=$(printf '%s/%02d-%s' "$WORK" "$i" "${spec%%[:@]*}")
    i=$((i + 1))
    echo "fault_matrix.sh: $spec" >&2
    run_one "$spec" "$stem"
    if [[ $spec == none ]]; then
      base_texts=$(jq -s -c '[.[] | select(.name == "STATUSTEXT") | .fields.text] | unique' "$stem.board.json")
    fi
    row "$spec" "$stem" "$base_texts"
  done
} >"$OUT"
