#include "acc_identification/ros/relative_state_ros.h"
#include "acc_identification/ros/ros_time.h"

#include <cmath>
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

namespace
{
/// Where the antennas sit on the cars: the two offsets, or one combined offset (what OpenACC gives).
bool readGeometry(ParameterReader& r, VehicleGeometry& g)
{
  if (!r.readAtLeast("leader_antenna_to_rear_bumper_m", g.leader_antenna_to_rear_bumper_m, -1e3) ||
      !r.readAtLeast("follower_antenna_to_front_bumper_m", g.follower_antenna_to_front_bumper_m, -1e3))
    return false;
  if (!r.has("antenna_offset_m"))
    return true;
  if (!r.require(!r.has("leader_antenna_to_rear_bumper_m") && !r.has("follower_antenna_to_front_bumper_m"),
                 "give either ~antenna_offset_m or the two antenna-to-bumper offsets, not both"))
    return false;
  double combined_m = 0.0;
  const bool ok = r.readAtLeast("antenna_offset_m", combined_m, -1e3);
  g.leader_antenna_to_rear_bumper_m = combined_m;
  return ok;
}

bool readPairing(ParameterReader& r, PairingSettings& q)
{
  int max_buffered = static_cast<int>(q.max_buffered_fixes);
  const bool ok = r.readAtLeast("max_buffered_fixes", max_buffered, 1) &&
                  r.readAtLeast("exact_match_tolerance_s", q.exact_match_tolerance_s, 0.0) &&
                  r.readAtLeast("max_interpolation_skew_s", q.max_interpolation_skew_s, 0.0) &&
                  r.readAtLeast("exact_wait_s", q.exact_wait_s, 0.0) && r.readAbove("timeout_s", q.timeout_s, 0.0) &&
                  r.readAbove("dropout_gap_s", q.dropout_gap_s, 0.0) && r.readAbove("time_reset_s", q.time_reset_s, 0.0);
  q.max_buffered_fixes = static_cast<std::size_t>(std::max(1, max_buffered));
  return ok;
}

/// The along-track gap and the plausibility and consistency checks.
bool readChecks(ParameterReader& r, RelativeStateSettings& s)
{
  return r.readAbove("track_min_spacing_m", s.track_min_spacing_m, 0.0) &&
         r.readAbove("track_max_length_m", s.track_max_length_m, 0.0) &&
         r.readAbove("track_max_lateral_offset_m", s.track_max_lateral_offset_m, 0.0) &&
         r.readAtLeast("min_speed_for_time_gap_mps", s.min_speed_for_time_gap_mps, 0.0) &&
         r.readAbove("max_gap_rate_mps", s.max_gap_rate_mps, 0.0) &&
         r.readAbove("max_acceleration_mps2", s.max_acceleration_mps2, 0.0) &&
         r.readAtLeast("jump_reference_max_age_s", s.jump_reference_max_age_s, 0.0) &&
         r.readAbove("consistency_window_s", s.consistency_window_s, 0.0) &&
         r.readAbove("min_held_position_move_m", s.min_held_position_move_m, 0.0);
}
}  // namespace

bool loadRelativeStateSettings(ParameterReader& reader, RelativeStateSettings& s)
{
  std::string mode = gapModeName(s.gap_mode);
  return readGeometry(reader, s.geometry) && reader.read("gap_mode", mode) &&
         reader.require(parseGapMode(mode, s.gap_mode),
                        "parameter ~gap_mode '" + mode + "' is neither straight_line nor along_track") &&
         readPairing(reader, s.pairing) && readChecks(reader, s);
}

