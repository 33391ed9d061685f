#include "acc_identification/ros/relative_state_ros.h"
#include "acc_identification/ros/ros_parameter_source.h"
#include "acc_identification/ros/ros_time.h"

#include <cmath>
#include <iostream>
#include <sstream>

namespace acc
{
namespace
{

std::uint64_t since(std::uint64_t now, std::uint64_t before) { return now - before; }
}  // namespace

acc_identification::RelativeState toMessage(const RelativeState& state, const std::string& frame_id)
{
  acc_identification::RelativeState m;
  m.header.stamp = toRosTime(state.time_s);
  m.header.frame_id = frame_id;
  m.space_gap_m = state.space_gap_m;
  m.follower_speed_mps = state.follower_speed_mps;
  m.leader_speed_mps = state.leader_speed_mps;
  m.relative_speed_mps = state.relative_speed_mps;
  m.time_gap_s = state.time_gap_s;
  m.epoch_skew_s = state.epoch_skew_s;
  m.space_gap_sigma_m = state.space_gap_sigma_m;
  m.gap_doppler_residual_m = state.gap_doppler_residual_m;
  m.valid = state.valid;
  m.invalid_reason = state.invalid_reason;
  return m;
}

RelativeStateRos::RelativeStateRos(ros::NodeHandle node, ros::NodeHandle private_node) : updater_(node, private_node)
{
  const RosParameterSource parameters(private_node);
  ParameterReader reader(parameters);
  reader.readElsewhere("diagnostic_period");  // diagnostic_updater's
  ok_ = loadRelativeStateSettings(reader, settings_) && loadRelativeStateNodeSettings(reader, node_settings_);
  if (!ok_)
  {
    ROS_FATAL("relative_state: %s", reader.error().c_str());
    return;
  }
  unread_parameters_ = reader.unreadNote();
  if (!unread_parameters_.empty())
    ROS_WARN("relative_state: %s", unread_parameters_.c_str());
  estimator_ = RelativeStateEstimator(settings_);
  leader_subscriber_ = node.subscribe("leader/fix", node_settings_.queue_size, &RelativeStateRos::onLeader, this);
  follower_subscriber_ = node.subscribe("follower/fix", node_settings_.queue_size, &RelativeStateRos::onFollower, this);
  // ROS drops the oldest messages of a full publisher queue, silently. Each sample is a follower
  // epoch, so the largest burst this node makes is every buffered follower epoch completed by one
  // fix, plus the follower fixes queued behind it on the subscriber. The queue holds that burst,
  // so that none of it is lost.
  // (Both terms come from int parameters: the sum fits the uint32 ROS takes.)
  publisher_queue_size_ = estimator_.mostStatesAtOnce() + static_cast<std::size_t>(node_settings_.queue_size);
  publisher_ = node.advertise<acc_identification::RelativeState>("relative_state",
                                                                 static_cast<std::uint32_t>(publisher_queue_size_));

  updater_.setHardwareID("leader/fix + follower/fix");
  updater_.add("Relative state", this, &RelativeStateRos::diagnose);
  // On the wall clock, so that health is reported also while a simulated clock is paused.
  diagnostic_timer_ = node.createWallTimer(ros::WallDuration(std::max(0.05, node_settings_.diagnostic_period_s)),
                                           [this](const ros::WallTimerEvent&) { updater_.force_update(); });
  last_leader_ = last_follower_ = last_valid_ = ros::WallTime::now();
  ROS_INFO("relative_state: %s gap, antenna offsets %.2f m + %.2f m, skew <= %.3f s, timeout %.1f s",
           gapModeName(settings_.gap_mode), settings_.geometry.leader_antenna_to_rear_bumper_m,
           settings_.geometry.follower_antenna_to_front_bumper_m, settings_.pairing.max_interpolation_skew_s,
           settings_.pairing.timeout_s);
}

RelativeStateRos::~RelativeStateRos()
{
  // On stderr: the node is past ros::shutdown here, where rosconsole prints nothing more.
  if (const std::size_t waiting = estimator_.followerEpochsWaiting(); waiting > 0)
    std::cerr << "[ WARN] relative_state: stopped with " << waiting
              << " follower epoch(s) still waiting for a leader epoch: neither paired nor counted in "
                 "follower_unpaired\n";
}

void RelativeStateRos::onLeader(const acc_identification::GnssFix::ConstPtr& message)
{
  last_leader_ = ros::WallTime::now();
  estimator_.addLeader(fromMessage(*message));
  publishStates();
}

void RelativeStateRos::onFollower(const acc_identification::GnssFix::ConstPtr& message)
{
  last_follower_ = ros::WallTime::now();
  if (!message->header.frame_id.empty())
    follower_frame_id_ = message->header.frame_id;
  estimator_.addFollower(fromMessage(*message));
  publishStates();
}

void RelativeStateRos::publishStates()
{
  for (const PairingEvent& event : estimator_.takeEvents())
  {
    if (event.per_epoch)
      ROS_WARN_THROTTLE(1.0, "relative_state: %s (further such reports throttled; all counted in diagnostics)",
                        event.text.c_str());
    else
      ROS_WARN("relative_state: %s", event.text.c_str());
  }
  for (const RelativeState& state : estimator_.takeStates())
  {
    last_state_ = state;
    if (state.valid)
      last_valid_ = ros::WallTime::now();
    if (!state.valid && !node_settings_.publish_invalid)
      continue;  // counted in invalid_states, reported in the log
    ros::Time stamp;
    if (!toRosTime(state.time_s, stamp))
    {
      // Stamped 0 it would read as a time reset downstream: not published, counted instead.
      ++unrepresentable_times_;
      ROS_WARN_THROTTLE(1.0, "relative_state: pair at GNSS time %.3f s is outside what ros::Time holds: not "
                        "published (counted in diagnostics)", state.time_s);
      continue;
    }
    publisher_.publish(toMessage(state, follower_frame_id_));
    ++published_;
  }
}

void RelativeStateRos::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  const PairingCounters& c = estimator_.pairingCounters();
  const RelativeStateCounters& r = estimator_.counters();
  const PairingCounters& b = counters_at_last_diagnostic_;
  const RelativeStateCounters& rb = state_counters_at_last_diagnostic_;
  const ros::WallTime now = ros::WallTime::now();
  const double leader_age_s = (now - last_leader_).toSec(), follower_age_s = (now - last_follower_).toSec();
  const double valid_age_s = (now - last_valid_).toSec();

