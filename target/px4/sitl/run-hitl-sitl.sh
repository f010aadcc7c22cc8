#!/usr/bin/env bash
# Runs PX4 SITL in HITL the way the VOXL2 runs PX4 (rcS.hitl beside this script): a PX4 build made
# with target/px4 (dsp_hitl and the MavlinkReceiver patch, docs/px4-module.md), no simulator module,
# HIL_SENSOR / HIL_GPS entering through the primary MAVLink instance on UDP 14560. Then fly it with
# `hitl sim --no-vio` and `hitl arm`, `hitl fly takeoff --alt 5`, `hitl shell -c "dsp_hitl status"`.
#
# Exit codes: 2 bad options or an unusable PX4 build; otherwise PX4's own.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
target_px4="$(dirname "$here")"

usage() {
	cat <<EOF
Usage: $(basename "$0") [options]

Starts PX4 SITL (a px4_sitl_nolockstep build with target/px4) in HITL: the spec's HITL parameters,
three MAVLink instances, dsp_hitl, sensors in HIL mode, the multicopter flight stack. PX4's console
(pxh>) runs in the foreground unless --daemon.

Options:
  --px4-build DIR         PX4 build directory (default: \$PX4_DIR/build/px4_sitl_nolockstep)
  --workdir DIR           PX4's working directory: parameters, dataman (default: a new temporary one)
  --params FILE           HITL parameter file (default: base/contract/hitl-defaults.params)
  --hil-port N            primary instance, the HIL link (default 14560); --hil-remote-port (14550)
  --onboard-port N        secondary instance (default 14556); --onboard-remote-port (14557)
  --gcs-port N            tertiary instance (default 14558); --gcs-remote-port (14559)
  --instance N            PX4 instance number (default 0); PX4's own clients need --instance N
  --daemon                no console; stop with SIGINT/SIGTERM
  -h, --help              this text
EOF
}

die() {
	echo "run-hitl-sitl: $1" >&2
	exit 2
}

port() { # name value
	if ! [[ "$2" =~ ^[0-9]+$ ]] || ((10#$2 < 1 || 10#$2 > 65535)); then
		die "$1 must be a UDP port 1..65535, not '$2'"
	fi
	echo $((10#$2))
}

px4_build="${PX4_DIR:+$PX4_DIR/build/px4_sitl_nolockstep}"
workdir=""
params="$(dirname "$(dirname "$target_px4")")/base/contract/hitl-defaults.params"
hil_port=14560 hil_remote_port=14550
onboard_port=14556 onboard_remote_port=14557
gcs_port=14558 gcs_remote_port=14559
instance=0
daemon=""

while [ $# -gt 0 ]; do
	opt="$1"
	case "$opt" in
	-h | --help) usage; exit 0 ;;
	--daemon) daemon="-d"; shift; continue ;;
	esac
	[ $# -ge 2 ] || die "$opt needs a value (see --help)"
	value="$2"
	shift 2
	case "$opt" in
	--px4-build) px4_build="$value" ;;
	--workdir) workdir="$value" ;;
	--params) params="$value" ;;
	--hil-port) hil_port="$(port "$opt" "$value")" ;;
	--hil-remote-port) hil_remote_port="$(port "$opt" "$value")" ;;
	--onboard-port) onboard_port="$(port "$opt" "$value")" ;;
	--onboard-remote-port) onboard_remote_port="$(port "$opt" "$value")" ;;
	--gcs-port) gcs_port="$(port "$opt" "$value")" ;;
	--gcs-remote-port) gcs_remote_port="$(port "$opt" "$value")" ;;
	--instance)
		[[ "$value" =~ ^[0-9]+$ ]] || die "--instance must be a number, not '$value'"
		instance="$value"
		;;
	*) die "unknown option '$opt' (see --help)" ;;
	esac
done

[ -n "$px4_build" ] || die "no PX4 build: give --px4-build DIR or set PX4_DIR (docs/px4-module.md)"
[ -x "$px4_build/bin/px4" ] || die "$px4_build/bin/px4 does not exist or is not executable: not a PX4 SITL build directory"
[ -d "$px4_build/etc/init.d" ] || die "$px4_build/etc has no init.d: not a PX4 SITL build directory"
[ -e "$px4_build/bin/px4-dsp_hitl" ] ||
	die "$px4_build has no dsp_hitl: build PX4 with target/px4 as EXTERNAL_MODULES_LOCATION (cmake --build <hitl build> --target px4_hitl)"
