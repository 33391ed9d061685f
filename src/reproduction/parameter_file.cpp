#include "acc_identification/reproduction/parameter_file.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace acc
{
namespace
{
double requireNumber(const nlohmann::json& parameters, const char* key, const std::string& path)
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
  const nlohmann::json& parameters = document["parameters"];
  NamedSetting setting;
  setting.name = fileStem(path);
  setting.source = path;
  setting.parameters.k1_per_s2 = requireNumber(parameters, "k1_per_s2", path);
  setting.parameters.k2_per_s = requireNumber(parameters, "k2_per_s", path);
  setting.parameters.tau_e_s = requireNumber(parameters, "tau_e_s", path);
  setting.parameters.eta_m = requireNumber(parameters, "eta_m", path);
  return setting;
}

}  // namespace acc
