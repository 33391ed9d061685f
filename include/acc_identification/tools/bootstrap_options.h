#pragma once

#include <cmath>
#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/calibration/refit_bootstrap.h"
#include "acc_identification/tools/number_checks.h"

namespace acc
{
/// 0 (no bootstrap) or kMinRefitsFor95Interval to 100000 replicates, whole numbers: a negative
/// count must not wrap to an unsigned one.
inline CLI::Validator bootstrapReplicates()
{
  const double fewest = static_cast<double>(kMinRefitsFor95Interval);
  return number_checks::finiteNumber(
      [fewest](double value) { return value == std::floor(value) && (value == 0.0 || (value >= fewest && value <= 1e5)); },
      "0 (none) or a whole number from " + number_checks::text(fewest) + " to 100000", "REPLICATES");
}

/// --bootstrap N and --bootstrap-below SECONDS: the refitting bootstrap (calibration/refit_bootstrap.h)
/// of `model` ("the fit", "the final model"), as calibrate and diagnose take it.
inline void addRefitBootstrapOptions(CLI::App& app, std::size_t& replicates, double& below_s, const std::string& model)
{
  app.add_option("--bootstrap", replicates,
                 "replicates of the refitting bootstrap of " + model +
                     " (95 % intervals that hold on short data; 0: none)")
      ->check(bootstrapReplicates())
      ->capture_default_str();
  app.add_option("--bootstrap-below", below_s,
                 "make it when the fitted data span less than SECONDS (longer data: value +- t se covers)")
      ->check(nonNegativeNumber())
      ->capture_default_str();
}
}  // namespace acc
