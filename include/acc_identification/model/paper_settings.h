#pragma once

#include <optional>
#include <string>
#include <vector>

#include "acc_identification/model/acc_parameters.h"

namespace acc
{
/// A named parameter set with where it comes from.
struct NamedSetting
{
  std::string name;
  std::string source;
  AccParameters parameters;
};

/// Table II of Gunter et al.: the minimum following setting.
AccParameters paperMinimumSetting();
/// Table II of Gunter et al.: the maximum following setting.
AccParameters paperMaximumSetting();
/// Section II-B, Fig. 2: k1 = k2 = 0.5, eta = 8 with the given effective time gap.
AccParameters paperFigure2Setting(double tau_e_s);

/// All named settings the tools accept by name ("min", "max", "fig2-unstable", "fig2-stable").
std::vector<NamedSetting> namedSettings();
std::optional<NamedSetting> findNamedSetting(const std::string& name);

}  // namespace acc