  std::uint64_t new_unpaired = since(c.follower_unpaired, b.follower_unpaired);
  std::uint64_t new_dropouts = since(c.leader_dropouts, b.leader_dropouts) + since(c.follower_dropouts, b.follower_dropouts);
  std::uint64_t new_resets =
      since(c.leader_time_resets, b.leader_time_resets) + since(c.follower_time_resets, b.follower_time_resets);
  std::uint64_t new_strays =
      since(c.leader_stray_stamps, b.leader_stray_stamps) + since(c.follower_stray_stamps, b.follower_stray_stamps);
  std::uint64_t new_invalid = since(r.invalid_states, rb.invalid_states) +
                             since(unrepresentable_times_, unrepresentable_times_at_last_diagnostic_);
  if (leader_age_s > node_settings_.stale_after_s || follower_age_s > node_settings_.stale_after_s)
    status.summaryf(diagnostic_msgs::DiagnosticStatus::ERROR, "no %s fix for %.1f s",
                    leader_age_s > follower_age_s ? "leader" : "follower", std::max(leader_age_s, follower_age_s));
  else if (valid_age_s > node_settings_.stale_after_s)
    status.summaryf(diagnostic_msgs::DiagnosticStatus::ERROR, "fixes arrive but no valid pair for %.1f s", valid_age_s);
  else if (new_unpaired + new_dropouts + new_resets + new_strays + new_invalid > 0)
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "since last report: %lu unpaired epochs, %lu dropouts, %lu time resets, %lu stray time stamps, "
                    "%lu invalid samples",
                    static_cast<unsigned long>(new_unpaired), static_cast<unsigned long>(new_dropouts),
                    static_cast<unsigned long>(new_resets), static_cast<unsigned long>(new_strays),
                    static_cast<unsigned long>(new_invalid));
  else if (const GapDopplerConsistency& check = estimator_.consistency();
           receiversLookSwapped(check.recentGapPerDopplerSlope(), check.recentDopplerIntegralRms(),
                                check.recentWindows()))
    status.summaryf(diagnostic_msgs::DiagnosticStatus::ERROR,
                    "the gap grows where the Doppler speeds say the cars close in (slope %.2f over the last %zu "
                    "windows, 1 for a leader ahead): are the leader and follower receivers swapped?",
                    check.recentGapPerDopplerSlope(), check.recentWindows());
  else if (std::isfinite(last_state_.gap_doppler_residual_m) && last_state_.gap_doppler_residual_m > node_settings_.consistency_warn_m)
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "gap disagrees with Doppler speeds: %.2f m RMS",
                    last_state_.gap_doppler_residual_m);
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "pairing");

  status.add("published", published_);
  status.add("publisher_queue_size", publisher_queue_size_);
  status.add("last space_gap_m", last_state_.space_gap_m);
  status.add("last epoch_skew_s", last_state_.epoch_skew_s);
  status.add("last gap_doppler_residual_m", last_state_.gap_doppler_residual_m);
  status.add("leader fix age (wall) s", leader_age_s);
  status.add("follower fix age (wall) s", follower_age_s);
  status.add("leader_fixes", c.leader_fixes);
  status.add("follower_fixes", c.follower_fixes);
  status.add("exact_pairs", c.exact_pairs);
  status.add("interpolated_pairs", c.interpolated_pairs);
  status.add("follower_unpaired", c.follower_unpaired);
  status.add("follower_waiting (for a leader epoch, now)", estimator_.followerEpochsWaiting());
  status.add("leader_dropouts", c.leader_dropouts);
  status.add("follower_dropouts", c.follower_dropouts);
  status.add("leader_time_resets", c.leader_time_resets);
  status.add("follower_time_resets", c.follower_time_resets);
  status.add("leader_stray_stamps", c.leader_stray_stamps);
  status.add("follower_stray_stamps", c.follower_stray_stamps);
  status.add("leader_out_of_order", c.leader_out_of_order);
  status.add("follower_out_of_order", c.follower_out_of_order);
  status.add("leader_too_late", c.leader_too_late);
  status.add("follower_too_late", c.follower_too_late);
  status.add("leader_duplicates", c.leader_duplicates);
  status.add("follower_duplicates", c.follower_duplicates);
  status.add("leader_invalid_fixes", c.leader_invalid_fixes);
  status.add("follower_invalid_fixes", c.follower_invalid_fixes);
  status.add("buffer_overflows", c.buffer_overflows);
  status.add("invalid_states", r.invalid_states);
  status.add("jumps_rejected", r.jumps_rejected);
  status.add("missing_speed", r.missing_speed);
  status.add("along_track_fallbacks", r.along_track_fallbacks);
  status.add("held_positions", r.held_positions);
  status.add("times_outside_ros_time (not published)", unrepresentable_times_);
  counters_at_last_diagnostic_ = c;
  unrepresentable_times_at_last_diagnostic_ = unrepresentable_times_;
  state_counters_at_last_diagnostic_ = r;
}

}  // namespace acc
