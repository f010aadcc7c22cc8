// The fuzz targets' invariant check: a failed one traps, so libFuzzer keeps the input.
#pragma once

#define FUZZ_CHECK(cond)             \
  do {                               \
    if (!(cond)) __builtin_trap();   \
  } while (0)
