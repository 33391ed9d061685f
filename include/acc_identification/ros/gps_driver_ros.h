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
#include "acc_identification/parameters/parameter_reader.h"

#include <geometry_msgs/TwistStamped.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/TimeReference.h>

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

/// GGA quality (0..8, FIX_* of msg/GnssFix.msg) to sensor_msgs/NavSatStatus, as nmea_navsat_driver
/// maps it where it has a row: 0 NO_FIX, 1 FIX, 2 (DGPS) SBAS_FIX, 4 and 5 (RTK fixed and float)
/// GBAS_FIX. 3 (PPS, the precise code) is a standalone fix: FIX. 6 (dead reckoning), 7 (manual
/// input), 8 (simulator) and anything above are NO_FIX: no satellite fix, and navsat_transform and
/// other fusers take every status but NO_FIX as a GNSS measurement, so an extrapolated position
/// would be fused as one (nmea_navsat_driver has no row for them and also says NO_FIX).
/// NavSatStatus cannot tell RTK fixed from float: fix.fix_quality (acc_identification/GnssFix) does.
std::int8_t navSatStatusOf(std::uint8_t gga_quality);

/// The standard ROS messages of a fix. Stamped with the receive time on the ROS clock by default,
/// as nmea_navsat_driver does, because tf and message_filters users (robot_localization's
/// navsat_transform) drop messages stamped far from now, and a GNSS time before the first date is
/// counted from 1970; with use_gnss_time, the GNSS time (acc_identification/GnssFix carries both).
/// position_covariance (ENU, m^2): the three GST (or PUBX,00) sigmas squared, DIAGONAL_KNOWN, when
/// all three are there; else from HDOP, APPROXIMATED: east = north = (hdop * hdop_uere_m)^2,
/// up = (2 * hdop * hdop_uere_m)^2; else zero and UNKNOWN. The same for every fix quality.
/// hdop_uere_m: the range error behind an HDOP-only covariance. false when the fix has no position
/// (or no velocity, for the twist), or when ros::Time cannot hold the chosen stamp.
bool toNavSatFix(const GnssFix& fix, const std::string& frame_id, double hdop_uere_m, bool use_gnss_time,
                 sensor_msgs::NavSatFix& navsat);
bool toEnuTwist(const GnssFix& fix, const std::string& frame_id, bool use_gnss_time,
                geometry_msgs::TwistStamped& twist);

/// Why a fix gives no time_reference (kMade: it gives one).
enum class TimeReferenceOutcome
{
  kMade,
  kNoDate,          ///< GNSS time of day only (VALID_DATE clear): no absolute time to state
  kOutsideRosTime,  ///< the GNSS or the receive time is one ros::Time cannot hold
};

/// sensor_msgs/TimeReference of a fix, as nmea_navsat_driver publishes it: header.stamp = the
/// receive time of the epoch on the ROS clock (the stamp navsat_fix has by default), time_ref = the
/// epoch's GNSS (UTC) time, header.frame_id = frame_id, source = source. Only a dated fix has
/// an absolute GNSS time to give; reference is left as it was when the outcome is not kMade.
TimeReferenceOutcome toTimeReference(const GnssFix& fix, const std::string& frame_id, const std::string& source,
                                     sensor_msgs::TimeReference& reference);

/// gps_driver_node: one instance per receiver. Reads bytes from ~source, publishes every line on
/// nmea_sentence, one fix per epoch on fix (acc_identification/GnssFix), navsat_fix
/// (sensor_msgs/NavSatFix), vel (geometry_msgs/TwistStamped, ENU) and, for dated fixes,
/// time_reference (sensor_msgs/TimeReference), and health on /diagnostics. All parsing is in the
/// ROS-free NmeaDecoder.
/// With ~source "topic" the bytes come from nmea_sentence_in (acc_identification/Sentence, e.g. a
/// bag of recorded sentences under rosbag play): each sentence goes through the same decoder with
/// its header.stamp as receive time, and nothing is republished on nmea_sentence (the bag has it).
class GpsDriverRos
{
public:
  GpsDriverRos(ros::NodeHandle node, ros::NodeHandle private_node);
  /// False when a parameter was refused (logged FATAL): run() then returns 1 at once.
  bool ok() const { return settings_ok_; }
  /// ParameterReader::unreadNote() of the node's parameters (warned at start): empty when all were read.
  const std::string& unreadParameters() const { return unread_parameters_; }
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
  /// The private parameters into the members (queue_size: the publishers'); false and
  /// reader.error() on a parameter of the wrong type or out of range.
  bool readParameters(ParameterReader& reader, int& queue_size);
  int runTopic();
  /// Logs the byte source going from open to not open and back (once per change).
  void reportSourceState();
  /// Warns once when bytes are stamped 0: /use_sim_time set and no /clock.
  void warnIfNoClock();
  std::string sourceDescription() const;
  void publishLine(std::string_view line);
  void publishFix(const GnssFix& fix);
  void publishTimeReference(const GnssFix& fix);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);
  void waitForSubscribers();
  void finishReplay();

  ros::NodeHandle node_;
  bool settings_ok_ = false;  ///< the parameters read; false: run() returns 1 at once
  std::string unread_parameters_;
  std::string source_uri_ = "serial:///dev/ttyACM0?baud=115200";
  std::string frame_id_ = "gps";
  std::string vel_frame_id_ = "enu";
  std::string time_ref_source_;  ///< TimeReference.source: ~time_ref_source, or frame_id_ when empty
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
  ros::Publisher sentence_publisher_, fix_publisher_, navsat_publisher_, vel_publisher_, time_reference_publisher_;
  diagnostic_updater::Updater updater_;

  ros::Time receive_time_;  ///< ROS time of the bytes being decoded
  SteadyClock::time_point last_bytes_, last_fix_, last_diagnostic_;
  bool warned_no_clock_ = false;
  bool source_open_ = true;  ///< as last logged by reportSourceState (a failure at start is logged too)
  bool have_fix_ = false;
  std::uint8_t last_fix_quality_ = 0;
  std::uint64_t fixes_at_last_diagnostic_ = 0;
  std::uint64_t errors_at_last_diagnostic_ = 0;  ///< bad sentences, fixes and time references outside ros::Time
  std::uint64_t fixes_outside_ros_time_ = 0;     ///< GNSS time ros::Time cannot hold: fix not published
  /// Fixes without a date (time of day only, e.g. before the first RMC/ZDA): no time_reference.
  /// Expected at start-up, so a warning only when every fix of a report has none.
  std::uint64_t time_references_without_date_ = 0;
  std::uint64_t undated_at_last_diagnostic_ = 0;
  std::uint64_t repeated_at_last_diagnostic_ = 0;  ///< NmeaStatistics::repeated_sentences
  /// Dated fixes whose GNSS or receive time ros::Time cannot hold: no time_reference (an error).
  std::uint64_t time_references_outside_ros_time_ = 0;
};

}  // namespace acc
