#include "acc_identification/reproduction/parameter_file.h"

#include "acc_identification/model/acc_parameters.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace acc
{
namespace
{
/// A model parameter of the file; gains and time gaps must be 0 or more, the model's domain (a
/// negative one turns lambda2's sign against |Gamma| and the figures' platoons run away).
double requireNumber(const nlohmann::json& parameters, const char* key, const std::string& path,
                     bool non_negative = false)
{
  if (!parameters.contains(key) || !parameters[key].is_number())
  {
    throw ParameterFileError(path + ": \"parameters\"." + key + " is missing or not a number");
  }
  const double value = parameters[key].get<double>();
  if (!std::isfinite(value))
  {
    throw ParameterFileError(path + ": \"parameters\"." + key + " is not finite");
  }
  if (non_negative && !(value >= 0.0 && value <= kLargestModelGainOrTimeGap))
  {
    throw ParameterFileError(path + ": \"parameters\"." + key + " is " + nlohmann::json(value).dump() +
                             ": the model's gains and time gap are 0 to " +
                             nlohmann::json(kLargestModelGainOrTimeGap).dump());
  }
  return value;
}

std::string fileStem(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}
}  // namespace

NamedSetting readParameterFile(const std::string& path)
{
  if (std::filesystem::is_directory(path))
  {
    throw ParameterFileError(path + ": is a folder, not a calibrate JSON");
  }
  std::ifstream in(path);
  if (!in)
  {
    throw ParameterFileError(path + ": cannot open");
  }
  const nlohmann::json document = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded())
  {
    throw ParameterFileError(path + ": not valid JSON");
  }
  if (!document.is_object() || !document.contains("parameters") || !document["parameters"].is_object())
  {
    throw ParameterFileError(path + ": no \"parameters\" object (expected a calibrate JSON)");
  }
  // A model with effects (synthesize's truth with --effect): the figures simulate the paper's
  // law alone, so they would be another model's; said, not dropped.
  if (document.contains("effects") && !document["effects"].empty())
  {
    std::string names;
    if (document["effects"].is_object())
      for (const auto& effect : document["effects"].items())
        names += (names.empty() ? "" : ", ") + effect.key();
    throw ParameterFileError(path + ": the model holds effects beside its parameters (" +
                             (names.empty() ? document["effects"].dump() : names) +
                             "), which the figures do not simulate (the paper's law alone): they would not be this "
                             "model's; to draw its base law, give --k1 --k2 --tau-e [--eta]");
  }
  const nlohmann::json& parameters = document["parameters"];
  NamedSetting setting;
  setting.name = fileStem(path);
  setting.source = path;
  setting.parameters.k1_per_s2 = requireNumber(parameters, "k1_per_s2", path, true);
  setting.parameters.k2_per_s = requireNumber(parameters, "k2_per_s", path, true);
  setting.parameters.tau_e_s = requireNumber(parameters, "tau_e_s", path, true);
  setting.parameters.eta_m = requireNumber(parameters, "eta_m", path);
  return setting;
}

std::string describeUndeterminedParameterFile(const std::string& path)
{
  std::ifstream in(path);
  const nlohmann::json document = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded() || !document.is_object())
    return "";
  // The figures' dynamics are k1's, k2's and tau_e's: eta alone undetermined moves none of them.
  const nlohmann::json quantities =
      document.value("identifiable_quantities", nlohmann::json::object()).value("quantities", nlohmann::json());
  std::string reasons;
  for (const char* name : {"k1", "k2", "tau_e"})
  {
    const nlohmann::json q = quantities.is_object() ? quantities.value(name, nlohmann::json()) : nlohmann::json();
    if (q.is_object() && !q.value("determined", true))
      reasons += (reasons.empty() ? "" : "; ") + q.value("reason", std::string(name) + " not determined");
  }
  if (reasons.empty())
    return "";
  return path + ": the data it was fitted on do not determine its dynamics (" + reasons +
         "): the figure draws a point estimate they do not pin";
}

}  // namespace acc
