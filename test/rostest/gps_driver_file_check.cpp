// rostest node: subscribes to everything gps_driver_node publishes while it replays
// test/data/nmea/drive_10s.nmea (100 epochs, 600 lines, see make_drive_fixture.py) and checks
// counts and values, time_reference against fix, and the final diagnostics' counts.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <acc_identification/GnssFix.h>
#include <acc_identification/Sentence.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/TwistStamped.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/TimeReference.h>

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kStartOfDay = 18562 * 86400.0;       // 2020-10-27 00:00 UTC
constexpr double kStartTimeOfDay = 10 * 3600 + 15 * 60 + 30.0;  // 10:15:30

struct Received
{
  std::vector<acc_identification::GnssFix> fixes;
  std::vector<sensor_msgs::NavSatFix> navsat;
  std::vector<geometry_msgs::TwistStamped> vel;
  std::vector<acc_identification::Sentence> sentences;
  std::vector<sensor_msgs::TimeReference> time_references;
  /// This driver's diagnostics once it had made all 100 fixes (key -> value); empty if none came.
  std::vector<diagnostic_msgs::KeyValue> final_diagnostics;
};

/// The status of the driver publishing frame_id's fixes in a diagnostics array, or nullptr.
const diagnostic_msgs::DiagnosticStatus* driverStatus(const diagnostic_msgs::DiagnosticArray& array,
                                                      const std::string& frame_id)
{
  for (const auto& status : array.status)
    if (status.name.find("NMEA receiver " + frame_id) != std::string::npos)
      return &status;
  return nullptr;
}

std::string valueOf(const std::vector<diagnostic_msgs::KeyValue>& values, const std::string& key)
{
  for (const auto& kv : values)
    if (kv.key == key)
      return kv.value;
  return "(missing)";
}

Received receiveAll(const std::string& frame_id)
{
  ros::NodeHandle node;
  Received r;
  // Subscribed first: the driver waits for its topics' subscribers only, and reports its final
  // counts once, at the end of the file.
  auto diagnostics = node.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& array) {
        const diagnostic_msgs::DiagnosticStatus* status = driverStatus(*array, frame_id);
        if (status && valueOf(status->values, "fixes") == "100")
          r.final_diagnostics = status->values;
      });
  auto s1 = node.subscribe<acc_identification::Sentence>(
      "nmea_sentence", 1000, [&](const acc_identification::Sentence::ConstPtr& m) { r.sentences.push_back(*m); });
  auto s2 = node.subscribe<sensor_msgs::NavSatFix>(
      "navsat_fix", 1000, [&](const sensor_msgs::NavSatFix::ConstPtr& m) { r.navsat.push_back(*m); });
  auto s3 = node.subscribe<geometry_msgs::TwistStamped>(
      "vel", 1000, [&](const geometry_msgs::TwistStamped::ConstPtr& m) { r.vel.push_back(*m); });
  auto s4 = node.subscribe<acc_identification::GnssFix>(
      "fix", 1000, [&](const acc_identification::GnssFix::ConstPtr& m) { r.fixes.push_back(*m); });
  auto s5 = node.subscribe<sensor_msgs::TimeReference>(
      "time_reference", 1000, [&](const sensor_msgs::TimeReference::ConstPtr& m) { r.time_references.push_back(*m); });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(30.0);
  // Until everything came, then a little longer to catch anything extra.
  while (ros::ok() && ros::WallTime::now() < end && (r.fixes.size() < 100 || r.sentences.size() < 600))
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
  const ros::WallTime grace = ros::WallTime::now() + ros::WallDuration(1.0);
  while (ros::ok() && ros::WallTime::now() < grace)
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
  return r;
}
}  // namespace

