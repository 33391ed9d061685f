#pragma once

// gps_driver_ros.h includes the GnssFix message under the name acc_identification::GnssFix (the library has
// a struct of that name); it must come before any other include of acc_identification/GnssFix.h.
#include "acc_identification/ros/gps_driver_ros.h"

#include <cstddef>
#include <cstdint>
#include <string>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "acc_identification/relative_state/relative_state_estimator.h"
#include "acc_identification/relative_state/relative_state_parameters.h"

// Same clash for RelativeState: the message is acc_identification::RelativeState here.
#include <acc_identification/RelativeState.h>

namespace acc
{
/// The library state as a message. header.stamp: the pair's GNSS time (as the driver's fixes).
acc_identification::RelativeState toMessage(const RelativeState& state, const std::string& frame_id);

/// relative_state_node: subscribes to leader/fix and follower/fix (acc_identification/GnssFix),
/// pairs them by GNSS epoch and publishes relative_state (acc_identification/RelativeState);
/// health on /diagnostics. The science is in the ROS-free RelativeStateEstimator; nothing here
/// uses the ROS clock for the data, so it runs the same under /use_sim_time.
class RelativeStateRos
{
public:
  RelativeStateRos(ros::NodeHandle node, ros::NodeHandle private_node);
  /// Says how many follower epochs were still waiting for a leader epoch: lost with the node.
  ~RelativeStateRos();
  bool ok() const { return ok_; }
  /// ParameterReader::unreadNote() of the node's parameters (warned at start): empty when all were read.
  const std::string& unreadParameters() const { return unread_parameters_; }

private:
  void onLeader(const acc_identification::GnssFix::ConstPtr& message);
  void onFollower(const acc_identification::GnssFix::ConstPtr& message);
  void publishStates();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  bool ok_ = false;
  std::string unread_parameters_;
  RelativeStateSettings settings_;
  RelativeStateEstimator estimator_;
  RelativeStateNodeSettings node_settings_;
  std::string follower_frame_id_ = "follower_gps";

  ros::Subscriber leader_subscriber_, follower_subscriber_;
  ros::Publisher publisher_;
  diagnostic_updater::Updater updater_;
  ros::WallTimer diagnostic_timer_;

  // Wall-clock health: the data's own time may be a replay's.
  ros::WallTime last_leader_, last_follower_, last_valid_;
  std::uint64_t published_ = 0;
  std::size_t publisher_queue_size_ = 0;  // holds the largest burst of states (see the constructor)
  /// States whose GNSS time ros::Time cannot hold (acc::toRosTime failed): counted, not published.
  std::uint64_t unrepresentable_times_ = 0, unrepresentable_times_at_last_diagnostic_ = 0;
  RelativeState last_state_;
  PairingCounters counters_at_last_diagnostic_;
  RelativeStateCounters state_counters_at_last_diagnostic_;
};

}  // namespace acc
