#pragma once

#include <cstdint>
#include <random>

namespace acc
{
/// Standard normal numbers from std::mt19937_64 through our own Box-Muller transform, so that a
/// seed gives the same numbers with every standard library (std::normal_distribution is not
/// specified bit for bit and differs between libstdc++ and libc++; so do the other standard
/// distributions). Every seeded noise of the package (synthetic runs and drives, the withheld
/// suite, tests and benchmarks) draws from it, so that seeded data are the same on every platform.
class NormalSource
{
public:
  explicit NormalSource(std::uint64_t seed);

  /// Uniform on (0, 1]: the top 53 bits of one engine draw (never 0, so log() is finite).
  double uniformOpenClosed();
  /// N(0, 1). Box-Muller makes two numbers per pair of uniforms; the second is kept for the next call.
  double standardNormal();

private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

/// An independent stream's seed from the user's seed and a stream number (SplitMix64 mixing), so
/// that each noise source (e.g. each receiver) has its own numbers and adding a stream does not
/// shift the others.
std::uint64_t streamSeed(std::uint64_t seed, std::uint64_t stream);

}  // namespace acc