TEST(GpsDriverFile, PublishesEveryLineAndOneFixPerEpoch)
{
  std::string frame_id;
  ASSERT_TRUE(ros::NodeHandle("~").getParam("expected_frame_id", frame_id));
  const Received r = receiveAll(frame_id);
  EXPECT_EQ(r.sentences.size(), 600u);
  ASSERT_EQ(r.fixes.size(), 100u);
  EXPECT_EQ(r.navsat.size(), 100u);
  EXPECT_EQ(r.vel.size(), 100u);
  ASSERT_FALSE(r.sentences.empty());
  EXPECT_EQ(r.sentences[0].sentence.substr(0, 7), "$GNRMC,");
  EXPECT_EQ(r.sentences[0].header.frame_id, frame_id);

  // Start-up epochs: time of day only, VALID_DATE clear.
  const auto& first = r.fixes[0];
  EXPECT_EQ(first.valid_fields & acc_identification::GnssFix::VALID_DATE, 0u);
  EXPECT_NEAR(first.header.stamp.toSec(), kStartTimeOfDay, 1e-3);
  EXPECT_EQ(first.header.frame_id, frame_id);
  // From the fourth epoch: full UTC time.
  const auto& dated = r.fixes[3];
  EXPECT_NE(dated.valid_fields & acc_identification::GnssFix::VALID_DATE, 0u);
  EXPECT_NEAR(dated.header.stamp.toSec(), kStartOfDay + kStartTimeOfDay + 0.3, 1e-3);
  EXPECT_EQ(dated.header.stamp.nsec, 300000000u);  // exact centiseconds, no double noise

  const auto& last = r.fixes.back();
  EXPECT_NEAR(last.header.stamp.toSec(), kStartOfDay + kStartTimeOfDay + 9.9, 1e-3);
  EXPECT_NEAR(last.speed_over_ground_mps, 14.95, 1e-3);
  EXPECT_NEAR(last.course_rad, kPi / 4, 1e-9);
  EXPECT_EQ(last.fix_quality, acc_identification::GnssFix::FIX_GPS);
  EXPECT_EQ(last.satellites_used, 12);
  EXPECT_DOUBLE_EQ(last.hdop, 0.8);
  EXPECT_DOUBLE_EQ(last.altitude_m, 159.9);
  EXPECT_DOUBLE_EQ(last.latitude_sigma_m, 0.7);
  EXPECT_EQ(last.valid_fields, 255u);
  const double north_m = (99.0 + 0.25 * 9.9 * 9.9) / std::sqrt(2.0);
  EXPECT_NEAR((last.latitude_deg - 45.13) * kPi / 180 * 6378137.0, north_m, 0.02);

  // navsat_fix and vel: the receive time by default (as nmea_navsat_driver: tf and message_filters
  // drop stamps far from now), GNSS time with ~use_gnss_time; fix carries both either way.
  bool expect_gnss_time = false;
  ASSERT_TRUE(ros::NodeHandle("~").getParam("expect_gnss_time", expect_gnss_time));
  ASSERT_EQ(r.navsat.size(), r.fixes.size());
  ASSERT_EQ(r.vel.size(), r.fixes.size());
  for (std::size_t i = 0; i < r.fixes.size(); ++i)
  {
    const ros::Time expected = expect_gnss_time ? r.fixes[i].header.stamp : r.fixes[i].receive_time;
    EXPECT_EQ(r.navsat[i].header.stamp, expected) << i;
    EXPECT_EQ(r.vel[i].header.stamp, expected) << i;
  }
  if (!expect_gnss_time)
  {
    EXPECT_NE(r.navsat.back().header.stamp, r.fixes.back().header.stamp) << "navsat_fix carries GNSS time";
  }

  const auto& navsat = r.navsat.back();
  EXPECT_DOUBLE_EQ(navsat.latitude, last.latitude_deg);
  EXPECT_NEAR(navsat.altitude, 159.9 + 47.3, 1e-9);  // ellipsoid height
  EXPECT_EQ(navsat.position_covariance_type, sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN);
  EXPECT_NEAR(navsat.position_covariance[4], 0.49, 1e-12);

  // Course 45 deg: equal east and north components in ENU.
  const auto& vel = r.vel.back();
  EXPECT_NEAR(vel.twist.linear.x, 14.95 / std::sqrt(2.0), 1e-3);
  EXPECT_NEAR(vel.twist.linear.y, 14.95 / std::sqrt(2.0), 1e-3);
  EXPECT_EQ(vel.header.frame_id, "enu");

  // Epochs 0.1 s apart, in order.
  for (std::size_t i = 4; i < r.fixes.size(); ++i)
    EXPECT_NEAR((r.fixes[i].header.stamp - r.fixes[i - 1].header.stamp).toSec(), 0.1, 1e-3) << i;

  // time_reference: one per dated fix (the first three epochs have a time of day only), time_ref =
  // the fix's GNSS time, header.stamp = its receive time whatever ~use_gnss_time says; the
  // undated fixes are counted in the diagnostics.
  constexpr std::size_t kUndatedFixes = 3;
  ASSERT_EQ(r.time_references.size(), r.fixes.size() - kUndatedFixes);
  for (std::size_t i = 0; i < r.time_references.size(); ++i)
  {
    const acc_identification::GnssFix& fix = r.fixes[i + kUndatedFixes];
    const sensor_msgs::TimeReference& reference = r.time_references[i];
    EXPECT_EQ(reference.time_ref, fix.header.stamp) << i;
    EXPECT_EQ(reference.header.stamp, fix.receive_time) << i;
    EXPECT_EQ(reference.header.frame_id, frame_id) << i;
    EXPECT_EQ(reference.source, frame_id) << i;  // ~time_ref_source unset: the frame_id
  }
  ASSERT_FALSE(r.final_diagnostics.empty()) << "no diagnostics after the last fix";
  EXPECT_EQ(valueOf(r.final_diagnostics, "fixes without a date (no time_reference)"), "3");
  EXPECT_EQ(valueOf(r.final_diagnostics, "dated fixes with a time outside ros::Time (no time_reference)"), "0");
}

