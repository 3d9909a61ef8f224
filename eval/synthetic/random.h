// Platform-independent pseudo-random numbers for the synthetic benchmark.
//
// std::mt19937's output sequence is fixed by the C++ standard, but the standard distributions
// (std::uniform_real_distribution, ...) are not, so the generator converts raw engine output to
// numbers itself. Independent streams (per pose, per purpose) come from DeriveSeed, so that
// turning an option on (noise, say) does not change the numbers drawn for anything else.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <string>

namespace symembed {

// A 32-bit seed from a base seed and a path of labels (SplitMix64 mixing of each part).
uint32_t DeriveSeed(uint64_t seed, const std::string& label, uint64_t a = 0, uint64_t b = 0);

class SynthRandom {
 public:
  explicit SynthRandom(uint32_t seed) : engine_(seed) {}

  // Uniform in [0, 1) with 53 random bits (two engine outputs).
  double Uniform();
  // Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform integer in [0, n), n >= 1 (rejection sampling, no modulo bias).
  int Index(int n);

 private:
  std::mt19937 engine_;
};

// A unit vector uniform on the sphere, from its own stream.
Eigen::Vector3d RandomUnitVector(uint32_t seed);

}  // namespace symembed
