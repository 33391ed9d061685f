#pragma once

#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/tools/number_checks.h"

namespace acc
{
/// --bootstrap N and --bootstrap-below SECONDS: the refitting bootstrap (calibration/refit_bootstrap.h)
/// of `model` ("the fit", "the final model"), as calibrate and diagnose take it.
inline void addRefitBootstrapOptions(CLI::App& app, std::size_t& replicates, double& below_s, const std::string& model)
{
  app.add_option("--bootstrap", replicates,
                 "replicates of the refitting bootstrap of " + model +
                     " (95 % intervals that hold on short data; 0: none)")
      ->capture_default_str();
  app.add_option("--bootstrap-below", below_s,
                 "make it when the fitted data span less than SECONDS (longer data: value +- t se covers)")
      ->check(nonNegativeNumber())
      ->capture_default_str();
}
}  // namespace acc
