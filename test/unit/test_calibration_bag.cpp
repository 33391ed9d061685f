#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>
#include <string>

#include <rosbag/bag.h>

#include "acc_identification/ros/run_bag_reader.h"

#include <acc_identification/RelativeState.h>


namespace
{
acc_identification::RelativeState stateAt(double t, bool valid = true)
{
  acc_identification::RelativeState state;
  state.header.stamp = ros::Time(t);
  state.space_gap_m = 20.0 + t;
  state.follower_speed_mps = 10.0;
  state.leader_speed_mps = 10.5;
  state.valid = valid;
  return state;
}

TEST(RunBagReader, SplitsAtInvalidSamplesGapsAndTimeResets)
{
  const std::string path = testing::TempDir() + "/run_bag_reader_test.bag";
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    const ros::Time recorded(1.0);
    for (int k = 0; k < 30; ++k) bag.write("/relative_state", recorded, stateAt(100.0 + 0.1 * k));  // 100.0-102.9
    bag.write("/relative_state", recorded, stateAt(103.0, false));                                  // invalid
    for (int k = 31; k < 40; ++k) bag.write("/relative_state", recorded, stateAt(100.0 + 0.1 * k));  // 103.1-103.9
    for (int k = 50; k < 60; ++k) bag.write("/relative_state", recorded, stateAt(100.0 + 0.1 * k));  // hole, 105.0-105.9
    bag.write("/relative_state", recorded, stateAt(105.9));                                          // repeated stamp
    acc_identification::RelativeState nan_state = stateAt(106.0);
    nan_state.space_gap_m = std::numeric_limits<double>::quiet_NaN();
    bag.write("/relative_state", recorded, nan_state);
    for (int k = 0; k < 5; ++k) bag.write("/relative_state", recorded, stateAt(10.0 + 0.1 * k));    // replay restarted
    bag.write("/other_topic", recorded, stateAt(1.0));
  }
  const acc::BagRuns runs = acc::readRunsFromBag(path, "relative_state", 0.5);
  EXPECT_EQ(runs.messages, 57u);  // the other topic is not read
  EXPECT_EQ(runs.invalid, 2u);
  EXPECT_EQ(runs.out_of_order, 1u);
  EXPECT_EQ(runs.time_resets, 1u);
  ASSERT_EQ(runs.runs.size(), 4u);
  EXPECT_EQ(runs.runs[0].size(), 30u);
  EXPECT_EQ(runs.runs[0].name, "run_bag_reader_test#1");
  EXPECT_EQ(runs.runs[1].size(), 9u);
  EXPECT_EQ(runs.runs[2].size(), 10u);
  EXPECT_DOUBLE_EQ(runs.runs[2].time_s.front(), 105.0);
  EXPECT_EQ(runs.runs[3].size(), 5u);
  EXPECT_DOUBLE_EQ(runs.runs[3].time_s.front(), 10.0);
  EXPECT_DOUBLE_EQ(runs.runs[0].space_gap_m[1], 20.0 + 100.1);
  // The tools' account of the same bag (their JSON's inputs_read): every message used or counted.
  std::ostringstream log;
  const acc::RunArgument argument =
      acc::readRunArgument(path, "relative_state", 0.5, log, acc::OpenAccPairSelector::first());
  EXPECT_EQ(argument.account.format, "bag");
  using Counts = std::vector<std::pair<std::string, std::size_t>>;
  EXPECT_EQ(argument.account.counts, (Counts{{"messages", 57}, {"samples_used", 54}, {"runs", 4}, {"invalid", 2},
                                             {"implausible", 0}, {"out_of_order", 1}, {"time_holes", 1},
                                             {"time_resets", 1}, {"short_pieces", 0}}));
  try
  {
    acc::readRunsFromBag(path, "missing_topic");
    ADD_FAILURE() << "no error for a topic the bag does not have";
  }
  catch (const std::runtime_error& error)
  {
    // The bag's topics, with their types and counts, so that the user can pass --topic.
    const std::string what = error.what();
    EXPECT_NE(what.find("has no messages on topic 'missing_topic'; its topics: /other_topic "
                        "(acc_identification/RelativeState, 1 message), /relative_state "
                        "(acc_identification/RelativeState, 57 messages) (choose one with --topic)"),
              std::string::npos)
        << what;
  }
  std::remove(path.c_str());
  EXPECT_THROW(acc::readRunsFromBag(path), std::runtime_error);
}
}  // namespace
