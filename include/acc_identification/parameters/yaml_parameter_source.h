#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "acc_identification/parameters/parameter_source.h"

namespace acc
{
/// A YAML file of a node's parameters (config/*.yaml) as a tool reads it: the same keys, and
/// each value typed as rosparam types it (YAML 1.1, PyYAML's resolver), so that a file the node
/// refuses is refused here with the same message: 1e6 and 1.0e6 are text (a float wants a dot and
/// a signed exponent, 1.0e+6), yes/on/true are bools, a quoted "12" is a string. The top level
/// must be a mapping of names to values.
class YamlParameterSource : public ParameterSource
{
public:
  /// Reads path; error() says why when it cannot (no such file, not YAML, not a mapping).
  static YamlParameterSource fromFile(const std::string& path);
  /// The same from YAML text (name: where it came from, for the error).
  static YamlParameterSource fromText(const std::string& text, const std::string& name);

  std::optional<ParameterValue> get(const std::string& name) const override;
  std::vector<std::string> names() const override;

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  /// "key(s) given more than once: a, b (the last value of each is used, as rosparam loads it)",
  /// or "" when every key is given once.
  std::string repeatedKeysNote() const;

private:
  std::map<std::string, ParameterValue> values_;
  std::vector<std::string> repeated_;  ///< keys given more than once, each named once
  std::string error_;
};

/// A plain scalar's type as YAML 1.1 (PyYAML, rosparam) resolves it: bool, int, float or null,
/// else a string. Base-60 numbers are numbers, as PyYAML reads them: 1:30 is the int 90, -1:30.5
/// the float -90.5 (01:30 and 1:60 are strings).
ParameterValue resolveYamlScalar(const std::string& text);

}  // namespace acc
