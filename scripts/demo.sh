#!/usr/bin/env bash
# The README's first command: install dependencies, build hitl, and run `hitl demo`: an emulated
# board and the simulator in lockstep fly docs/examples/square.json (takeoff, a 5 m square, land)
# and print a report. No board, no network, no configuration: everything stays on 127.0.0.1.
# Extra arguments go to `hitl demo` (e.g. --tui to watch it, --json for the numbers).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
# A fresh tree is configured for hitl alone (no tests, no benchmarks: quicker), with the build type
# ./scripts/test.sh uses, so that either command after the other reuses the objects. A build/ that exists
# (./scripts/test.sh's) is used as it is: the demo never changes its options.
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHITL_BUILD_TESTS=OFF -DHITL_BUILD_BENCH=OFF >/dev/null
fi
cmake --build build -j"$(nproc)" --target hitl
echo
echo "== hitl demo: an EMULATED VOXL2 board (not PX4) and the Simbody x500 fly a 5 m square"
exec build/cli/hitl demo "$@"
