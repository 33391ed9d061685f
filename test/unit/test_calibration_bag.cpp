#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>
#include <string>

#include <rosbag/bag.h>
#include <std_msgs/Bool.h>
#include <std_msgs/String.h>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/calibration/margin_constrained_fit.h"
#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/ros/run_bag_reader.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/synthesis/synthetic_runs.h"

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
      acc::readRunArgument(path, acc::BagTopics{}, 0.5, log, acc::OpenAccPairSelector::first());
  EXPECT_EQ(argument.account.format, "bag");
  using Counts = std::vector<std::pair<std::string, std::size_t>>;
  EXPECT_EQ(argument.account.counts, (Counts{{"messages", 57}, {"samples_used", 54}, {"runs", 4}, {"invalid", 2},
                                             {"implausible", 0}, {"out_of_order", 1}, {"time_holes", 1},
                                             {"time_resets", 1}, {"short_pieces", 0}, {"acc_off", 0},
                                             {"acc_state_unknown", 0}, {"engagement_reports", 0},
                                             {"other_setting", 0}, {"setting_changes", 0}}));
  EXPECT_EQ(log.str().find("engagement"), std::string::npos) << "a bag without a source is read as before";
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
                        "(acc_identification/RelativeState, 57 messages) (choose the one of type "
                        "acc_identification/RelativeState with --topic)"),
              std::string::npos)
        << what;
  }
  std::remove(path.c_str());
  EXPECT_THROW(acc::readRunsFromBag(path), std::runtime_error);
}

std_msgs::Bool engaged(bool value)
{
  std_msgs::Bool report;
  report.data = value;
  return report;
}

/// A drive whose safety driver took over for 2 s, recorded as drive.launch records it: samples
/// and engagement reports on the ROS clock, in the order the node received them.
std::string writeDriveWithATakeOver(const std::string& name)
{
  const std::string path = testing::TempDir() + "/" + name + ".bag";
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  for (int k = 0; k < 100; ++k)  // 10 s at 10 Hz, record time = GNSS time + 0.15 s of pairing
  {
    const double t = 200.0 + 0.1 * k;
    if (k == 5)
      bag.write("/acc_engaged", ros::Time(t + 0.1), engaged(true));
    if (k == 40)
      bag.write("/acc_engaged", ros::Time(t + 0.1), engaged(false));  // samples 40-59 while off
    if (k == 60)
      bag.write("/acc_engaged", ros::Time(t + 0.1), engaged(true));
    bag.write("/relative_state", ros::Time(t + 0.15), stateAt(t));
  }
  return path;
}

// A drive's bag of raw sentences (drive.launch records those) holds no samples yet: the error says
// how to make them, where it once suggested --topic, which every topic listed then refused.
TEST(RunBagReader, ABagOfRawSentencesSaysHowToMakeSamples)
{
  const std::string path = testing::TempDir() + "/raw_sentences.bag";
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    std_msgs::String line;
    line.data = "$GNGGA,...";
    bag.write("/leader/nmea_sentence", ros::Time(100.0), line);
  }
  try
  {
    acc::readRunsFromBag(path);
    ADD_FAILURE() << "no error for a bag without samples";
  }
  catch (const std::runtime_error& error)
  {
    const std::string what = error.what();
    EXPECT_NE(what.find("holds no acc_identification/RelativeState at all: replay it through the chain"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("nmea_to_csv"), std::string::npos) << what;
  }
  std::remove(path.c_str());
}

