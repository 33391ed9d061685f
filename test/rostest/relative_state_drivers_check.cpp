// rostest of the whole chain on a real run: the OpenACC CSV (JRC, CC BY 4.0) converted by
// openacc_to_nmea at build time, replayed by two gps_driver_nodes (leader/, follower/) at 20 times
// real time, paired by relative_state_node. Checks every epoch's gap against an independent
// geodesic computation on the CSV's Lat/Lon, the speeds against Speed1/Speed2, and that the gap
// is at least as consistent with the Doppler speeds as the database's IVS1.
#include "acc_identification/ros/relative_state_ros.h"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <map>
#include <thread>
#include <vector>

#include <geometry_msgs/TwistStamped.h>
#include <sensor_msgs/NavSatFix.h>

#include "acc_identification/Sentence.h"
#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/relative_state/gap_doppler_consistency.h"


namespace
{
constexpr double kOffset_m = 5.60;

template <class Message>
void ignore(const boost::shared_ptr<const Message>&)
{
}

struct Received
{
  std::vector<acc_identification::RelativeState> states;
  ros::WallTime last = ros::WallTime::now();
  void onState(const acc_identification::RelativeState& m)
  {
    states.push_back(m);
    last = ros::WallTime::now();
  }
};
}  // namespace

TEST(RelativeStateDrivers, EveryEpochOfARealRunThroughTheDriversAndTheNode)
{
  ros::NodeHandle node, private_node("~");
  std::string csv;
  ASSERT_TRUE(private_node.getParam("csv", csv));
  auto file = acc::readOpenAccPairTrack(csv);
  ASSERT_TRUE(file.error.empty()) << file.error;

  Received received;
  auto state_sub = node.subscribe("relative_state", 100000, &Received::onState, &received);
  // Connected to relative_state_node first, so that its first states are not missed.
  ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && state_sub.getNumPublishers() == 0 && ros::WallTime::now() < deadline)
  {
    ros::spinOnce();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_GT(state_sub.getNumPublishers(), 0u) << "relative_state_node did not come up";
  // The drivers start replaying once each of their topics has a subscriber (wait_for_subscribers):
  // relative_state_node takes fix; these take the rest.
  std::vector<ros::Subscriber> others;
  for (const std::string ns : {"leader", "follower"})
  {
    others.push_back(node.subscribe(ns + "/nmea_sentence", 100000, &ignore<acc_identification::Sentence>));
    others.push_back(node.subscribe(ns + "/navsat_fix", 100000, &ignore<sensor_msgs::NavSatFix>));
    others.push_back(node.subscribe(ns + "/vel", 100000, &ignore<geometry_msgs::TwistStamped>));
  }
  // Until every epoch has come, or nothing has come for 15 s.
  received.last = ros::WallTime::now();
  while (ros::ok() && received.states.size() < file.rows.size() &&
         (ros::WallTime::now() - received.last).toSec() < 15.0)
  {
    ros::spinOnce();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }

  EXPECT_EQ(received.states.size(), file.rows.size());
  std::map<long long, const acc::OpenAccRow*> by_centisecond;
  for (const auto& row : file.rows)
    by_centisecond[std::llround(row.time_of_day_s * 100.0)] = &row;
  std::vector<double> times, gaps, ivs1, relative_speeds;
  double sum_squares = 0.0, speed_error_max = 0.0;
  for (const auto& s : received.states)
  {
    ASSERT_TRUE(s.valid) << s.invalid_reason;
    auto at = by_centisecond.find(std::llround((s.header.stamp.toSec() - file.dayStartUnixS()) * 100.0));
    ASSERT_NE(at, by_centisecond.end()) << "no CSV row at " << s.header.stamp.toSec();
    const acc::OpenAccRow& r = *at->second;
    double distance_m = 0.0;
    GeographicLib::Geodesic::WGS84().Inverse(r.latitude_deg[0], r.longitude_deg[0], r.latitude_deg[1],
                                             r.longitude_deg[1], distance_m);
    sum_squares += std::pow(s.space_gap_m - (distance_m - kOffset_m), 2);
    speed_error_max = std::max({speed_error_max, std::abs(s.leader_speed_mps - r.speed_mps[0]),
                                std::abs(s.follower_speed_mps - r.speed_mps[1])});
    times.push_back(r.time_of_day_s);
    gaps.push_back(s.space_gap_m);
    ivs1.push_back(r.ivs_m);
    relative_speeds.push_back(r.speed_mps[0] - r.speed_mps[1]);
  }
  ASSERT_FALSE(received.states.empty());
  double rms_m = std::sqrt(sum_squares / received.states.size());
  auto ours = acc::gapDopplerConsistency(times, gaps, relative_speeds, 10.0);
  auto database = acc::gapDopplerConsistency(times, ivs1, relative_speeds, 10.0);
  std::printf("%s: %zu states of %zu rows; gap vs geodesic RMS %.4f m; speeds max error %.5f m/s; "
              "gap-Doppler 10 s RMS: node %.3f m, IVS1 %.3f m\n",
              csv.c_str(), received.states.size(), file.rows.size(), rms_m, speed_error_max, ours.rms_m,
              database.rms_m);
  EXPECT_LE(rms_m, 0.05);
  EXPECT_LE(speed_error_max, 3e-4);
  EXPECT_LE(ours.rms_m, database.rms_m);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "relative_state_drivers_check");
  return RUN_ALL_TESTS();
}
