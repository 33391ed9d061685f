// What the rostest checks share: spinning for a while, and the latest key/values of one
// diagnostic status (a node's diagnostic_updater task, found by its name).
#pragma once

#include <chrono>
#include <map>
#include <string>
#include <thread>
#include <utility>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>

namespace acc_test
{
/// Serves callbacks for `seconds` of wall time (the bag's clock may not run), polling every step.
inline void spinFor(double seconds, std::chrono::milliseconds step = std::chrono::milliseconds(2))
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok() && ros::WallTime::now() < end)
  {
    ros::spinOnce();
    std::this_thread::sleep_for(step);
  }
}

/// The latest values and message of the diagnostic status whose name contains `name`.
struct DiagnosticStatusRecord
{
  explicit DiagnosticStatusRecord(std::string status_name) : name(std::move(status_name)) {}

  std::string name;
  std::map<std::string, std::string> values;
  std::string message;

  void onDiagnostics(const diagnostic_msgs::DiagnosticArray& array)
  {
    for (const auto& status : array.status)
    {
      if (status.name.find(name) == std::string::npos)
        continue;
      message = status.message;
      for (const auto& kv : status.values)
        values[kv.key] = kv.value;
    }
  }
};
}  // namespace acc_test
