#include "eval/synthetic/random.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace symembed {

namespace {

uint64_t SplitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

uint32_t DeriveSeed(uint64_t seed, const std::string& label, uint64_t a, uint64_t b) {
  uint64_t h = SplitMix64(seed);
  for (unsigned char c : label) h = SplitMix64(h ^ c);
  h = SplitMix64(h ^ a);
  h = SplitMix64(h ^ b);
  return static_cast<uint32_t>(h >> 32);
}

double SynthRandom::Uniform() {
  const uint64_t hi = engine_() >> 5;  // 27 bits
  const uint64_t lo = engine_() >> 6;  // 26 bits
  return static_cast<double>((hi << 26) | lo) * (1.0 / 9007199254740992.0);  // / 2^53
}

int SynthRandom::Index(int n) {
  SYMEMBED_CHECK(n >= 1, "Index needs n >= 1, got " << n);
  const uint32_t range = static_cast<uint32_t>(n);
  const uint32_t limit = 0xffffffffu - (0xffffffffu % range + 1) % range;  // largest multiple - 1
  uint32_t x;
  do {
    x = static_cast<uint32_t>(engine_());
  } while (x > limit);
  return static_cast<int>(x % range);
}

Eigen::Vector3d RandomUnitVector(uint32_t seed) {
  SynthRandom random(seed);
  const double z = random.Uniform(-1.0, 1.0), phi = random.Uniform(0.0, 2.0 * M_PI);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), z);
}

}  // namespace symembed
