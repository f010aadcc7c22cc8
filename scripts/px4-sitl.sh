#!/usr/bin/env bash
# Builds PX4 v1.16.0 SITL, the flight stack hitl's PX4 tests fly, from a PX4 tree laid out as
# docs/sim.md "Building PX4 SITL" says (PX4-Autopilot at v1.16.0 with the five submodules SITL needs put in place).
# PX4 is not part of hitl: build it outside this repository, then point the tests at it:
#   scripts/px4-sitl.sh ~/px4/PX4-Autopilot            # build/px4_sitl_default (lockstep)
#   scripts/px4-sitl.sh ~/px4/PX4-Autopilot --nolockstep   # build/px4_sitl_nolockstep too (HITL over UDP)
#   HITL_PX4_DIR=~/px4/PX4-Autopilot ctest -L px4
# It installs PX4's Python and build packages from Debian (install-deps.sh --px4), switches off in
# boards/px4/sitl/default.px4board the modules that need submodules SITL does not use, and builds
# with Ninja on every core. It never fetches anything: a missing submodule is named and it stops.
set -euo pipefail
usage() {
  echo "usage: scripts/px4-sitl.sh PX4_TREE [--nolockstep] [-j N]" >&2
  exit 2
}
[ $# -ge 1 ] || usage
tree=$1
shift
nolockstep=0
jobs=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --nolockstep) nolockstep=1 ;;
    -j) [ $# -ge 2 ] || usage; jobs=$2; shift ;;
    *) usage ;;
  esac
  shift
done

fail() {
  echo "px4-sitl: $tree: $*" >&2
  exit 2
}
[ -d "$tree" ] || fail "no such folder"
if [ ! -f "$tree/boards/px4/sitl/default.px4board" ] || [ ! -f "$tree/Tools/px4moduledoc/srcparser.py" ]; then
  fail "not a PX4-Autopilot tree (no boards/px4/sitl/default.px4board or Tools/px4moduledoc)"
fi
# The submodules SITL needs (docs/sim.md "Building PX4 SITL"): each must hold files.
for sub in src/modules/mavlink/mavlink/message_definitions src/modules/mavlink/mavlink/pymavlink/generator \
           src/lib/events/libevents/libs src/drivers/gps/devices/src src/lib/heatshrink/heatshrink; do
  [ -n "$(ls -A "$tree/$sub" 2>/dev/null)" ] || fail "the submodule folder $sub is empty or missing (docs/sim.md "Building PX4 SITL" lists the five and their commits)"
done
# PX4's build depends on each submodule's .git (cmake/px4_git.cmake); a snapshot put in place has
# none. An empty folder stands for it: git skips it as no repository, and GIT_SUBMODULES_ARE_EVIL
# keeps PX4 from updating anything.
for sub in src/modules/mavlink/mavlink src/drivers/gps/devices src/lib/events/libevents src/lib/heatshrink/heatshrink; do
  [ -e "$tree/$sub/.git" ] || mkdir "$tree/$sub/.git"
done
if git -C "$tree" rev-parse --git-dir >/dev/null 2>&1; then
  described=$(git -C "$tree" describe --tags --always 2>/dev/null || true)
  case "$described" in
    v1.16.0*) ;;
    *) echo "px4-sitl: warning: $tree describes itself as '$described', not v1.16.0: PX4 reports that version (tag the commit v1.16.0 if it is 6ea35391)" >&2 ;;
  esac
fi

"$(dirname "$0")/install-deps.sh" --px4

# Modules whose sources are submodules SITL does not need (or Gazebo): off, so the build needs
# only the five above. Idempotent.
board=$tree/boards/px4/sitl/default.px4board
for module in GYRO_FFT UXRCE_DDS_CLIENT SIMULATION_GZ_MSGS SIMULATION_GZ_BRIDGE SIMULATION_GZ_PLUGINS; do
  sed -i "s/^CONFIG_MODULES_${module}=y$/CONFIG_MODULES_${module}=n/" "$board"
done

# Debian's Python with its packages first (a pyenv or venv python lacks them); PX4's build must not
# try to update submodules over the network.
export PATH=/usr/bin:$PATH GIT_SUBMODULES_ARE_EVIL=1
unset PX4_SIM_HOSTNAME PX4_SIM_HOST_ADDR
configs=(px4_sitl_default)
[ $nolockstep -eq 1 ] && configs+=(px4_sitl_nolockstep)
for config in "${configs[@]}"; do
  cmake -S "$tree" -B "$tree/build/$config" -G Ninja -DCONFIG="$config" >/dev/null
  ninja -C "$tree/build/$config" -j"$jobs"
  [ -x "$tree/build/$config/bin/px4" ] || fail "the build of $config made no bin/px4"
  echo "px4-sitl: built $tree/build/$config"
done
echo "px4-sitl: HITL_PX4_DIR=$tree"
