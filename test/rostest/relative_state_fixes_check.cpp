// rostest of relative_state_node from recorded fixes: 30 s of the OpenACC Casale run part4
// (JRC, CC BY 4.0) as the drivers would publish them (through NMEA and back). The follower's fixes
// come on time; the leader's come 1.2 s late in shuffled bursts of 5 with 2 s cut out, as over a radio
// link; then both streams loop back to the start (time going backwards) and one follower fix has
// no position. Checks what relative_state publishes and what /diagnostics says.
#include "acc_identification/ros/relative_state_ros.h"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <random>
#include <thread>
#include <vector>

#include <unistd.h>

#include <diagnostic_msgs/DiagnosticArray.h>

#include "ros_test_support.h"

#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/gnss/nmea_log.h"
#include "acc_identification/model/portable_uniform.h"

namespace fs = std::filesystem;

namespace
{
constexpr double kOffset_m = 5.60;
constexpr std::size_t kDelayEpochs = 12, kBurst = 5, kDropoutFirst = 100, kDropoutLast = 120, kLoopEpochs = 50;

std::vector<acc::GnssFix> recorded(const acc::OpenAccPairTrack& file, int vehicle)
{
  fs::path log = fs::temp_directory_path() / ("relstate_fixes_" + std::to_string(vehicle) + "_" + std::to_string(::getpid()));
  std::string error;
  EXPECT_TRUE(acc::writeNmeaLog(log.string(), acc::openAccFixes(file, vehicle), "GN", error)) << error;
  auto back = acc::readNmeaLog(log.string());
  fs::remove(log);
  return back.fixes;
}

struct Received
{
  std::vector<acc_identification::RelativeState> states;
  acc_test::DiagnosticStatusRecord diagnostics{"Relative state"};
  void onState(const acc_identification::RelativeState& m) { states.push_back(m); }
};
using acc_test::spinFor;
}  // namespace

