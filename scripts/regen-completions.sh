#!/usr/bin/env bash
# Regenerates every file made from hitl's command-line model: the shell completions in
# completions/, the man page docs/hitl.1 and the config reference docs/config.md. Run it after
# adding or changing a command or an option (tests/completions fails until you do).
#
#   scripts/regen-completions.sh               # builds build/cli/hitl first
#   scripts/regen-completions.sh BUILD_DIR     # builds and uses BUILD_DIR/cli/hitl
#   scripts/regen-completions.sh path/to/hitl  # uses that binary as it is
#   cmake --build build --target regen-completions   # the same from CMake
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
arg="${1:-build}"

if [ -f "$arg" ] && [ -x "$arg" ]; then
  hitl="$arg"
else
  build="$arg"
  case "$build" in /*) ;; *) build="$root/$build" ;; esac
  if [ ! -f "$build/CMakeCache.txt" ]; then
    echo "regen-completions: $build is not a configured build directory (cmake -S $root -B $build first)," \
         "nor an executable hitl" >&2
    exit 2
  fi
  cmake --build "$build" --target hitl -j2 >&2
  hitl="$build/cli/hitl"
fi

# Write each file whole or not at all: a failing hitl leaves the committed file untouched.
generate() {
  local out="$1"
  shift
  local tmp
  tmp="$(mktemp "$out.XXXXXX")"
  if ! "$hitl" "$@" > "$tmp"; then
    rm -f "$tmp"
    echo "regen-completions: '$hitl $*' failed" >&2
    exit 1
  fi
  chmod 644 "$tmp"
  mv "$tmp" "$out"
  echo "wrote ${out#"$root"/}"
}

mkdir -p "$root/completions"
generate "$root/completions/hitl.bash" completion bash
generate "$root/completions/_hitl" completion zsh
generate "$root/completions/hitl.fish" completion fish
generate "$root/docs/hitl.1" reference man
generate "$root/docs/config.md" reference config
