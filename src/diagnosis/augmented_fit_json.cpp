#include "acc_identification/diagnosis/augmented_fit_json.h"

#include <string>

#include "acc_identification/model/json_number.h"

namespace acc
{
std::vector<std::string> augmentedParameterNames(const std::vector<EffectKind>& effects)
{
  std::vector<std::string> names = {"k1_per_s2", "k2_per_s", "tau_e_s", "eta_m"};
  for (const std::string& name : effectParameterNames(effects))
  {
    names.push_back(name);
  }
  return names;
}

nlohmann::json standardErrorsJson(const std::vector<EffectKind>& effects, const std::vector<double>& standard_errors)
{
  const std::vector<std::string> names = augmentedParameterNames(effects);
  nlohmann::json e = nlohmann::json::object();
  for (std::size_t i = 0; i < names.size() && i < standard_errors.size(); ++i)
  {
    e[names[i]] = jsonNumber(standard_errors[i]);
  }
  return e;
}

nlohmann::json effectSizeJson(const EffectSize& size)
{
  return {{"value", jsonNumber(size.value)},
          {"standard_error", jsonNumber(size.standard_error)},
          {"z", jsonNumber(size.z)},
          {"at_bound", size.at_bound},
          {"determined", size.determined},
          {"bootstrap_interval_holds_none", size.bootstrap_interval_holds_none
                                                ? nlohmann::json(*size.bootstrap_interval_holds_none)
                                                : nlohmann::json(nullptr)}};
}

}  // namespace acc
