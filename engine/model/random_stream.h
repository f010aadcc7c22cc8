// Seeded random numbers: one independent stream per named consumer ("imu", "gps", "wind", ...),
// derived from the run's seed and the name, so adding a consumer never changes the others.
#pragma once

#include <cstdint>
#include <random>
#include <string_view>

namespace hitl::model {

/// The seed of stream `name` under run seed `seed` (FNV-1a of the name mixed by splitmix64).
std::uint64_t stream_seed(std::uint64_t seed, std::string_view name);

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::string_view name) : engine_(stream_seed(seed, name)) {}
  /// A standard normal draw, N(0, 1).
  double normal() { return normal_(engine_); }
  /// sigma * N(0, 1); draws nothing when sigma is 0, so zero noise gives exact values.
  double normal(double sigma) { return sigma == 0.0 ? 0.0 : sigma * normal_(engine_); }

 private:
  std::mt19937_64 engine_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

/// A first-order Gauss-Markov process x' = -x / tau + w, sampled exactly at any interval:
/// x <- phi x + sigma_d N(0,1), phi = exp(-dt/tau). Specified by its driving density
/// (random_walk, unit/s/sqrt(Hz)): sigma_d^2 = random_walk^2 tau / 2 (1 - exp(-2 dt / tau)).
/// (The Gazebo IMU plugin's bias model.)
double gauss_markov_step(double x, double dt_s, double tau_s, double random_walk, RandomStream& rng);

/// Driving density of a Gauss-Markov process with stationary sigma `sigma` and time constant tau.
double random_walk_for_stationary_sigma(double sigma, double tau_s);

}  // namespace hitl::model
