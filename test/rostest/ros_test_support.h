// What the rostest checks share: spinning for a while, and the latest key/values of one
// diagnostic status (a node's diagnostic_updater task, found by its name).
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

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

/// Every message of one subscription, in order, for a test to read once the node has run.
template <typename Message>
struct MessageLog
{
  std::mutex mutex;
  std::vector<Message> messages;
  void on(const typename Message::ConstPtr& message)
  {
    std::lock_guard<std::mutex> lock(mutex);
    messages.push_back(*message);
  }
};

/// Waits (wall time, at most `seconds`) until `connected` holds, e.g. until the node under test has
/// subscribed to what the test publishes; returns whether it does.
inline bool waitForConnections(const std::function<bool()>& connected, double seconds = 30.0)
{
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(seconds);
  while (!connected() && ros::WallTime::now() < deadline)
    ros::WallDuration(0.05).sleep();
  return connected();
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
