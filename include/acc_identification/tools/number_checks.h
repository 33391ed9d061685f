#pragma once

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/model/acc_parameters.h"

namespace acc
{
/// Checks of the tools' number options whose error a user can read. CLI11 2.1's PositiveNumber and
/// NonNegativeNumber are ranges whose error prints the range's ends in full ("not in range
/// 0.000000 to 179769313486231570814527423731704356798..."), and its Range prints six decimals, so
/// (1e-9, 1 - 1e-9) read "0 not in range 0.000000 to 1.000000".
namespace number_checks
{
/// A bound as a user wrote it: 0.5, 1, 1e-06, 4294967295.
inline std::string text(double value)
{
  std::ostringstream out;
  out << std::setprecision(15) << value;
  return out.str();
}

/// Finite numbers for which accepts(value) holds; the error says "must be <asks>, not <text>".
template <typename Accepts>
CLI::Validator finiteNumber(Accepts accepts, const std::string& asks, const std::string& name)
{
  return CLI::Validator(
      [accepts, asks](std::string& written) {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(written, value) || !std::isfinite(value))
          return "not a finite number: " + written;
        return accepts(value) ? std::string() : "must be " + asks + ", not " + written;
      },
      name);
}
}  // namespace number_checks

/// Any finite number, for an option whose range a library rule judges: NaN, which a caller would
/// take for "not given", is refused here.
inline CLI::Validator finiteNumber(const std::string& name)
{
  return number_checks::finiteNumber([](double) { return true; }, "", name);
}

/// A number above 0.
inline CLI::Validator positiveNumber()
{
  return number_checks::finiteNumber([](double value) { return value > 0.0; }, "above 0", "POSITIVE");
}

/// A number of 0 or more.
inline CLI::Validator nonNegativeNumber()
{
  return number_checks::finiteNumber([](double value) { return value >= 0.0; }, "0 or more", "NONNEGATIVE");
}

/// A gain or time gap of the model: 0 to kLargestModelGainOrTimeGap.
inline CLI::Validator modelGainOrTimeGap()
{
  return number_checks::finiteNumber(
      [](double value) { return value >= 0.0 && value <= kLargestModelGainOrTimeGap; },
      "0 to " + number_checks::text(kLargestModelGainOrTimeGap) + " (a gain or time gap of the model)", "NUMBER");
}

/// A whole number of 0 or more, for counts and seeds held unsigned: CLI11 would wrap -1 to the
/// largest unsigned value.
inline CLI::Validator nonNegativeWholeNumber()
{
  return number_checks::finiteNumber([](double value) { return value >= 0.0 && value == std::floor(value); },
                                     "a whole number 0 or more", "WHOLE");
}

/// A number of lower or more.
inline CLI::Validator atLeast(double lower, const std::string& name)
{
  return number_checks::finiteNumber([lower](double value) { return value >= lower; },
                                     number_checks::text(lower) + " or more", name);
}

/// A number from lower to upper, both included. CLI11's Range lets "nan" through (every comparison
/// with NaN is false): openacc_to_nmea --time-shift-s nan wrote NMEA without times, exit status 0.
inline CLI::Validator closedInterval(double lower, double upper, const std::string& name)
{
  return number_checks::finiteNumber([lower, upper](double value) { return value >= lower && value <= upper; },
                                     "from " + number_checks::text(lower) + " to " + number_checks::text(upper), name);
}

/// A number strictly between lower and upper (a level alpha: between 0 and 1).
inline CLI::Validator openInterval(double lower, double upper)
{
  return number_checks::finiteNumber([lower, upper](double value) { return value > lower && value < upper; },
                                     "above " + number_checks::text(lower) + " and below " + number_checks::text(upper),
                                     "(" + number_checks::text(lower) + ", " + number_checks::text(upper) + ")");
}
}  // namespace acc
