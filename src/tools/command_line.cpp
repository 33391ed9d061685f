#include "acc_identification/command_line.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace acc
{
namespace
{
bool contains(const std::vector<std::string>& names, const std::string& name)
{
  return std::find(names.begin(), names.end(), name) != names.end();
}
}  // namespace

CommandLine::CommandLine(std::vector<std::string> value_options, std::vector<std::string> flag_options)
  : value_options_(std::move(value_options)), flag_options_(std::move(flag_options))
{
}

bool CommandLine::parse(int argc, char** argv)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string argument = argv[i];
    if (argument.rfind("--", 0) != 0 || argument == "--")
    {
      positional_.push_back(argument);
      continue;
    }
    std::string name = argument.substr(2);
    std::optional<std::string> inline_value;
    const auto equals = name.find('=');
    if (equals != std::string::npos)
    {
      inline_value = name.substr(equals + 1);
      name = name.substr(0, equals);
    }
    if (contains(flag_options_, name) && !inline_value)
    {
      given_[name].push_back("");
    }
    else if (contains(value_options_, name))
    {
      if (!inline_value && i + 1 >= argc)
      {
        error_ = "option --" + name + " needs a value";
        return false;
      }
      given_[name].push_back(inline_value ? *inline_value : argv[++i]);
    }
    else
    {
      error_ = "unknown option --" + name;
      return false;
    }
  }
  return true;
}

bool CommandLine::has(const std::string& name) const { return given_.count(name) > 0; }

std::optional<std::string> CommandLine::value(const std::string& name) const
{
  const auto found = given_.find(name);
  if (found == given_.end())
  {
    return std::nullopt;
  }
  return found->second.back();
}

std::vector<std::string> CommandLine::values(const std::string& name) const
{
  const auto found = given_.find(name);
  return found == given_.end() ? std::vector<std::string>{} : found->second;
}

std::optional<double> CommandLine::number(const std::string& name)
{
  const auto text = value(name);
  if (!text)
  {
    return std::nullopt;
  }
  char* end = nullptr;
  const double parsed = std::strtod(text->c_str(), &end);
  if (text->empty() || end != text->c_str() + text->size() || !std::isfinite(parsed))
  {
    error_ = "option --" + name + " expects a finite number, got '" + *text + "'";
    return std::nullopt;
  }
  return parsed;
}

}  // namespace acc
