// Seeded randomness that gives the same numbers with every standard library.
//
// std::mt19937_64's output sequence is fixed by the C++ standard, its distributions are not
// (libstdc++ and libc++ draw normals differently), so the mapping to [0, 1) and the normal draw
// are written out here. Each simulated part owns its own generator, seeded by derive_seed from
// the run's seed and a stream number, so that adding draws in one part never shifts another's.
#pragma once

#include <cstdint>
#include <random>

namespace marsokhod::sim {

// SplitMix64 of seed + stream: independent-looking seeds for the parts of one run.
std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream);

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  // Uniform in [min, max).
  double uniform(double min, double max);
  // Normal by Box–Muller; two uniforms per call (no cached second value, so the stream of draws
  // depends only on the number of calls).
  double normal(double mean, double sigma);
  // true with probability p (p ≤ 0: never, p ≥ 1: always, without drawing in either case).
  bool bernoulli(double probability);

 private:
  std::mt19937_64 engine_;
};

}  // namespace marsokhod::sim
