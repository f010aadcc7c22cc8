#include "engine/model/random_stream.h"

#include <cmath>

namespace hitl::model {

std::uint64_t stream_seed(std::uint64_t seed, std::string_view name) {
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a 64
  for (char c : name) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  std::uint64_t z = seed ^ h;  // splitmix64 finaliser
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double gauss_markov_step(double x, double dt_s, double tau_s, double random_walk, RandomStream& rng) {
  const double phi = std::exp(-dt_s / tau_s);
  const double sigma_d = std::sqrt(random_walk * random_walk * tau_s / 2.0 * (1.0 - std::exp(-2.0 * dt_s / tau_s)));
  return phi * x + rng.normal(sigma_d);
}

double random_walk_for_stationary_sigma(double sigma, double tau_s) { return sigma * std::sqrt(2.0 / tau_s); }

}  // namespace hitl::model