TEST(RunBagReader, SamplesRecordedWhileTheAccWasOffSplitTheRunAndAreCounted)
{
  const std::string path = writeDriveWithATakeOver("take_over");
  const acc::BagRuns runs = acc::readRunsFromBag(path, "relative_state", 0.5);
  EXPECT_EQ(runs.messages, 100u);
  EXPECT_EQ(runs.engagement_reports, 3u);
  EXPECT_EQ(runs.acc_off, 20u);
  EXPECT_EQ(runs.acc_state_unknown, 0u);  // before the first report: used, engagement not required
  ASSERT_EQ(runs.runs.size(), 2u);
  EXPECT_EQ(runs.runs[0].size(), 40u);
  EXPECT_EQ(runs.runs[1].size(), 40u);
  EXPECT_DOUBLE_EQ(runs.runs[1].time_s.front(), 206.0);
  ASSERT_EQ(runs.problems.size(), 1u);  // one line for the stretch, not one per sample
  EXPECT_NE(runs.problems[0].find("t = 204.000 s): ACC off"), std::string::npos) << runs.problems[0];

  acc::BagTopics required;
  required.engagement.required = true;
  std::ostringstream log;
  const acc::RunArgument argument = acc::readRunArgument(path, required, 0.5, log, acc::OpenAccPairSelector::first());
  // Samples 0-4 came before the first report: unknown, a piece too short to simulate on its own.
  EXPECT_EQ(argument.account.count("acc_state_unknown"), std::optional<std::size_t>(5));
  EXPECT_EQ(argument.account.count("acc_off"), std::optional<std::size_t>(20));
  EXPECT_EQ(argument.account.count("samples_used"), std::optional<std::size_t>(75));
  EXPECT_NE(log.str().find(", 20 recorded with the ACC off, 5 with its state unknown (3 engagement reports) -> 2 runs"),
            std::string::npos)
      << log.str();

  acc::BagTopics no_source;
  no_source.acc_engaged = "";
  EXPECT_EQ(acc::readRunsFromBag(path, no_source, acc::RunPlausibilityBounds{}).runs.size(), 1u);
  std::remove(path.c_str());
}

acc::AccParameters fitted(const std::vector<acc::CarFollowingRun>& runs)
{
  const acc::CalibrationObjective objective(runs);
  acc::MultistartOptions options;
  options.starts = 12;
  return acc::calibrateMultistart(objective, options).parameters;
}

/// Why the reports matter: 300 s of the paper's minimum setting, then the safety driver takes over
/// and brakes (2 m/s^2 for 5 s, then holds 10 m/s) while the leader drives on. Fitted with it, the
/// take-over is fitted as the ACC's; recorded as a take-over, it stays out.
TEST(RunBagReader, ATakeOverReportedOnAccEngagedStaysOutOfTheFit)
{
  const acc::AccParameters truth = acc::paperMinimumSetting();
  acc::CarFollowingRun drive = acc::synthesizeRun(truth, 300.0, 0.1, 20.0, 7);
  const double leader_mps = drive.leader_speed_mps.back();
  for (int k = 1; k <= 200; ++k)  // 20 s of manual driving
  {
    const double follower_mps = std::max(10.0, drive.follower_speed_mps.back() - 2.0 * 0.1);
    drive.space_gap_m.push_back(drive.space_gap_m.back() + 0.1 * (leader_mps - follower_mps));
    drive.follower_speed_mps.push_back(follower_mps);
    drive.leader_speed_mps.push_back(leader_mps);
    drive.time_s.push_back(drive.time_s.back() + 0.1);
  }
  const std::string path = testing::TempDir() + "/take_over_fit.bag";
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    bag.write("/acc_engaged", ros::Time(1000.0), engaged(true));
    for (std::size_t i = 0; i < drive.size(); ++i)
    {
      const double t = 1000.0 + drive.time_s[i];
      if (i == 3001)
        bag.write("/acc_engaged", ros::Time(t + 0.1), engaged(false));
      acc_identification::RelativeState state = stateAt(t);
      state.space_gap_m = drive.space_gap_m[i];
      state.follower_speed_mps = drive.follower_speed_mps[i];
      state.leader_speed_mps = drive.leader_speed_mps[i];
      bag.write("/relative_state", ros::Time(t + 0.15), state);
    }
  }
  acc::BagTopics ignoring;
  ignoring.acc_engaged = "";
  const acc::BagRuns with_take_over = acc::readRunsFromBag(path, ignoring, acc::RunPlausibilityBounds{});
  const acc::BagRuns without = acc::readRunsFromBag(path, acc::BagTopics{}, acc::RunPlausibilityBounds{});
  EXPECT_EQ(without.acc_off, 200u);  // every sample of the take-over
  ASSERT_EQ(without.runs.size(), 1u);
  const double truth_margin = acc::stabilityMargin(truth);
  const double error_with = std::abs(acc::stabilityMargin(fitted(with_take_over.runs)) - truth_margin);
  const double error_without = std::abs(acc::stabilityMargin(fitted(without.runs)) - truth_margin);
  std::printf("take-over: margin error %.3f fitted with it, %.3f without (truth %.3f)\n", error_with, error_without,
              truth_margin);
  EXPECT_LT(error_without, 0.1);
  EXPECT_GT(error_with, 5.0 * error_without);
  std::remove(path.c_str());
}

std_msgs::String setting(const std::string& name)
{
  std_msgs::String report;
  report.data = name;
  return report;
}

