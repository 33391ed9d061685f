#include "acc_identification/reproduction/figure_options.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/reproduction/parameter_file.h"

namespace acc
{
const std::vector<std::string>& figureValueOptions()
{
  static const std::vector<std::string> kValueOptions{
      "setting", "params", "k1", "k2", "tau-e", "eta", "time-step", "vehicles", "map-tau-e", "k1-max", "k2-max",
      "grid", "speed", "step", "step-down-at", "step-up-at", "duration", "min-frequency", "max-frequency", "points",
      "amplitude", "frequency", "lead-in", "fit-periods", "profile", "short-platoon", "tail", "lead-accel",
      "lead-decel", "run", "max-relative-speed", "max-acceleration", "train-fraction"};
  return kValueOptions;
}

double FigureOptions::number(const std::string& name, double fallback) const
{
  if (!has(name))
  {
    return fallback;
  }
  const std::string& text = single(name);
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0')
  {
    throw FigureUsageError("--" + name + ": '" + text + "' is not a number");
  }
  if (!std::isfinite(value))
  {
    throw FigureUsageError("--" + name + " must be finite");
  }
  return value;
}

double FigureOptions::positive(const std::string& name, double fallback) const
{
  const double value = number(name, fallback);
  if (!(value > 0.0))
  {
    throw FigureUsageError("--" + name + " must be positive");
  }
  return value;
}

double FigureOptions::between(const std::string& name, double fallback, double lower, double upper) const
{
  const double value = number(name, fallback);
  if (!(value >= lower && value <= upper))
  {
    std::ostringstream bounds;
    bounds << "--" << name << " must be from " << lower << " to " << upper << ", not " << value;
    throw FigureUsageError(bounds.str());
  }
  return value;
}

std::size_t FigureOptions::count(const std::string& name, std::size_t fallback, std::size_t minimum) const
{
  const double value = number(name, static_cast<double>(fallback));
  if (value < static_cast<double>(minimum) || value != std::floor(value) || value > 1e6)
  {
    throw FigureUsageError("--" + name + " must be a whole number >= " + std::to_string(minimum));
  }
  return static_cast<std::size_t>(value);
}

std::string FigureOptions::text(const std::string& name, const std::string& fallback) const
{
  return has(name) ? single(name) : fallback;
}

std::vector<std::string> FigureOptions::texts(const std::string& name) const
{
  return has(name) ? given_.at(name) : std::vector<std::string>{};
}

bool FigureOptions::has(const std::string& name) const
{
  read_.insert(name);
  return given_.count(name) > 0 && !given_.at(name).empty();
}

std::vector<std::string> FigureOptions::namesGiven() const
{
  std::vector<std::string> names;
  for (const auto& [name, values] : given_)
    if (!values.empty())
      names.push_back(name);
  return names;
}

const std::string& FigureOptions::single(const std::string& name) const
{
  const std::vector<std::string>& values = given_.at(name);
  if (values.size() > 1)
  {
    throw FigureUsageError("--" + name + " given " + std::to_string(values.size()) +
                           " times: which value is meant is not said (it takes one)");
  }
  return values.front();
}

std::vector<double> parseNumberList(const std::string& text, const std::string& option)
{
  std::vector<double> numbers;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(value))
    {
      throw FigureUsageError("--" + option + ": '" + item + "' is not a number");
    }
    numbers.push_back(value);
  }
  return numbers;
}

namespace
{
/// The custom set of --k1 --k2 --tau-e [--eta], when any of them is given.
void addCustomSetting(const FigureOptions& options, std::vector<NamedSetting>& settings)
{
  if (!options.has("k1") && !options.has("k2") && !options.has("tau-e") && !options.has("eta"))
  {
    return;
  }
  if (!options.has("k1") || !options.has("k2") || !options.has("tau-e"))
  {
    throw FigureUsageError("--k1, --k2 and --tau-e go together (--eta defaults to 0)");
  }
  // The model's domain, as stability_report and synthesize hold it.
  constexpr double kMost = kLargestModelGainOrTimeGap;
  settings.push_back({"custom", "command line",
                      {options.between("k1", 0.0, 0.0, kMost), options.between("k2", 0.0, 0.0, kMost),
                       options.between("tau-e", 0.0, 0.0, kMost), options.number("eta", 0.0)}});
}
}  // namespace

std::vector<NamedSetting> resolveSettings(const FigureOptions& options, const std::vector<std::string>& defaults)
{
  std::vector<NamedSetting> settings;
  for (const std::string& name : options.texts("setting"))
  {
    const auto found = findNamedSetting(name);
    if (!found)
    {
      throw FigureUsageError("unknown setting '" + name + "'");
    }
    settings.push_back(*found);
  }
  for (const std::string& path : options.texts("params"))
  {
    try
    {
      settings.push_back(readParameterFile(path));
    }
    catch (const ParameterFileError& error)
    {
      throw FigureUsageError(error.what());
    }
  }
  addCustomSetting(options, settings);
  for (const std::string& name : settings.empty() ? defaults : std::vector<std::string>{})
  {
    settings.push_back(*findNamedSetting(name));
  }
  return settings;
}

}  // namespace acc
