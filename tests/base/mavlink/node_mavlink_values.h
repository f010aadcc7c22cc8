// The node-mavlink conformance test's values: every field of a message filled from a seed, in four
// patterns (random bits, extremes, trailing zeros for v2 truncation, all zero). Deterministic.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <tuple>
#include <type_traits>

namespace hitl::mavlink::conformance {

struct Rng {
  uint64_t state;
  uint64_t next() {  // splitmix64
    uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
};

enum class Fill {
  Random,        ///< full-range random bits (finite floats incl. subnormals and -0), strings with a NUL
  Extremes,      ///< min/max/0/-1 integers, +-max/+-denorm/-0 floats, strings filling the whole array
  TrailingZero,  ///< random, but the second half of the fields (wire order) zero: v2 truncation
  AllZero,       ///< every field zero (see kAllZeroDeviation in node_mavlink_test.cpp)
};

inline const char* fill_name(Fill fill) {
  switch (fill) {
    case Fill::Random: return "random";
    case Fill::Extremes: return "extremes";
    case Fill::TrailingZero: return "trailing-zero";
    case Fill::AllZero: return "all-zero";
  }
  return "?";
}

template <class T>
T random_element(Rng& rng, Fill fill, std::size_t k) {
  if constexpr (std::is_same_v<T, float> || std::is_same_v<T, double>) {
    using Bits = std::conditional_t<std::is_same_v<T, float>, uint32_t, uint64_t>;
    if (fill == Fill::Extremes) {
      constexpr T kValues[] = {std::numeric_limits<T>::max(),        -std::numeric_limits<T>::max(),
                               std::numeric_limits<T>::denorm_min(), -std::numeric_limits<T>::denorm_min(),
                               T(-0.0),                              std::numeric_limits<T>::min(),
                               T(1.0),                               T(-1.0)};
      return kValues[k % std::size(kValues)];
    }
    constexpr int kMantissa = std::numeric_limits<T>::digits - 1;
    constexpr Bits kExpMask = ((Bits{1} << (sizeof(T) * 8 - 1 - kMantissa)) - 1) << kMantissa;
    Bits bits = static_cast<Bits>(rng.next());
    if ((bits & kExpMask) == kExpMask) bits &= ~(Bits{1} << (sizeof(T) * 8 - 2));  // Inf/NaN -> finite
    return std::bit_cast<T>(bits);
  } else {
    if (fill == Fill::Extremes) {
      const T kValues[] = {std::numeric_limits<T>::max(), std::numeric_limits<T>::min(), T(1),
                           static_cast<T>(std::numeric_limits<T>::max() - 1), static_cast<T>(-1)};
      return kValues[k % std::size(kValues)];
    }
    return static_cast<T>(rng.next());
  }
}

template <class T>
void fill_value(T& value, Rng& rng, Fill fill, std::size_t k) {
  value = random_element<T>(rng, fill, k);
}

template <class T, std::size_t N>
void fill_value(std::array<T, N>& values, Rng& rng, Fill fill, std::size_t k) {
  if constexpr (std::is_same_v<T, char>) {
    values.fill('\0');
    // Random: a string of 0..N-1 bytes (1..255) and its NUL. Extremes: all N bytes used, no NUL.
    const std::size_t len = fill == Fill::Extremes ? N : static_cast<std::size_t>(rng.next() % N);
    for (std::size_t i = 0; i < len; ++i) {
      const uint8_t byte = fill == Fill::Extremes ? static_cast<uint8_t>(0x20 + (k + i) % 95)
                                                  : static_cast<uint8_t>(1 + rng.next() % 255);
      values[i] = static_cast<char>(byte);
    }
  } else {
    for (std::size_t i = 0; i < N; ++i) values[i] = random_element<T>(rng, fill, k + i);
  }
}

template <class M>
M make_message(Fill fill, uint64_t seed) {
  M m{};
  if (fill == Fill::AllZero) return m;
  Rng rng{seed};
  constexpr std::size_t kFields = std::tuple_size_v<decltype(M::fields())>;
  std::size_t index = 0;
  std::apply(
      [&](const auto&... field) {
        auto one = [&](const auto& f) {
          const std::size_t i = index++;
          if (fill == Fill::TrailingZero && i >= (kFields + 1) / 2) return;  // stays zero
          fill_value(m.*(f.member), rng, fill, i);
        };
        (one(field), ...);
      },
      M::fields());
  return m;
}

}  // namespace hitl::mavlink::conformance
