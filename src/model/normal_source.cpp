#include "acc_identification/model/normal_source.h"

#include <cmath>

namespace acc
{
namespace
{
constexpr double kTwoPi = 6.283185307179586476925;
}  // namespace

NormalSource::NormalSource(std::uint64_t seed) : engine_(seed) {}

double NormalSource::uniformOpenClosed()
{
  // 53 random bits scaled to (0, 1]: exact in a double, and 0 excluded for the logarithm.
  return (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;
}

double NormalSource::standardNormal()
{
  if (has_spare_)
  {
    has_spare_ = false;
    return spare_;
  }
  const double radius = std::sqrt(-2.0 * std::log(uniformOpenClosed()));
  const double angle = kTwoPi * uniformOpenClosed();
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

std::uint64_t streamSeed(std::uint64_t seed, std::uint64_t stream)
{
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace acc
