#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <random>

namespace acc
{
/// A uniform integer in [0, range) from one raw 64-bit draw of the engine (multiply-high: the
/// bias is below range / 2^64, negligible). std::uniform_int_distribution maps the draws
/// differently in each standard library; this gives the same numbers with all of them, so that
/// every seeded resampling of the package (MovingBlockBootstrap, the diagnosis's selection rule)
/// is reproducible anywhere. range must be at least 1.
inline std::uint64_t uniformBelow(std::mt19937_64& engine, std::uint64_t range)
{
  const unsigned __int128 product = static_cast<unsigned __int128>(engine()) * range;
  return static_cast<std::uint64_t>(product >> 64);
}

/// Fisher-Yates with uniformBelow: the same order from the same seed with every standard library
/// (std::shuffle's order is the library's own).
template <class Sequence>
void portableShuffle(Sequence& items, std::mt19937_64& engine)
{
  using std::swap;
  for (std::size_t i = items.size(); i > 1; --i)
  {
    swap(items[i - 1], items[static_cast<std::size_t>(uniformBelow(engine, i))]);
  }
}

}  // namespace acc
