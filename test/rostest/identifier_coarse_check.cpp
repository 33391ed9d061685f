// Publishes /clock and a 1 Hz relative_state (a receiver at its default rate) to two identifier
// nodes, and checks what each says: the one whose ~max_gap_s exceeds the step checks the drive
// fit's Euler step live (drive_note: MATERIAL, k1 a quarter low at 1 Hz); the one left at 0.5 s
// simulates nothing and says why in identifiability_note.
#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include "acc_identification/synthesis/synthetic_runs.h"
#include "ros_test_support.h"

#include <acc_identification/AccParameters.h>
#include <acc_identification/RelativeState.h>

namespace
{
TEST(IdentifierCoarse, EulerStepCheckedLiveAndASlowStreamAgainstMaxGapIsSaid)
{
  ros::NodeHandle node;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  auto clock = node.advertise<rosgraph_msgs::Clock>("/clock", 10);
  auto coarse_in = node.advertise<acc_identification::RelativeState>("/coarse/relative_state", 1000);
  auto strict_in = node.advertise<acc_identification::RelativeState>("/strict/relative_state", 1000);
  acc_test::MessageLog<acc_identification::AccParameters> coarse, strict;
  auto coarse_out = node.subscribe("/coarse/acc_parameters", 100, &acc_test::MessageLog<acc_identification::AccParameters>::on, &coarse);
  auto strict_out = node.subscribe("/strict/acc_parameters", 100, &acc_test::MessageLog<acc_identification::AccParameters>::on, &strict);
  ASSERT_TRUE(acc_test::waitForConnections([&] {
    return coarse_in.getNumSubscribers() > 0 && strict_in.getNumSubscribers() > 0 &&
           coarse_out.getNumPublishers() > 0 && strict_out.getNumPublishers() > 0 && clock.getNumSubscribers() > 0;
  })) << "the identifiers did not subscribe";

  const acc::CarFollowingRun run = acc::synthesizeRun({0.1, 0.5, 1.0, 6.0}, 600.0, 1.0, 15.0, 7, {0.02, 0.05});
  const double t0 = 1000.0;
  const auto tick = [&](double t) {
    rosgraph_msgs::Clock now;
    now.clock = ros::Time(t);
    clock.publish(now);
  };
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    tick(t0 + run.time_s[k]);
    acc_identification::RelativeState state;
    state.header.stamp = ros::Time(t0 + run.time_s[k]);
    state.space_gap_m = run.space_gap_m[k];
    state.follower_speed_mps = run.follower_speed_mps[k];
    state.leader_speed_mps = run.leader_speed_mps[k];
    state.relative_speed_mps = state.leader_speed_mps - state.follower_speed_mps;
    state.valid = true;
    coarse_in.publish(state);
    strict_in.publish(state);
    ros::WallDuration(0.02).sleep();  // 50 times real time
  }
  for (int i = 1; i <= 40; ++i)  // the last periods and looks, once the data stop
  {
    tick(t0 + run.time_s.back() + 0.5 * i);
    ros::WallDuration(0.1).sleep();
  }

  std::lock_guard<std::mutex> coarse_lock(coarse.mutex), strict_lock(strict.mutex);
  ASSERT_FALSE(coarse.messages.empty()) << "nothing published with max_gap_s 2.5";
  const acc_identification::AccParameters& checked = coarse.messages.back();
  EXPECT_TRUE(checked.identifiable) << checked.identifiability_note;
  EXPECT_EQ(checked.identifiability_note.find("max_gap_s must exceed"), std::string::npos) << checked.identifiability_note;
  EXPECT_NE(checked.drive_note.find("Euler step (the paper's calibration simulates at the data's own step, median 1 s)"),
            std::string::npos)
      << checked.drive_note;
  EXPECT_NE(checked.drive_note.find("MATERIAL: k1 -"), std::string::npos) << checked.drive_note;

  ASSERT_FALSE(strict.messages.empty()) << "nothing published with max_gap_s 0.5";
  const acc_identification::AccParameters& refused = strict.messages.back();
  EXPECT_FALSE(refused.identifiable);
  EXPECT_NE(refused.identifiability_note.find("the samples' median step, 1 s, is itself such a hole (a receiver at 1 Hz); "
                                              "max_gap_s must exceed the step"),
            std::string::npos)
      << refused.identifiability_note;
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "identifier_coarse_check");
  return RUN_ALL_TESTS();
}
