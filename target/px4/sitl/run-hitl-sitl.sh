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

cd "$workdir"
# shellcheck disable=SC2086 # $daemon is empty or -d
exec "$px4_build/bin/px4" $daemon -i "$instance" -w "$workdir" -s "$here/rcS.hitl" "$px4_build/etc"
