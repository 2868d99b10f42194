#pragma once
// Deterministic random numbers of our own: the same bytes on every library and platform (the
// std:: distributions differ between standard libraries), and one independent stream per named
// noise source, so that two runs with the same seed see the same wind and sensor noise whatever
// else they do differently (common random numbers, docs/swath-control.md).

#include <cstdint>
#include <string_view>

namespace swath::vehicle {

/// FNV-1a, 64 bit, of `text`: names a stream.
constexpr std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  return h;
}

/// SplitMix64 (Steele, Lea, Flood 2014): 64-bit state, passes BigCrush, trivially seeded.
class SplitMix64 {
 public:
  explicit constexpr SplitMix64(std::uint64_t seed) : state_(seed) {}

  /// The stream for noise source `name` under run seed `seed`: SplitMix64(seed ^ FNV-1a(name)).
  static constexpr SplitMix64 stream(std::uint64_t seed, std::string_view name) {
    return SplitMix64(seed ^ fnv1a(name));
  }

  constexpr std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n), n > 0, without modulo bias (Lemire's method).
  std::uint64_t below(std::uint64_t n);
  /// Standard normal N(0, 1): Marsaglia's polar method; the spare value is kept.
  double normal();
  /// Exponential with rate `rate_per_s` (> 0): the waiting time of a Poisson process, seconds.
  double exponential(double rate_per_s);

  std::uint64_t state() const { return state_; }

 private:
  std::uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace swath::vehicle
