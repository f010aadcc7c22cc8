#!/usr/bin/env bash
# The VOXL2's programs hitl board runs, for the tests (tests/support/fake_adb.h, FakeAdb::make_board):
# one script linked as dpkg, dpkg-query, systemctl, systemd-run, journalctl and voxl-px4-hitl under
# the device root's bin/. Each records its call as one line ("systemctl start voxl-vision-hub") in
# $FAKE_ADB_ROOT/board.log and acts on a state under $FAKE_ADB_ROOT/var/fake-board:
#   services/NAME   "enabled|disabled active|inactive" (no file: the unit does not exist)
#   packages/NAME   the installed version
#   NAME.journal    what a systemd-run unit printed (journalctl -u NAME)
#   FAKE_BOARD_FAIL a call line prefix that fails ("dpkg -i": dpkg says no, exit 1)
set -u
root="${FAKE_ADB_ROOT:?}"
state="$root/var/fake-board"
mkdir -p "$state/services" "$state/packages"
me="$(basename "$0")"
line="$me $*"
printf '%s\n' "$line" >> "$root/board.log"
if [ -n "${FAKE_BOARD_FAIL:-}" ] && [ "${line#"$FAKE_BOARD_FAIL"}" != "$line" ]; then
  echo "$me: error: the stand-in board was told to fail '$FAKE_BOARD_FAIL'" >&2
  exit 1
fi

svc() { cat "$state/services/$1" 2>/dev/null; }
set_svc() { printf '%s %s\n' "$2" "$3" > "$state/services/$1"; }

case "$me" in
  dpkg)
    op="$1"; shift
    case "$op" in
      -i)
        for f in "$@"; do
          [ -r "$f" ] || { echo "dpkg: error: cannot access archive '$f': No such file or directory" >&2; exit 2; }
          b="$(basename "$f" .deb)"; name="${b%%_*}"; rest="${b#*_}"; version="${rest%%_*}"
          echo "Unpacking $name ($version) ..."
          echo "$version" > "$state/packages/$name"
          if [ "$name" = voxl-hitl-vio-server ]; then
            [ -e "$state/services/$name" ] || set_svc "$name" disabled inactive
            mkdir -p "$root/etc/modalai"
            [ -e "$root/etc/modalai/voxl-hitl-vio-server.conf" ] ||
              printf '{\n\t"receiver_ip":\t"0.0.0.0",\n\t"receiver_port":\t14570\n}\n' > "$root/etc/modalai/voxl-hitl-vio-server.conf"
          fi
        done ;;
      -r|--purge)
        for name in "$@"; do
          rm -f "$state/packages/$name"
          if [ "$name" = voxl-hitl-vio-server ]; then
            rm -f "$state/services/$name"
            [ "$op" = --purge ] && rm -f "$root/etc/modalai/voxl-hitl-vio-server.conf"
          fi
        done ;;
      *) echo "fake dpkg: '$op' is not emulated" >&2; exit 2 ;;
    esac ;;
  dpkg-query)
    [ "${1:-}" = -W ] || { echo "fake dpkg-query: only -W" >&2; exit 2; }
    shift; code=0
    for name in "$@"; do
      if [ -e "$state/packages/$name" ]; then printf '%s\t%s\n' "$name" "$(cat "$state/packages/$name")"
      else echo "dpkg-query: no packages found matching $name" >&2; code=1; fi
    done
    exit $code ;;
  systemctl)
    op="$1"; shift
    case "$op" in
      daemon-reload) ;;
      reset-failed) [ -e "$state/services/$1" ] || { echo "Unit $1.service not loaded." >&2; exit 1; } ;;
      is-enabled)
        s="$(svc "$1")" || { echo "Failed to get unit file state for $1.service: No such file or directory" >&2; exit 1; }
        read -r en _ <<< "$s"; echo "$en"; [ "$en" = enabled ] ;;
      is-active)
        s="$(svc "$1")" || { echo inactive; exit 3; }
        read -r _ ac <<< "$s"; echo "$ac"; [ "$ac" = active ] || exit 3 ;;
      enable|disable|start|stop|restart)
        for name in "$@"; do
          s="$(svc "$name")" || { echo "Failed to $op $name.service: Unit $name.service not found." >&2; exit 5; }
          read -r en ac <<< "$s"
          case "$op" in
            enable) en=enabled ;; disable) en=disabled ;; start|restart) ac=active ;; stop) ac=inactive ;;
          esac
          set_svc "$name" "$en" "$ac"
        done ;;
      *) echo "fake systemctl: '$op' is not emulated" >&2; exit 2 ;;
    esac ;;
  systemd-run)
    unit="${1#--unit=}"; shift
    s="$(svc "$unit")" && case "$s" in *" active") echo "Failed to start transient service unit: Unit $unit.service already exists." >&2; exit 1 ;; esac
    prog="$(basename "$1")"; shift
    if "$prog" "$@" >> "$state/$unit.journal" 2>&1; then set_svc "$unit" disabled active; else set_svc "$unit" disabled inactive; fi
    echo "Running as unit: $unit.service" ;;
  journalctl)
    unit=""
    while [ $# -gt 0 ]; do [ "$1" = -u ] && unit="$2"; shift; done
    cat "$state/$unit.journal" 2>/dev/null ;;
  voxl-px4-hitl)
    echo "voxl-px4-hitl: [1/9] running on M0197"
    if [ -n "${FAKE_BOARD_PX4_ERROR:-}" ]; then echo "voxl-px4-hitl: error: $FAKE_BOARD_PX4_ERROR" >&2; fi ;;
  *) echo "fake board: '$me' is not emulated" >&2; exit 2 ;;
esac
