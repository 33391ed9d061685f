#include "acc_identification/parameters/parameter_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <utility>
#include <sstream>

namespace acc
{
namespace
{
/// True when the whole text reads as a number ("1e6"): the likely slip of an exponent YAML 1.1 and
/// roslaunch take for text.
bool looksNumeric(const std::string& text)
{
  if (text.empty())
    return false;
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0';
}
}  // namespace

bool ParameterReader::fetch(const std::string& name, ParameterValue& raw)
{
  read_.insert(name);
  if (!ok())
    return false;
  std::optional<ParameterValue> value = source_.get(name);
  if (!value)
    return false;
  raw = std::move(*value);
  return true;
}

std::string ParameterReader::unreadNote() const
{
  std::string unread;
  int count = 0;
  for (const std::string& name : source_.names())
  {
    if (read_.count(name) > 0)
      continue;
    unread += (count++ > 0 ? ", ~" : "~") + name;
  }
  if (count == 0)
    return "";
  return (count == 1 ? "parameter " + unread + " is" : "parameters " + unread + " are") +
         " set but never read (misspelt?): ignored";
}

bool ParameterReader::fail(const std::string& message)
{
  if (error_.empty())
    error_ = message;
  return false;
}

bool ParameterReader::require(bool condition, const std::string& message)
{
  return condition || fail(message);
}

bool ParameterReader::read(const std::string& name, double& value)
{
  ParameterValue raw;
  if (!fetch(name, raw))
    return ok();
  if (raw.type == ParameterValue::Type::kDouble)
  {
    value = raw.number;
    return true;
  }
  if (raw.type == ParameterValue::Type::kInt)
  {
    value = raw.integer;
    return true;
  }
  std::string message = "parameter ~" + name + " is " + raw.describe() + ", not a number";
  if (raw.type == ParameterValue::Type::kString && looksNumeric(raw.text))
  {
    // YAML 1.1 (rosparam, <rosparam>) reads an exponent as a number only with a dot and a sign, and
    // roslaunch's <param value> or arg:= only with a dot: 1e6 is text to both, 1.0e+6 a number to both.
    message += " (1e6 is text to YAML and to roslaunch: write 1000000 or 1.0e+6, without quotes)";
  }
  return fail(message);
}

bool ParameterReader::read(const std::string& name, int& value)
{
  ParameterValue raw;
  if (!fetch(name, raw))
    return ok();
  if (raw.type == ParameterValue::Type::kInt)
  {
    value = raw.integer;
    return true;
  }
  if (raw.type == ParameterValue::Type::kDouble)
  {
    const double number = raw.number;
    if (number == std::floor(number) && number >= std::numeric_limits<int>::min() &&
        number <= std::numeric_limits<int>::max())
    {
      value = static_cast<int>(number);
      return true;
    }
  }
  return fail("parameter ~" + name + " is " + raw.describe() + ", not an integer");
}

bool ParameterReader::read(const std::string& name, bool& value)
{
  ParameterValue raw;
  if (!fetch(name, raw))
    return ok();
  if (raw.type != ParameterValue::Type::kBool)
    return fail("parameter ~" + name + " is " + raw.describe() + ", not true or false");
  value = raw.boolean;
  return true;
}

bool ParameterReader::read(const std::string& name, std::string& value)
{
  ParameterValue raw;
  if (!fetch(name, raw))
    return ok();
  if (raw.type != ParameterValue::Type::kString)
    return fail("parameter ~" + name + " is " + raw.describe() + ", not a string");
  value = raw.text;
  return true;
}

bool ParameterReader::read(const std::string& name, std::vector<std::string>& value)
{
  ParameterValue raw;
  if (!fetch(name, raw))
    return ok();
  bool all_strings = raw.type == ParameterValue::Type::kList;
  for (const ParameterValue& item : raw.items)
    all_strings = all_strings && item.type == ParameterValue::Type::kString;
  if (!all_strings)
    return fail("parameter ~" + name + " is " + raw.describe() + ", not a list of strings");
  std::vector<std::string> strings;
  for (const ParameterValue& item : raw.items)
    strings.push_back(item.text);
  value = std::move(strings);
  return true;
}

bool ParameterReader::readAtLeast(const std::string& name, double& value, double minimum)
{
  if (!read(name, value))
    return false;
  std::ostringstream out;
  out << "parameter ~" << name << " = " << value << " must be finite and >= " << minimum;
  return require(std::isfinite(value) && value >= minimum, out.str());
}

bool ParameterReader::readAbove(const std::string& name, double& value, double minimum)
{
  if (!read(name, value))
    return false;
  std::ostringstream out;
  out << "parameter ~" << name << " = " << value << " must be finite and > " << minimum;
  return require(std::isfinite(value) && value > minimum, out.str());
}

bool ParameterReader::readAtLeast(const std::string& name, int& value, int minimum)
{
  if (!read(name, value))
    return false;
  return require(value >= minimum,
                 "parameter ~" + name + " = " + std::to_string(value) + " must be >= " + std::to_string(minimum));
}

}  // namespace acc
