#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "acc_identification/gnss/byte_source.h"
#include "acc_identification/gnss/gnss_fix.h"
#include "acc_identification/gnss/nmea_decoder.h"

#include <geometry_msgs/TwistStamped.h>
#include <sensor_msgs/NavSatFix.h>

#include <acc_identification/GnssFix.h>
#include <acc_identification/Sentence.h>

namespace acc
{
/// The library fix as a message (header.frame_id = frame_id). header.stamp is the GNSS time:
/// the full UTC time when fix.has_date, else the time of day counted from 1970-01-01 00:00
/// (VALID_DATE clear), so that a fix before the first date is still published.
acc_identification::GnssFix toMessage(const GnssFix& fix, const std::string& frame_id);
/// The message as a library fix (for nodes that consume the driver's output).
GnssFix fromMessage(const acc_identification::GnssFix& message);

/// Whether ros::Time can hold the fix's GNSS time (acc::toRosTime). The driver publishes fix only
/// then: a fix stamped 0 would pair as a time reset downstream.
bool hasRosGnssTime(const GnssFix& fix);

/// The standard ROS messages of a fix. Stamped with the receive time on the ROS clock by default,
/// as nmea_navsat_driver does, because tf and message_filters users (robot_localization's
/// navsat_transform) drop messages stamped far from now, and a GNSS time before the first date is
/// counted from 1970; with use_gnss_time, the GNSS time (acc_identification/GnssFix carries both).
/// hdop_uere_m: the range error behind an HDOP-only covariance. false when the fix has no position
/// (or no velocity, for the twist), or when ros::Time cannot hold the chosen stamp.
bool toNavSatFix(const GnssFix& fix, const std::string& frame_id, double hdop_uere_m, bool use_gnss_time,
                 sensor_msgs::NavSatFix& navsat);
bool toEnuTwist(const GnssFix& fix, const std::string& frame_id, bool use_gnss_time,
                geometry_msgs::TwistStamped& twist);

/// gps_driver_node: one instance per receiver. Reads bytes from ~source, publishes every line on
/// nmea_sentence, one fix per epoch on fix (acc_identification/GnssFix), navsat_fix
/// (sensor_msgs/NavSatFix) and vel (geometry_msgs/TwistStamped, ENU), and health on
/// /diagnostics. All parsing is in the ROS-free NmeaDecoder.
/// With ~source "topic" the bytes come from nmea_sentence_in (acc_identification/Sentence, e.g. a
/// bag of recorded sentences under rosbag play): each sentence goes through the same decoder with
/// its header.stamp as receive time, and nothing is republished on nmea_sentence (the bag has it).
class GpsDriverRos
{
public:
  GpsDriverRos(ros::NodeHandle node, ros::NodeHandle private_node);
  /// Runs until shutdown, or until the end of a replayed file. Returns the exit code.
  int run();

private:
  using SteadyClock = std::chrono::steady_clock;

  /// ~source "topic": one recorded line through the decoder.
  void onSentence(const acc_identification::Sentence::ConstPtr& message);
  /// Completes a pending epoch after epoch_idle_s without sentences on both the ROS clock (sim
  /// time under rosbag play: a paused bag does not split an epoch) and the host's clock (a fast
  /// replay's next sentence may still be in transit), or after epoch_idle_wall_s of the host's
  /// clock alone (the bag ended, so /clock stopped; a pause longer than this splits the epoch).
  void flushIdleTopicEpoch();
  int runTopic();
  std::string sourceDescription() const;
  void publishLine(std::string_view line);
  void publishFix(const GnssFix& fix);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);
  void waitForSubscribers();
  void finishReplay();

  ros::NodeHandle node_;
  std::string source_uri_;
  std::string frame_id_;
  std::string vel_frame_id_;
  double epoch_idle_s_ = 0.05;
  double epoch_idle_wall_s_ = 1.0;
  double end_of_file_wait_s_ = 0.5;  // ~end_of_file_wait_s: file source, stay this long after the end
  bool topic_source_ = false;
  ros::Subscriber sentence_subscriber_;
  std::uint64_t sentences_in_ = 0;
  std::uint32_t queue_size_in_ = 1000;
  double hdop_uere_m_ = 3.0;
  bool use_gnss_time_ = false;  ///< stamp navsat_fix and vel with GNSS time instead of the receive time
  double expected_rate_hz_ = 10.0;
  double fix_timeout_s_ = 1.0;
  int wait_for_subscribers_ = 0;
  std::vector<std::string> wait_for_topics_{"nmea_sentence", "fix", "navsat_fix", "vel"};
  double wait_for_subscribers_timeout_s_ = 30.0;
  double diagnostic_period_s_ = 1.0;

  std::unique_ptr<ByteSource> source_;
  NmeaDecoder decoder_;
  ros::Publisher sentence_publisher_, fix_publisher_, navsat_publisher_, vel_publisher_;
  diagnostic_updater::Updater updater_;

  ros::Time receive_time_;  ///< ROS time of the bytes being decoded
  SteadyClock::time_point last_bytes_, last_fix_, last_diagnostic_;
  bool have_fix_ = false;
  std::uint8_t last_fix_quality_ = 0;
  std::uint64_t fixes_at_last_diagnostic_ = 0;
  std::uint64_t errors_at_last_diagnostic_ = 0;  ///< bad sentences and fixes outside ros::Time
  std::uint64_t fixes_outside_ros_time_ = 0;     ///< GNSS time ros::Time cannot hold: fix not published
};

}  // namespace acc