TEST(GpsDriverDiagnostics, RateAndBadSentencesDuringARealTimeReplay)
{
  std::string frame_id;
  ASSERT_TRUE(ros::NodeHandle("~").getParam("expected_frame_id", frame_id));
  ros::NodeHandle node;
  bool ok_at_10_hz = false, bad_checksum_counted = false;
  auto subscription = node.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& array) {
        for (const auto& status : array->status)
        {
          if (status.name.find("NMEA receiver " + frame_id) == std::string::npos)
            continue;
          for (const auto& kv : status.values)
          {
            if (kv.key == "fix rate [Hz]" && status.level == diagnostic_msgs::DiagnosticStatus::OK)
              ok_at_10_hz |= std::fabs(std::stod(kv.value) - 10.0) < 1.0;
            if (kv.key == "bad checksum")
              bad_checksum_counted |= kv.value == "1";
          }
        }
      });
  // The log is 10 s long at rate 1 and has one bad checksum at 5 s.
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::ok() && ros::WallTime::now() < end && !(ok_at_10_hz && bad_checksum_counted))
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
  EXPECT_TRUE(ok_at_10_hz);
  EXPECT_TRUE(bad_checksum_counted);
}

/// One datagram of 20 epochs (120 lines, about 6.9 kB: more than the 4096 bytes the driver once
/// read a datagram into, which lost the rest without a count) must give 20 fixes.
TEST(GpsDriverUdp, ALargeDatagramIsReadWhole)
{
  ros::NodeHandle private_node("~");
  std::string log_path;
  int port = 0;
  ASSERT_TRUE(private_node.getParam("log", log_path));
  ASSERT_TRUE(private_node.getParam("port", port));
  std::ifstream log(log_path);
  std::string datagram, line;
  for (int lines = 0; lines < 120 && std::getline(log, line); ++lines)
    datagram += line + "\r\n";
  ASSERT_GT(datagram.size(), 4096u);

  ros::NodeHandle node;
  std::size_t fixes = 0;
  auto subscriber = node.subscribe<acc_identification::GnssFix>(
      "fix", 100, [&](const acc_identification::GnssFix::ConstPtr&) { ++fixes; });
  const ros::WallTime connected_by = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::ok() && subscriber.getNumPublishers() == 0 && ros::WallTime::now() < connected_by)
    ros::WallDuration(0.05).sleep();
  ASSERT_GT(subscriber.getNumPublishers(), 0u) << "the driver's fix topic never connected";
  ros::WallDuration(0.5).sleep();  // the driver has bound its port by now (it reads from the start)

  const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::sendto(sender, datagram.data(), datagram.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to),
            static_cast<ssize_t>(datagram.size()));
  ::close(sender);
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10.0);  // the last epoch ends on idle
  while (ros::ok() && ros::WallTime::now() < end && fixes < 20)
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
  EXPECT_EQ(fixes, 20u);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "gps_driver_file_check");
  ros::NodeHandle node;  // starts the node before the test subscribes
  return RUN_ALL_TESTS();
}
