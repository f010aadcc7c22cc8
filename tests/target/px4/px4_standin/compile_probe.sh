#!/bin/sh
# Compiler launcher of the px4 stand-in build: compile_probe.sh COMPILER ARGS..., with
# HITL_PROBE_LOG and HITL_PROBE_HEADER in the environment. Appends one line per compile to the log:
#   compile <TAB> SOURCE <TAB> present|absent (the header at that moment) <TAB> the compile's arguments
# then runs the same compile with an empty file in place of SOURCE (same flags, same object and
# dependency files), so the build graph runs to the end without PX4's headers.
set -eu
log=${HITL_PROBE_LOG:?HITL_PROBE_LOG is not set}
header=${HITL_PROBE_HEADER:?HITL_PROBE_HEADER is not set}

src=
prev=
for a in "$@"; do
	if [ "$prev" = "-c" ]; then src=$a; fi
	prev=$a
done
if [ -z "$src" ]; then
	exec "$@"
fi

state=absent
if [ -f "$header" ]; then state=present; fi
printf 'compile\t%s\t%s\t%s\n' "$src" "$state" "$*" >>"$log"

empty="$(dirname "$log")/probe_empty.${src##*.}"
: >"$empty"
prev=
for a in "$@"; do
	shift
	if [ "$prev" = "-c" ]; then set -- "$@" "$empty"; else set -- "$@" "$a"; fi
	prev=$a
done
exec "$@"
