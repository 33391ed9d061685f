#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/diagnosis/determined_effects.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// The parameter names of the base model with `effects`, in a fit's x order: k1_per_s2, k2_per_s,
/// tau_e_s, eta_m, then each effect's parameters. The keys of every JSON of such a fit.
std::vector<std::string> augmentedParameterNames(const std::vector<EffectKind>& effects);

/// The standard errors of a fit of the base model with `effects`, by parameter name (k1_per_s2,
/// k2_per_s, tau_e_s, eta_m, then each effect's parameters in order); null where not finite.
/// One schema for diagnose's models and the campaign's diagnosed models.
nlohmann::json standardErrorsJson(const std::vector<EffectKind>& effects, const std::vector<double>& standard_errors);

/// How precisely the data pin an effect's size: {value, standard_error, z, at_bound, determined}.
nlohmann::json effectSizeJson(const EffectSize& size);

}  // namespace acc