/// The driver switches the ACC from its shortest to its longest gap between two test profiles:
/// the runs end there, carry their setting in their name, and one setting can be asked for.
TEST(RunBagReader, AChangeOfTheAccSettingEndsTheRunsAndOneSettingCanBeChosen)
{
  const std::string path = testing::TempDir() + "/settings.bag";
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    bag.write("/acc_setting", ros::Time(99.0), setting("min"));
    for (int k = 0; k < 100; ++k)
    {
      const double t = 100.0 + 0.1 * k;
      if (k == 60)
        bag.write("/acc_setting", ros::Time(t + 0.1), setting("max"));
      if (k == 80)
        bag.write("/acc_setting", ros::Time(t + 0.1), setting("max"));  // repeated: no change
      bag.write("/relative_state", ros::Time(t + 0.15), stateAt(t));
    }
  }
  const acc::BagRuns all = acc::readRunsFromBag(path, "relative_state", 0.5);
  ASSERT_EQ(all.runs.size(), 2u);
  EXPECT_EQ(all.runs[0].size(), 60u);
  EXPECT_EQ(all.runs[1].size(), 40u);  // no sample lost at the change: it is a cut, not a split point
  EXPECT_EQ(all.runs[0].name, "settings#1 (setting min)");
  EXPECT_EQ(all.runs[1].name, "settings#2 (setting max)");
  EXPECT_EQ(all.setting_changes, 2u);  // none -> min, min -> max
  ASSERT_FALSE(all.problems.empty());
  EXPECT_NE(all.problems.back().find("runs at 2 ACC settings (max, min): one model fitted across them mixes them; "
                                     "choose one with --acc-setting"),
            std::string::npos)
      << all.problems.back();

  acc::BagTopics max_only;
  max_only.only_setting = "max";
  std::ostringstream log;
  const acc::RunArgument argument = acc::readRunArgument(path, max_only, 0.5, log, acc::OpenAccPairSelector::first());
  ASSERT_EQ(argument.runs.size(), 1u);
  EXPECT_EQ(argument.runs[0].size(), 40u);
  EXPECT_EQ(argument.account.count("other_setting"), std::optional<std::size_t>(60));
  EXPECT_NE(log.str().find(", 60 at another ACC setting (2 setting changes) -> 1 runs"), std::string::npos) << log.str();
  EXPECT_EQ(log.str().find("one model fitted across them"), std::string::npos) << log.str();
  std::remove(path.c_str());
}

TEST(RunBagReader, AnEngagementTopicOfAnotherTypeIsRefusedWithTheWayOut)
{
  const std::string path = testing::TempDir() + "/engagement_type.bag";
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    bag.write("/relative_state", ros::Time(1.0), stateAt(1.0));
    bag.write("/acc_engaged", ros::Time(1.0), stateAt(1.0));
  }
  try
  {
    acc::readRunsFromBag(path);
    ADD_FAILURE() << "no error for an engagement topic that is not std_msgs/Bool";
  }
  catch (const std::runtime_error& error)
  {
    EXPECT_NE(std::string(error.what()).find("topic 'acc_engaged' is acc_identification/RelativeState, not "
                                             "std_msgs/Bool (choose the topic with --acc-engaged-topic, or none "
                                             "with --acc-engaged-topic '')"),
              std::string::npos)
        << error.what();
  }
  std::remove(path.c_str());
}

/// The message of the std::runtime_error f throws, or "" when it throws none.
template <typename F>
std::string errorOf(F&& f)
{
  try
  {
    f();
  }
  catch (const std::runtime_error& error)
  {
    return error.what();
  }
  return "";
}

