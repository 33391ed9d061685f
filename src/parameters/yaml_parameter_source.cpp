#include "acc_identification/parameters/yaml_parameter_source.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include <yaml-cpp/yaml.h>

namespace acc
{
namespace
{
// PyYAML's implicit resolvers (yaml/resolver.py), which rosparam uses.
const std::regex kBool("yes|Yes|YES|no|No|NO|true|True|TRUE|false|False|FALSE|on|On|ON|off|Off|OFF");
const std::regex kInt("[-+]?0b[0-1_]+|[-+]?0[0-7_]+|[-+]?(?:0|[1-9][0-9_]*)|[-+]?0x[0-9a-fA-F_]+|"
                      "[-+]?[1-9][0-9_]*(?::[0-5]?[0-9])+");
const std::regex kFloat("[-+]?(?:[0-9][0-9_]*)\\.[0-9_]*(?:[eE][-+][0-9]+)?|\\.[0-9_]+(?:[eE][-+][0-9]+)?|"
                        "[-+]?[0-9][0-9_]*(?::[0-5]?[0-9])+\\.[0-9_]*|"
                        "[-+]?\\.(?:inf|Inf|INF)|\\.(?:nan|NaN|NAN)");
const std::regex kNull("~|null|Null|NULL|");

std::string withoutUnderscores(const std::string& text)
{
  std::string digits;
  for (char c : text)
    if (c != '_')
      digits += c;
  return digits;
}

/// A base-60 number as PyYAML reads it (1:30 is 90, 1:30.5 is 90.5): the parts from the last, each
/// worth 60 times the one after it. digits: unsigned, without underscores.
double sexagesimal(const std::string& digits)
{
  double number = 0.0;
  std::istringstream parts(digits);
  for (std::string part; std::getline(parts, part, ':');)
    number = 60.0 * number + std::strtod(part.c_str(), nullptr);
  return number;
}

/// An int as PyYAML reads it (0b binary, 0 octal, 0x hex, base 60 with colons, else decimal);
/// beyond an int: a double.
ParameterValue integerValue(const std::string& text)
{
  std::string digits = withoutUnderscores(text);
  const bool negative = !digits.empty() && digits[0] == '-';
  if (!digits.empty() && (digits[0] == '-' || digits[0] == '+'))
    digits.erase(0, 1);
  int base = 10;
  if (digits.find(':') != std::string::npos)
    base = 60;
  else if (digits.rfind("0b", 0) == 0)
    base = 2, digits.erase(0, 2);
  else if (digits.rfind("0x", 0) == 0)
    base = 16, digits.erase(0, 2);
  else if (digits.size() > 1 && digits[0] == '0')
    base = 8;
  const double magnitude =
      base == 60 ? sexagesimal(digits) : static_cast<double>(std::strtoull(digits.c_str(), nullptr, base));
  const double number = negative ? -magnitude : magnitude;
  ParameterValue value;
  if (std::abs(number) <= std::numeric_limits<int>::max())
  {
    value.type = ParameterValue::Type::kInt;
    value.integer = static_cast<int>(number);
  }
  else
  {
    value.type = ParameterValue::Type::kDouble;  // as the parameter server holds a Python long
    value.number = number;
  }
  return value;
}

ParameterValue floatValue(const std::string& text)
{
  ParameterValue value;
  value.type = ParameterValue::Type::kDouble;
  const std::string digits = withoutUnderscores(text);
  if (digits.find("nan") != std::string::npos || digits.find("NaN") != std::string::npos ||
      digits.find("NAN") != std::string::npos)
    value.number = std::numeric_limits<double>::quiet_NaN();
  else if (digits.find("inf") != std::string::npos || digits.find("Inf") != std::string::npos ||
           digits.find("INF") != std::string::npos)
    value.number = digits[0] == '-' ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  else if (digits.find(':') != std::string::npos)
    value.number = digits[0] == '-' ? -sexagesimal(digits.substr(1))
                                    : sexagesimal(digits[0] == '+' ? digits.substr(1) : digits);
  else
    value.number = std::strtod(digits.c_str(), nullptr);
  return value;
}

ParameterValue fromNode(const YAML::Node& node)
{
  ParameterValue value;
  if (node.IsSequence())
  {
    value.type = ParameterValue::Type::kList;
    for (const YAML::Node& item : node)
      value.items.push_back(fromNode(item));
  }
  else if (node.IsMap())
    value.type = ParameterValue::Type::kDictionary;
  else if (node.IsScalar() && node.Tag() == "?")
    value = resolveYamlScalar(node.Scalar());
  else if (node.IsScalar())
  {
    value.type = ParameterValue::Type::kString;  // quoted, or tagged: text as written
    value.text = node.Scalar();
  }
  return value;
}
}  // namespace

ParameterValue resolveYamlScalar(const std::string& text)
{
  ParameterValue value;
  if (std::regex_match(text, kNull))
    return value;
  if (std::regex_match(text, kBool))
  {
    value.type = ParameterValue::Type::kBool;
    value.boolean = text[0] == 'y' || text[0] == 'Y' || text[0] == 't' || text[0] == 'T' ||
                    text == "on" || text == "On" || text == "ON";
    return value;
  }
  if (std::regex_match(text, kInt))
    return integerValue(text);
  if (std::regex_match(text, kFloat))
    return floatValue(text);
  value.type = ParameterValue::Type::kString;
  value.text = text;
  return value;
}

YamlParameterSource YamlParameterSource::fromFile(const std::string& path)
{
  std::ifstream file(path);
  if (!file)
  {
    YamlParameterSource source;
    source.error_ = "cannot open parameter file " + path;
    return source;
  }
  std::ostringstream text;
  text << file.rdbuf();
  return fromText(text.str(), path);
}

YamlParameterSource YamlParameterSource::fromText(const std::string& text, const std::string& name)
{
  YamlParameterSource source;
  YAML::Node root;
  try
  {
    root = YAML::Load(text);
  }
  catch (const YAML::Exception& e)
  {
    source.error_ = name + ": not YAML: " + e.what();
    return source;
  }
  if (root.IsNull())
    return source;  // an empty file: no parameter set
  if (!root.IsMap())
  {
    source.error_ = name + ": not a mapping of parameter names to values";
    return source;
  }
  for (const auto& entry : root)
  {
    const std::string key = entry.first.Scalar();
    if (source.values_.count(key) > 0 &&
        std::find(source.repeated_.begin(), source.repeated_.end(), key) == source.repeated_.end())
      source.repeated_.push_back(key);
    source.values_[key] = fromNode(entry.second);
  }
  return source;
}

std::string YamlParameterSource::repeatedKeysNote() const
{
  if (repeated_.empty())
    return "";
  std::string keys;
  for (const std::string& key : repeated_)
    keys += (keys.empty() ? "" : ", ") + key;
  return "key(s) given more than once: " + keys + " (the last value of each is used, as rosparam loads it)";
}

std::optional<ParameterValue> YamlParameterSource::get(const std::string& name) const
{
  const auto found = values_.find(name);
  if (found == values_.end())
    return std::nullopt;
  return found->second;
}

std::vector<std::string> YamlParameterSource::names() const
{
  std::vector<std::string> all;
  for (const auto& entry : values_)
    all.push_back(entry.first);
  return all;
}

}  // namespace acc
