#pragma once

#include <optional>
#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "acc_identification/parameters/parameter_source.h"

namespace acc
{
/// A node's private parameters on the ROS parameter server, as ParameterReader reads them: the
/// XML-RPC types the server holds (rosparam's YAML 1.1, roslaunch's <param>) kept as they are.
class RosParameterSource : public ParameterSource
{
public:
  explicit RosParameterSource(const ros::NodeHandle& private_node) : node_(private_node) {}

  std::optional<ParameterValue> get(const std::string& name) const override;
  /// The names in the node's namespace, relative to it.
  std::vector<std::string> names() const override;

private:
  ros::NodeHandle node_;
};

}  // namespace acc
