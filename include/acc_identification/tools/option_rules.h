#pragma once

#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/tools/number_checks.h"

namespace acc
{
/// The ranges of the options that calibrate, diagnose and campaign share with the Python API, one
/// definition each: the tools check their command line with them, and the Python functions check
/// the same values with them (src/python/python_module.cpp), so that a value a tool refuses is
/// refused in a notebook with the same words instead of changing a result.

/// A whole number from lower to upper (counts and seeds held unsigned: -1 must not wrap).
inline CLI::Validator wholeNumberFrom(double lower, double upper, const std::string& name)
{
  return number_checks::finiteNumber(
      [lower, upper](double value) { return value == std::floor(value) && value >= lower && value <= upper; },
      "a whole number from " + number_checks::text(lower) + " to " + number_checks::text(upper), name);
}

/// Starts of a multistart fit: with none nothing is tried, and "every start diverged" would be a
/// false reason.
inline CLI::Validator multistartStarts()
{
  return wholeNumberFrom(1.0, 100000.0, "STARTS");
}

/// The level of a string-stability test.
inline CLI::Validator testLevel()
{
  return openInterval(0.0, 1.0);
}

/// Grid nodes per axis of calibrate's global check (2000^3 simulations would run for days).
inline CLI::Validator gridNodesPerAxis()
{
  return wholeNumberFrom(2.0, 1000.0, "NODES");
}

/// A seed held in 32 bits (diagnose's bootstrap draws).
inline CLI::Validator seed32()
{
  return wholeNumberFrom(0.0, 4294967295.0, "SEED");
}

/// How often the sequential verdict looks: each look refits the drive so far.
inline CLI::Validator verdictEverySeconds()
{
  return atLeast(1.0, "SECONDS");
}

/// The share of each run the diagnosis fits on (the rest is scored).
inline CLI::Validator trainFraction()
{
  return number_checks::finiteNumber([](double value) { return value >= 0.05 && value <= 0.95; },
                                     "from 0.05 to 0.95", "FRACTION");
}
}  // namespace acc
