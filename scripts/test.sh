#!/usr/bin/env bash
# The README's second command (and CI's): install dependencies, build everything
# (hitl, tests, benchmarks, the libFuzzer target), and run every test with CTest.
# The options are given every time, so a build/ that ./scripts/demo.sh configured (hitl alone, no
# tests) gets its tests back; CTest fails when it finds no test instead of passing with none.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh --test
jobs=$(nproc)
# CI (CI=true, as .ci/run runs) builds hitl's own code with -Werror: no warning lands.
werror=()
if [ "${CI:-}" = "true" ]; then werror=(-DHITL_WERROR=ON); fi

fuzz_args=()
if [ -f tests/fuzz/CMakeLists.txt ]; then
  cmake -S . -B build/fuzz -DHITL_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build build/fuzz -j"$jobs"
  fuzz_args=(-DHITL_FUZZ_BUILD_DIR="$PWD/build/fuzz")
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHITL_BUILD_TESTS=ON -DHITL_BUILD_BENCH=ON \
  "${werror[@]}" "${fuzz_args[@]}" >/dev/null
cmake --build build -j"$jobs"
cd build
ctest --output-on-failure --no-tests=error -j"$jobs" --timeout 600
