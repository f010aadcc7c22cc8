#!/usr/bin/env bash
# A stand-in for adb in the tests (docs/adb.md, "How it is tested"): the "board" is this machine.
# It records every call, lists the devices it is told to, answers `forward tcp:0 tcp:REMOTE` with the
# port the relay listens on here, copies what is pushed under a device root, and runs `shell`
# commands here, with the device's PATH and the pushed relay's path mapped under that root.
#
#   FAKE_ADB_LOG         file that receives one line per call: the arguments (required)
#   FAKE_ADB_DEVICES     "SERIAL STATE;SERIAL STATE" (default "FAKE0001 device"; empty: none)
#   FAKE_ADB_ROOT        the device's file system root for pushed files, and the relay's log
#   FAKE_ADB_RELAY_PORT  the TCP port the relay listens on here (what `forward` prints)
#   FAKE_ADB_RELAY_ARGS  more relay options for this machine (its UDP targets, source ports)
#   FAKE_ADB_CONNECT     "refuse": `adb connect HOST:PORT` fails as adb does (exit 0, "failed to connect")
#
# `shell` commands see the board's files under the device root: /etc/modalai, /data and
# /tmp/hitl-board in a command are rewritten to $FAKE_ADB_ROOT/etc/modalai, ... (hitl board's
# files); the stand-in board programs (fake_board.sh: dpkg, systemctl, ...) sit in $FAKE_ADB_ROOT/bin.
set -u
log="${FAKE_ADB_LOG:?FAKE_ADB_LOG must name the file that records the calls}"
printf '%s\n' "$*" >> "$log"
root="${FAKE_ADB_ROOT:-/nonexistent}"
devices="${FAKE_ADB_DEVICES-FAKE0001 device}"

serial=""
if [ "${1:-}" = "-s" ]; then
  serial="${2:-}"
  shift 2
fi

# The one device this call addresses, like adb: "error: ..." on stderr and exit 1 otherwise.
check_device() {
  local ready=() entry s st
  IFS=';' read -ra entries <<< "$devices"
  for entry in "${entries[@]}"; do
    read -r s st <<< "$entry"
    [ -z "${s:-}" ] && continue
    if [ -n "$serial" ] && [ "$s" = "$serial" ]; then
      [ "$st" = "device" ] && return 0
      echo "error: device $st" >&2
      exit 1
    fi
    [ "$st" = "device" ] && ready+=("$s")
  done
  if [ -n "$serial" ]; then
    echo "error: device '$serial' not found" >&2
    exit 1
  fi
  if [ ${#ready[@]} -eq 0 ]; then
    echo "error: no devices/emulators found" >&2
    exit 1
  fi
  if [ ${#ready[@]} -gt 1 ]; then
    echo "error: more than one device/emulator" >&2
    exit 1
  fi
}

case "${1:-}" in
  devices)
    echo "List of devices attached"
    IFS=';' read -ra entries <<< "$devices"
    for entry in "${entries[@]}"; do
      read -r s st <<< "$entry"
      [ -n "${s:-}" ] && printf '%s\t%s\n' "$s" "$st"
    done
    echo
    ;;
  connect)
    if [ "${FAKE_ADB_CONNECT:-}" = refuse ]; then
      echo "failed to connect to '${2:-}': Connection refused"
    else
      echo "connected to ${2:-}"
    fi
    ;;
  forward)
    check_device
    if [ "${2:-}" = "--remove" ]; then exit 0; fi
    if [ "${2:-}" != "tcp:0" ]; then
      echo "fake adb: only 'forward tcp:0 tcp:PORT' is emulated, not '$*'" >&2
      exit 1
    fi
    echo "${FAKE_ADB_RELAY_PORT:?FAKE_ADB_RELAY_PORT must be set for forward}"
    ;;
  push)
    check_device
    src="${2:?push needs a source}"
    dst="$root${3:?push needs a destination}"
    mkdir -p "$(dirname "$dst")" && cp "$src" "$dst" || exit 1
    echo "$src: 1 file pushed, 0 skipped."
    ;;
  shell)
    check_device
    shift
    cmd="$*"
    cmd="${cmd//\/tmp\/hitl-adb-relay/$root/tmp/hitl-adb-relay}"
    cmd="${cmd//\/tmp\/hitl-board/$root/tmp/hitl-board}"
    cmd="${cmd//\/etc\/modalai/$root/etc/modalai}"
    cmd="${cmd//\/data\//$root/data/}"
    if [[ "$cmd" == *hitl-adb-relay*--daemon* ]]; then
      cmd="$cmd --port ${FAKE_ADB_RELAY_PORT:?} --log $root/relay.log ${FAKE_ADB_RELAY_ARGS:-}"
    fi
    PATH="$root/bin:/usr/bin:/bin" sh -c "$cmd" > "$root/shell.out.tmp" 2>&1
    code=$?
    cat "$root/shell.out.tmp"
    cat "$root/shell.out.tmp" >> "$root/shell.out"
    exit $code
    ;;
  *)
    echo "fake adb: '$*' is not emulated" >&2
    exit 1
    ;;
esac