// The same drive given twice (io/repeated_recording.h): a copy among a tool's RUN files would be
// counted twice, an excerpt of a fitted run given as held out would score a model on its own data.
// Both are refused, naming the two files; different drives are read. Fails if readRunArguments or
// refuseHeldOutRepeats let a repeat through, or refuse different drives.
TEST(RunArguments, TheSameRecordingGivenTwiceIsRefusedWithBothFilesNamed)
{
  const std::string folder = testing::TempDir();
  const acc::CarFollowingRun drive = acc::synthesizeRun(acc::truthWithMargin(1.0), 120.0, 0.1, 20.0, 3);
  acc::writeRunCsv(folder + "/drive.csv", drive);
  acc::writeRunCsv(folder + "/copy.csv", drive);
  acc::writeRunCsv(folder + "/other.csv", acc::synthesizeRun(acc::truthWithMargin(1.0), 120.0, 0.1, 20.0, 4));
  acc::CarFollowingRun excerpt;
  for (std::size_t k = 300; k < 900; ++k)
  {
    excerpt.time_s.push_back(drive.time_s[k]);
    excerpt.space_gap_m.push_back(drive.space_gap_m[k]);
    excerpt.follower_speed_mps.push_back(drive.follower_speed_mps[k]);
    excerpt.leader_speed_mps.push_back(drive.leader_speed_mps[k]);
  }
  acc::writeRunCsv(folder + "/excerpt.csv", excerpt);
  std::ostringstream log;
  const auto read = [&](const std::vector<std::string>& names) {
    std::vector<std::string> paths;
    for (const std::string& name : names)
      paths.push_back(folder + "/" + name);
    return acc::readRunArguments(paths, acc::BagTopics{}, 0.5, log, acc::OpenAccPairSelector::first());
  };
  const std::string copied = errorOf([&] { read({"drive.csv", "other.csv", "copy.csv"}); });
  EXPECT_NE(copied.find(folder + "/copy.csv: its run copy (from t = 0.0 s) repeats " + folder +
                        "/drive.csv's run drive (from t = 0.0 s) sample for sample"),
            std::string::npos)
      << copied;
  EXPECT_NE(copied.find("give each recording once"), std::string::npos) << copied;
  const acc::RunArguments fitted = read({"drive.csv", "other.csv"});
  EXPECT_EQ(fitted.runs.size(), 2u);
  EXPECT_EQ(fitted.argument_of_run, (std::vector<std::size_t>{0, 1}));
  const std::string held_out = errorOf([&] { acc::refuseHeldOutRepeats(fitted, read({"excerpt.csv"})); });
  EXPECT_NE(held_out.find("a held-out run repeats a fitted one: " + folder +
                          "/excerpt.csv: its run excerpt (from t = 30.0 s) repeats " + folder +
                          "/drive.csv's run drive (from t = 30.0 s)"),
            std::string::npos)
      << held_out;
  EXPECT_NE(held_out.find("is not held out"), std::string::npos) << held_out;
  EXPECT_EQ(errorOf([&] { acc::refuseHeldOutRepeats(read({"drive.csv"}), read({"other.csv"})); }), "");
  for (const char* name : {"drive.csv", "copy.csv", "other.csv", "excerpt.csv"})
    std::remove((folder + "/" + name).c_str());
}
}  // namespace

// A bag whose every message is unusable is bad input, as a CSV without a usable row is: the reader
// refuses it with the count (RunReadError, the tools' exit 1) rather than handing the fit no run,
// which once ended in "valid data, no fit" with a mean speed of nan. Fails if it returns no runs.
TEST(RunArguments, ABagWithoutAUsableMessageIsRefusedAsACsvWithoutAUsableRowIs)
{
  const std::string path = testing::TempDir() + "/no_usable_message.bag";
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    for (int k = 0; k < 40; ++k)
    {
      acc_identification::RelativeState state = stateAt(100.0 + 0.1 * k);
      state.follower_speed_mps = 400.0;  // km/h read as m/s, and then some: outside the bounds
      bag.write("/relative_state", ros::Time(1.0), state);
    }
  }
  std::ostringstream log;
  try
  {
    acc::readRunArgument(path, acc::BagTopics{}, 0.5, log, acc::OpenAccPairSelector::first());
    ADD_FAILURE() << "a bag without a usable message gave runs";
  }
  catch (const acc::RunReadError& error)
  {
    EXPECT_NE(std::string(error.what()).find(path + ": no usable run (40 messages"), std::string::npos) << error.what();
  }
  EXPECT_NE(log.str().find("40 outside the plausibility bounds"), std::string::npos) << log.str();
  std::remove(path.c_str());
}

// --acc-setting chooses among a bag's settings; given with a CSV it was silently ignored (a file
// at min fitted when max was asked). It is refused, saying why.
TEST(RunArguments, AnAccSettingAskedOfACsvIsRefused)
{
  const std::string path = testing::TempDir() + "/acc_setting_of_a_csv.csv";
  acc::writeRunCsv(path, acc::synthesizeRun(acc::truthWithMargin(1.0), 60.0, 0.1, 20.0, 3));
  acc::BagTopics topics;
  topics.only_setting = "max";
  std::ostringstream log;
  const std::string refused =
      errorOf([&] { acc::readRunArgument(path, topics, 0.5, log, acc::OpenAccPairSelector::first()); });
  EXPECT_NE(refused.find("give --acc-setting with bags only"), std::string::npos) << refused;
  std::remove(path.c_str());
}
