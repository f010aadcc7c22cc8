#!/usr/bin/env bash
# The README's first command: install dependencies, build hitl, and run its demonstration.
# No board, no network, no configuration needed.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DHITL_BUILD_TESTS=OFF -DHITL_BUILD_BENCH=OFF >/dev/null
cmake --build build -j"$(nproc)" --target hitl make_sample_tlog

echo
echo "== hitl inspect on a recorded HITL link (a synthetic 5 s log: the simulator's HIL_SENSOR,"
echo "   HIL_GPS and ODOMETRY, and the board's HIL_ACTUATOR_CONTROLS and HEARTBEAT) =="
build/tools/make_sample_tlog build/sample-hil-link.tlog 5
build/cli/hitl inspect --tlog build/sample-hil-link.tlog --show HIL_SENSOR \
  --expect HIL_SENSOR=250,HIL_GPS=30,ODOMETRY=250,HIL_ACTUATOR_CONTROLS=200
echo
echo "The binary is build/cli/hitl. Next: build/cli/hitl inspect --port 14570 --duration 5 --expect ODOMETRY=250"