if [ -f "$px4_build/build.ninja" ] && grep -q -- "-DENABLE_LOCKSTEP_SCHEDULER" "$px4_build/build.ninja"; then
	die "$px4_build is a lockstep build: its clock only advances with a simulator module; build px4_sitl_nolockstep"
fi
[ -r "$params" ] || die "cannot read the parameter file $params"
ports=("$hil_port" "$onboard_port" "$gcs_port")
[ "$(printf '%s\n' "${ports[@]}" | sort -u | wc -l)" -eq 3 ] || die "--hil-port, --onboard-port and --gcs-port must differ"

if [ -z "$workdir" ]; then
	workdir="$(mktemp -d "${TMPDIR:-/tmp}/hitl-sitl.XXXXXX")"
else
	mkdir -p "$workdir" || die "cannot create the working directory $workdir"
fi
workdir="$(cd "$workdir" && pwd)"
params="$(cd "$(dirname "$params")" && pwd)/$(basename "$params")"
px4_build="$(cd "$px4_build" && pwd)"

echo "run-hitl-sitl: PX4 $px4_build, working directory $workdir, HIL link UDP $hil_port" >&2

export HITL_PARAMS_FILE="$params"
export HITL_HIL_PORT="$hil_port" HITL_HIL_REMOTE_PORT="$hil_remote_port"
export HITL_ONBOARD_PORT="$onboard_port" HITL_ONBOARD_REMOTE_PORT="$onboard_remote_port"
export HITL_GCS_PORT="$gcs_port" HITL_GCS_REMOTE_PORT="$gcs_remote_port"

# PX4's clock without lockstep is the host's CLOCK_MONOTONIC, and its IMU integration (VehicleIMU)
# takes the first sample as spanning from time 0. Below 2^32 us of host uptime (71.6 min) its
# integrator accepts that as one sample minutes long and EKF2 stalls on it ("ekf2 missing data"
# at arming); above, the integrator's DT_MAX check discards it. So on a host up less than two hours
# PX4 runs in a time namespace whose clock starts at two hours: the script's own process joins it
# (nsenter --time, then exec: PX4 keeps this PID and gets its signals).
min_clock_s=7200
time_namespace=()
uptime_s="$(cut -d. -f1 /proc/uptime)"
if [ "$uptime_s" -lt "$min_clock_s" ]; then
	offset_s=$((min_clock_s - uptime_s))
	for user_ns in "" "--user --map-root-user"; do
		# The namespace's first process (a sleep, detached: not a child of PX4) holds it until PX4 is in.
		# shellcheck disable=SC2086 # $user_ns is empty or two options
		holder="$( (unshare $user_ns --time --monotonic "$offset_s" --boottime "$offset_s" --fork sleep 10 \
			</dev/null >/dev/null 2>&1 & echo $!))"
		clock_pid=""
		for _ in $(seq 1 40); do
			clock_pid="$(pgrep -P "$holder" 2>/dev/null || true)"
			[ -n "$clock_pid" ] || ! kill -0 "$holder" 2>/dev/null && break
			sleep 0.05
		done
		if [ -n "$clock_pid" ]; then
			if [ -z "$user_ns" ]; then
				time_namespace=(nsenter --time --target "$clock_pid" --)
			else
				time_namespace=(nsenter --user --preserve-credentials --time --target "$clock_pid" --)
			fi
			"${time_namespace[@]}" true 2>/dev/null && break
			time_namespace=()
		fi
		kill "$holder" 2>/dev/null || true
	done
	if [ ${#time_namespace[@]} -gt 0 ]; then
		echo "run-hitl-sitl: the host has been up ${uptime_s} s: PX4's clock starts at ${min_clock_s} s (a time namespace)" >&2
	else
		echo "run-hitl-sitl: warning: the host has been up ${uptime_s} s (< 4295 s) and no time namespace can be made here" \
			"(unshare --time): EKF2 may stall on PX4's first IMU sample until the host has been up 72 minutes" >&2
	fi
fi

cd "$workdir"
# shellcheck disable=SC2086 # $daemon is empty or -d
exec "${time_namespace[@]}" "$px4_build/bin/px4" $daemon -i "$instance" -w "$workdir" -s "$here/rcS.hitl" "$px4_build/etc"
