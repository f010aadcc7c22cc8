#!/usr/bin/env bash
# The README's first command: install dependencies, build hitl, and run its demonstration.
# No board, no network, no configuration needed: everything stays on 127.0.0.1.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DHITL_BUILD_TESTS=OFF -DHITL_BUILD_BENCH=OFF >/dev/null
cmake --build build -j"$(nproc)" --target hitl
hitl=build/cli/hitl

echo
echo "== The spec's Phase 1 (host side only): hitl sim sends HIL_SENSOR/HIL_GPS to 14560 and ODOMETRY"
echo "   to 14570 for 5 s; two hitl inspect processes stand in for the board and the VIO server."
echo "   (No flight stack answers, so hitl sim says so after 2 s: that is expected here.)"
$hitl inspect --port 14570 --duration 4 --expect ODOMETRY=250 > build/demo-vio.txt &
vio=$!
$hitl inspect --port 14560 --duration 4 --expect HIL_SENSOR=250,HIL_GPS=30 --show HIL_SENSOR > build/demo-hil.txt &
hil=$!
sleep 0.5
$hitl sim --duration 5 --record build/demo-session.tlog
status=0
wait $vio || status=1
wait $hil || status=1
echo
echo "== What the board's port saw (hitl inspect --port 14560):"
cat build/demo-hil.txt
echo
echo "== What the VIO port saw (hitl inspect --port 14570):"
tail -n 2 build/demo-vio.txt
echo
echo "== The session's recording, analysed offline (hitl inspect --tlog build/demo-session.tlog):"
$hitl inspect --tlog build/demo-session.tlog | tail -n 12
echo
echo "The binary is build/cli/hitl. With a board: build/cli/hitl sim -i 192.168.101.2 (see docs/sim.md)."
exit $status