TEST(RelativeStateNode, PairsLateBurstyLeaderFixesAndReportsDropoutsAndTimeResets)
{
  ros::NodeHandle node, private_node("~");
  std::string csv;
  ASSERT_TRUE(private_node.getParam("csv", csv));
  auto file = acc::readOpenAccPairTrack(csv);
  ASSERT_TRUE(file.error.empty()) << file.error;
  auto leader = recorded(file, 1), follower = recorded(file, 2);
  ASSERT_EQ(leader.size(), 300u);
  ASSERT_EQ(follower.size(), 300u);

  Received received;
  auto state_sub = node.subscribe("relative_state", 10000, &Received::onState, &received);
  auto diagnostics_sub = node.subscribe("/diagnostics", 100, &acc_test::DiagnosticStatusRecord::onDiagnostics,
                                        &received.diagnostics);
  auto leader_pub = node.advertise<acc_identification::GnssFix>("leader/fix", 1000);
  auto follower_pub = node.advertise<acc_identification::GnssFix>("follower/fix", 1000);
  ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::ok() && ros::WallTime::now() < deadline &&
         (leader_pub.getNumSubscribers() == 0 || follower_pub.getNumSubscribers() == 0 || state_sub.getNumPublishers() == 0))
    spinFor(0.05);
  ASSERT_GT(state_sub.getNumPublishers(), 0u) << "relative_state_node did not come up";
  spinFor(0.5);

  // The leader's stream: 2 s cut out, sent 1.2 s late in bursts shuffled inside.
  std::vector<std::size_t> leader_order;
  for (std::size_t i = 0; i < leader.size(); ++i)
    if (i < kDropoutFirst || i > kDropoutLast)
      leader_order.push_back(i);
  std::mt19937_64 random(11);
  std::size_t next_leader = 0;
  for (std::size_t i = 0; i < follower.size(); ++i)
  {
    follower_pub.publish(acc::toMessage(follower[i], "follower_gps"));
    if (i == 200)
    {
      auto no_position = follower[i];
      no_position.fix_quality = 0;
      no_position.valid_fields = 0;
      follower_pub.publish(acc::toMessage(no_position, "follower_gps"));
    }
    if (i % kBurst == kBurst - 1 && i >= kDelayEpochs)
    {
      std::vector<std::size_t> burst;
      while (next_leader < leader_order.size() && leader_order[next_leader] + kDelayEpochs <= i)
        burst.push_back(leader_order[next_leader++]);
      acc::portableShuffle(burst, random);  // the same order with every standard library
      for (std::size_t j : burst)
        leader_pub.publish(acc::toMessage(leader[j], "leader_gps"));
    }
    spinFor(0.003);
  }
  for (; next_leader < leader_order.size(); ++next_leader)
    leader_pub.publish(acc::toMessage(leader[leader_order[next_leader]], "leader_gps"));
  spinFor(0.5);
  // A looping bag: both streams start again from the beginning.
  for (std::size_t i = 0; i < kLoopEpochs; ++i)
  {
    leader_pub.publish(acc::toMessage(leader[i], "leader_gps"));
    follower_pub.publish(acc::toMessage(follower[i], "follower_gps"));
    spinFor(0.003);
  }
  spinFor(2.5);  // at least two diagnostic periods

  // Pass 1: every follower epoch but the 21 of the leader's dropout; then the loop's 50.
  const std::size_t pass1 = follower.size() - (kDropoutLast - kDropoutFirst + 1);
  ASSERT_EQ(received.states.size(), pass1 + kLoopEpochs);
  const double dropout_begin = leader[kDropoutFirst].gnss_time_s - 1e-3, dropout_end = leader[kDropoutLast].gnss_time_s + 1e-3;
  double sum_squares = 0.0;
  for (std::size_t k = 0; k < received.states.size(); ++k)
  {
    const auto& s = received.states[k];
    EXPECT_TRUE(s.valid) << s.invalid_reason;
    EXPECT_EQ(s.header.frame_id, "follower_gps");
    double t = s.header.stamp.toSec();
    if (k > 0 && k != pass1)
    {
      EXPECT_GT(t, received.states[k - 1].header.stamp.toSec()) << "output went back at " << k;
    }
    EXPECT_FALSE(t > dropout_begin && t < dropout_end) << "a sample inside the leader's dropout at " << t;
    std::size_t row = static_cast<std::size_t>(std::llround((t - follower[0].gnss_time_s) * 10.0));
    ASSERT_LT(row, file.rows.size());
    const auto& r = file.rows[row];
    double distance_m = 0.0;
    GeographicLib::Geodesic::WGS84().Inverse(r.latitude_deg[0], r.longitude_deg[0], r.latitude_deg[1],
                                             r.longitude_deg[1], distance_m);
    sum_squares += std::pow(s.space_gap_m - (distance_m - kOffset_m), 2);
    EXPECT_NEAR(s.follower_speed_mps, r.speed_mps[1], 3e-4);
    EXPECT_NEAR(s.leader_speed_mps, r.speed_mps[0], 3e-4);
    EXPECT_NEAR(s.relative_speed_mps, r.speed_mps[0] - r.speed_mps[1], 6e-4);
  }
  EXPECT_LE(std::sqrt(sum_squares / received.states.size()), 0.05);
  EXPECT_TRUE(std::isfinite(received.states[pass1 - 1].gap_doppler_residual_m));
  EXPECT_LT(received.states[pass1 - 1].gap_doppler_residual_m, 1.0);

  ASSERT_FALSE(received.diagnostics.values.empty()) << "no diagnostics from relative_state_node";
  EXPECT_EQ(received.diagnostics.values["leader_dropouts"], "1");
  EXPECT_EQ(received.diagnostics.values["follower_unpaired"], std::to_string(kDropoutLast - kDropoutFirst + 1));
  EXPECT_EQ(received.diagnostics.values["leader_time_resets"], "1");
  EXPECT_EQ(received.diagnostics.values["follower_time_resets"], "1");
  EXPECT_EQ(received.diagnostics.values["follower_invalid_fixes"], "1");
  EXPECT_NE(received.diagnostics.values["leader_out_of_order"], "0");
  EXPECT_EQ(received.diagnostics.values["published"], std::to_string(received.states.size()));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "relative_state_fixes_check");
  return RUN_ALL_TESTS();
}
