#pragma once

#include <optional>
#include <string>
#include <vector>

namespace acc
{
/// One parameter's value with the type its source gave it: YAML 1.1 as rosparam reads it (1e6 is
/// text), or the ROS parameter server's XML-RPC types.
struct ParameterValue
{
  enum class Type
  {
    kBool,
    kInt,
    kDouble,
    kString,
    kList,
    kDictionary,
    kNull,
  };
  Type type = Type::kNull;
  bool boolean = false;
  int integer = 0;
  double number = 0.0;
  std::string text;
  std::vector<ParameterValue> items;  ///< a list's values

  /// "the string \"1e6\"", "the number 2.5", "a list of 3 values": what it holds, for an error.
  std::string describe() const;
};

/// Where a node's or a tool's parameters come from: the ROS parameter server in a node's private
/// namespace (ros/ros_parameter_source.h) or a YAML file of the same keys
/// (parameters/yaml_parameter_source.h). Names are relative ("timeout_s" for ~timeout_s).
class ParameterSource
{
public:
  virtual ~ParameterSource() = default;
  /// The value of name, or nothing when it is not set.
  virtual std::optional<ParameterValue> get(const std::string& name) const = 0;
  /// Every name set, sorted (for the warning of those nobody reads).
  virtual std::vector<std::string> names() const = 0;
};

}  // namespace acc
