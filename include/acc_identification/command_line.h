#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace acc
{
/// A small "--name value" / "--flag" parser shared by the command-line tools, so that every tool
/// rejects unknown options and malformed numbers the same way, with a message, never a crash.
class CommandLine
{
public:
  /// @param value_options names (without "--") that take a value; may repeat on the line
  /// @param flag_options  names that take no value
  CommandLine(std::vector<std::string> value_options, std::vector<std::string> flag_options);

  /// Parses argv. Returns false and sets error() on an unknown option or a missing value.
  bool parse(int argc, char** argv);
  const std::string& error() const { return error_; }

  bool has(const std::string& name) const;
  /// The last value given for name.
  std::optional<std::string> value(const std::string& name) const;
  /// Every value given for name, in order.
  std::vector<std::string> values(const std::string& name) const;
  /// The last value of name as a number; nullopt when absent. Sets error() when not a number.
  std::optional<double> number(const std::string& name);
  /// Arguments that are not options (e.g. input files).
  const std::vector<std::string>& positional() const { return positional_; }

private:
  std::vector<std::string> value_options_;
  std::vector<std::string> flag_options_;
  std::map<std::string, std::vector<std::string>> given_;
  std::vector<std::string> positional_;
  std::string error_;
};

}  // namespace acc
