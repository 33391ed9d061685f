#include "acc_identification/ros/parameter_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include <ros/param.h>


namespace acc
{
namespace
{
/// "the string \"1e6\"", "the number 2.5", "a list of 3 values": what a parameter holds, for an error.
std::string describe(XmlRpc::XmlRpcValue& value)
{
  std::ostringstream out;
  switch (value.getType())
  {
    case XmlRpc::XmlRpcValue::TypeString:
      out << "the string \"" << static_cast<std::string&>(value) << "\"";
      break;
    case XmlRpc::XmlRpcValue::TypeInt:
      out << "the integer " << static_cast<int>(value);
      break;
    case XmlRpc::XmlRpcValue::TypeDouble:
      out << "the number " << static_cast<double>(value);
      break;
    case XmlRpc::XmlRpcValue::TypeBoolean:
      out << "the bool " << (static_cast<bool>(value) ? "true" : "false");
      break;
    case XmlRpc::XmlRpcValue::TypeArray:
      out << "a list of " << value.size() << " values";
      break;
    case XmlRpc::XmlRpcValue::TypeStruct:
      out << "a dictionary";
      break;
    default:
      out << "a value of XML-RPC type " << static_cast<int>(value.getType());
  }
  return out.str();
}

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

bool ParameterReader::fetch(const std::string& name, XmlRpc::XmlRpcValue& raw)
{
  read_.insert(name);
  return ok() && node_.getParam(name, raw);
}

std::string ParameterReader::unreadNote() const
{
  std::vector<std::string> names;
  if (!ros::param::getParamNames(names))
    return "";
  const std::string prefix = node_.getNamespace() + "/";
  std::string unread;
  int count = 0;
  std::sort(names.begin(), names.end());
  for (const std::string& name : names)
  {
    if (name.compare(0, prefix.size(), prefix) != 0 || read_.count(name.substr(prefix.size())) > 0)
      continue;
    unread += (count++ > 0 ? ", ~" : "~") + name.substr(prefix.size());
  }
  if (count == 0)
    return "";
  return (count == 1 ? "parameter " + unread + " is" : "parameters " + unread + " are") +
         " set but not read by this node (misspelt?): ignored";
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
  XmlRpc::XmlRpcValue raw;
  if (!fetch(name, raw))
    return ok();
  if (raw.getType() == XmlRpc::XmlRpcValue::TypeDouble)
  {
    value = static_cast<double>(raw);
    return true;
  }
  if (raw.getType() == XmlRpc::XmlRpcValue::TypeInt)
  {
    value = static_cast<int>(raw);
    return true;
  }
  std::string message = "parameter ~" + name + " is " + describe(raw) + ", not a number";
  if (raw.getType() == XmlRpc::XmlRpcValue::TypeString && looksNumeric(static_cast<std::string&>(raw)))
  {
    // YAML 1.1 (rosparam, <rosparam>) reads an exponent as a number only with a dot and a sign, and
    // roslaunch's <param value> or arg:= only with a dot: 1e6 is text to both, 1.0e+6 a number to both.
    message += " (1e6 is text to YAML and to roslaunch: write 1000000 or 1.0e+6, without quotes)";
  }
  return fail(message);
}

bool ParameterReader::read(const std::string& name, int& value)
{
  XmlRpc::XmlRpcValue raw;
  if (!fetch(name, raw))
    return ok();
  if (raw.getType() == XmlRpc::XmlRpcValue::TypeInt)
  {
    value = static_cast<int>(raw);
    return true;
  }
  if (raw.getType() == XmlRpc::XmlRpcValue::TypeDouble)
  {
    const double number = static_cast<double>(raw);
    if (number == std::floor(number) && number >= std::numeric_limits<int>::min() &&
        number <= std::numeric_limits<int>::max())
    {
      value = static_cast<int>(number);
      return true;
    }
  }
  return fail("parameter ~" + name + " is " + describe(raw) + ", not an integer");
}

bool ParameterReader::read(const std::string& name, bool& value)
{
  XmlRpc::XmlRpcValue raw;
  if (!fetch(name, raw))
    return ok();
  if (raw.getType() != XmlRpc::XmlRpcValue::TypeBoolean)
    return fail("parameter ~" + name + " is " + describe(raw) + ", not true or false");
  value = static_cast<bool>(raw);
  return true;
}

bool ParameterReader::read(const std::string& name, std::string& value)
{
  XmlRpc::XmlRpcValue raw;
  if (!fetch(name, raw))
    return ok();
  if (raw.getType() != XmlRpc::XmlRpcValue::TypeString)
    return fail("parameter ~" + name + " is " + describe(raw) + ", not a string");
  value = static_cast<std::string&>(raw);
  return true;
}

bool ParameterReader::read(const std::string& name, std::vector<std::string>& value)
{
  XmlRpc::XmlRpcValue raw;
  if (!fetch(name, raw))
    return ok();
  bool all_strings = raw.getType() == XmlRpc::XmlRpcValue::TypeArray;
  for (int i = 0; all_strings && i < raw.size(); ++i)
    all_strings = raw[i].getType() == XmlRpc::XmlRpcValue::TypeString;
  if (!all_strings)
    return fail("parameter ~" + name + " is " + describe(raw) + ", not a list of strings");
  std::vector<std::string> strings;
  for (int i = 0; i < raw.size(); ++i)
    strings.push_back(static_cast<std::string&>(raw[i]));
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