RelativeStateRos::RelativeStateRos(ros::NodeHandle node, ros::NodeHandle private_node) : updater_(node, private_node)
{
  // Bursts of late leader fixes come together: queues deep enough for several seconds at 10 Hz.
  int queue_size = 200;
  ParameterReader reader(private_node);
  reader.readElsewhere("diagnostic_period");  // diagnostic_updater's
  ok_ = loadRelativeStateSettings(reader, settings_) && reader.readAbove("stale_after_s", stale_after_s_, 0.0) &&
        reader.readAbove("consistency_warn_m", consistency_warn_m_, 0.0) &&
        reader.readAbove("diagnostic_period_s", diagnostic_period_s_, 0.0) &&
        reader.read("publish_invalid", publish_invalid_) && reader.readAtLeast("queue_size", queue_size, 1);
  if (!ok_)
  {
    ROS_FATAL("relative_state: %s", reader.error().c_str());
    return;
  }
  unread_parameters_ = reader.unreadNote();
  if (!unread_parameters_.empty())
    ROS_WARN("relative_state: %s", unread_parameters_.c_str());
  estimator_ = RelativeStateEstimator(settings_);
  leader_subscriber_ = node.subscribe("leader/fix", queue_size, &RelativeStateRos::onLeader, this);
  follower_subscriber_ = node.subscribe("follower/fix", queue_size, &RelativeStateRos::onFollower, this);
  // ROS drops the oldest messages of a full publisher queue, silently. Each sample is a follower
  // epoch, so the largest burst this node makes is every buffered follower epoch completed by one
  // fix, plus the follower fixes queued behind it on the subscriber. The queue holds that burst,
  // so that none of it is lost.
  // (Both terms come from int parameters: the sum fits the uint32 ROS takes.)
  publisher_queue_size_ = estimator_.mostStatesAtOnce() + static_cast<std::size_t>(queue_size);
  publisher_ = node.advertise<acc_identification::RelativeState>("relative_state",
                                                                 static_cast<std::uint32_t>(publisher_queue_size_));

  updater_.setHardwareID("leader/fix + follower/fix");
  updater_.add("Relative state", this, &RelativeStateRos::diagnose);
  // On the wall clock, so that health is reported also while a simulated clock is paused.
  diagnostic_timer_ = node.createWallTimer(ros::WallDuration(std::max(0.05, diagnostic_period_s_)),
                                           [this](const ros::WallTimerEvent&) { updater_.force_update(); });
  last_leader_ = last_follower_ = last_valid_ = ros::WallTime::now();
  ROS_INFO("relative_state: %s gap, antenna offsets %.2f m + %.2f m, skew <= %.3f s, timeout %.1f s",
           gapModeName(settings_.gap_mode), settings_.geometry.leader_antenna_to_rear_bumper_m,
           settings_.geometry.follower_antenna_to_front_bumper_m, settings_.pairing.max_interpolation_skew_s,
           settings_.pairing.timeout_s);
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
    if (!state.valid && !publish_invalid_)
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
  std::uint64_t new_invalid = since(r.invalid_states, rb.invalid_states) +
                             since(unrepresentable_times_, unrepresentable_times_at_last_diagnostic_);
  if (leader_age_s > stale_after_s_ || follower_age_s > stale_after_s_)
    status.summaryf(diagnostic_msgs::DiagnosticStatus::ERROR, "no %s fix for %.1f s",
                    leader_age_s > follower_age_s ? "leader" : "follower", std::max(leader_age_s, follower_age_s));
  else if (valid_age_s > stale_after_s_)
    status.summaryf(diagnostic_msgs::DiagnosticStatus::ERROR, "fixes arrive but no valid pair for %.1f s", valid_age_s);
  else if (new_unpaired + new_dropouts + new_resets + new_invalid > 0)
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "since last report: %lu unpaired epochs, %lu dropouts, %lu time resets, %lu invalid samples",
                    static_cast<unsigned long>(new_unpaired), static_cast<unsigned long>(new_dropouts),
                    static_cast<unsigned long>(new_resets), static_cast<unsigned long>(new_invalid));
  else if (std::isfinite(last_state_.gap_doppler_residual_m) && last_state_.gap_doppler_residual_m > consistency_warn_m_)
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
  status.add("leader_dropouts", c.leader_dropouts);
  status.add("follower_dropouts", c.follower_dropouts);
  status.add("leader_time_resets", c.leader_time_resets);
  status.add("follower_time_resets", c.follower_time_resets);
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
