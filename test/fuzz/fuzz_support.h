#pragma once

// What every fuzzer of test/fuzz needs: an invariant check that stops the run with its words, and
// (for the fuzzers that build their input from choices) a number as a bad sender may send it.
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <fuzzer/FuzzedDataProvider.h>

namespace fuzz_support
{
/// Aborts with "invariant violated: what", which the hooks report as the finding.
inline void check(bool condition, const char* what)
{
  if (!condition)
  {
    std::fprintf(stderr, "invariant violated: %s\n", what);
    std::abort();
  }
}

/// A number as a receiver or a link may send it: usually in [low, high], sometimes NaN, an
/// infinity or anything a double can hold.
inline double field(FuzzedDataProvider& input, double low, double high)
{
  switch (input.ConsumeIntegralInRange<int>(0, 15))
  {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return input.ConsumeBool() ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    case 2:
      return input.ConsumeFloatingPoint<double>();
    default:
      return input.ConsumeFloatingPointInRange<double>(low, high);
  }
}
}  // namespace fuzz_support
