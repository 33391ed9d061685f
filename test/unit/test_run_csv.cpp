#include <gtest/gtest.h>

#include <algorithm>

#include <cstdio>
#include <sstream>
#include <fstream>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "acc_identification/io/problem_lines.h"
#include "acc_identification/io/run_csv.h"
#include "run_matchers.h"


namespace
{
const std::string kDataDir = ACC_TEST_DATA_DIR;

TEST(RunCsv, CanonicalBadRowsAreRejectedWithLineNumbersAndSplitTheRun)
{
  const auto contents = acc::readRunFile(kDataDir + "/canonical_with_bad_rows.csv");
  EXPECT_EQ(contents.data_rows, 11u);
  // Line 5: not a number; line 8: time repeats; line 10: a field is missing.
  ASSERT_EQ(contents.rejected_rows, 3u);
  // ... and the one sample (0.7 s) left between two rejected rows is too short to simulate.
  ASSERT_EQ(contents.problems.size(), 4u);
  EXPECT_NE(contents.problems[0].find(":5: space gap is not a finite number: 'abc'"), std::string::npos)
      << contents.problems[0];
  EXPECT_NE(contents.problems[1].find(":8: time 0.5 s does not increase"), std::string::npos)
      << contents.problems[1];
  // The sample alone is named at its own line, before the row that left it alone: line order.
  EXPECT_NE(contents.problems[2].find(":9: a piece of one sample (t = 0.7 s)"), std::string::npos)
      << contents.problems[2];
  EXPECT_NE(contents.problems[3].find(":10: expected 4 fields, found 3"), std::string::npos)
      << contents.problems[3];
  // Usable pieces: 0.0-0.2 s, 0.4-0.5 s, 0.9-1.0 s.
  ASSERT_EQ(contents.runs.size(), 3u);
  EXPECT_EQ(contents.runs[0].size(), 3u);
  EXPECT_EQ(contents.runs[0].name, "canonical_with_bad_rows");
  EXPECT_EQ(contents.runs[1].size(), 2u);
  EXPECT_EQ(contents.runs[1].name, "canonical_with_bad_rows#2");
  EXPECT_EQ(contents.runs[2].size(), 2u);
  EXPECT_DOUBLE_EQ(contents.runs[2].time_s[0], 0.9);
  EXPECT_DOUBLE_EQ(contents.runs[2].leader_speed_mps[1], 10.5);
  for (const auto& run : contents.runs)
  {
    EXPECT_EQ(acc::describeRunProblem(run), "");
  }
}

TEST(RunCsv, ColumnsHandedOverAreJudgedByTheReadersRules)
{
  // Ten samples at 10 Hz as a DataFrame hands them over: a NaN at row 2, an implausible gap at
  // row 5, a hole of 2 s before row 8; rows are named by the numbers given (the frame's places).
  acc::CarFollowingRun columns;
  for (int i = 0; i < 10; ++i)
  {
    columns.time_s.push_back(0.1 * i + (i >= 8 ? 2.0 : 0.0));
    columns.space_gap_m.push_back(i == 5 ? 5000.0 : 20.0);
    columns.follower_speed_mps.push_back(i == 2 ? std::numeric_limits<double>::quiet_NaN() : 10.0);
    columns.leader_speed_mps.push_back(10.0);
  }
  const std::vector<std::size_t> rows{100, 101, 102, 103, 104, 105, 106, 107, 108, 109};
  const acc::RunFileContents contents =
      acc::assembleRunColumns("DataFrame 1", "mine", columns, rows, acc::RunPlausibilityBounds{});
  EXPECT_EQ(contents.data_rows, 10u);
  EXPECT_EQ(contents.rejected_rows, 2u);
  EXPECT_EQ(contents.implausible_rows, 1u);
  EXPECT_EQ(contents.time_holes, 1u);
  ASSERT_EQ(contents.problems.size(), 3u);
  EXPECT_NE(contents.problems[0].find("DataFrame 1:102: follower speed is not a finite number"), std::string::npos)
      << contents.problems[0];
  EXPECT_NE(contents.problems[1].find("DataFrame 1:105: space_gap_m 5000 outside"), std::string::npos)
      << contents.problems[1];
  EXPECT_NE(contents.problems[2].find("DataFrame 1:108: hole of"), std::string::npos) << contents.problems[2];
  // Pieces: rows 100-101, 103-104, 106-107, 108-109.
  ASSERT_EQ(contents.runs.size(), 4u);
  EXPECT_EQ(contents.runs[0].name, "mine");
  EXPECT_EQ(contents.runs[3].name, "mine#4");
  EXPECT_DOUBLE_EQ(contents.runs[3].time_s[0], 2.8);
  columns.leader_speed_mps.pop_back();
  EXPECT_THROW(acc::assembleRunColumns("DataFrame 1", "mine", columns, rows, acc::RunPlausibilityBounds{}),
               std::invalid_argument);
}

TEST(RunCsv, OpenAccColumnsAreMappedByNameAndAccOffSplits)
{
  const auto contents = acc::readRunFile(kDataDir + "/openacc_excerpt.csv");
  EXPECT_EQ(contents.data_rows, 6u);
  EXPECT_EQ(contents.rejected_rows, 0u);
  EXPECT_EQ(contents.acc_off_rows, 1u);
  ASSERT_EQ(contents.runs.size(), 2u);
  const auto& first = contents.runs[0];
  ASSERT_EQ(first.size(), 3u);
  EXPECT_DOUBLE_EQ(first.time_s[1], 100.1);
  EXPECT_DOUBLE_EQ(first.space_gap_m[1], 40.1);         // IVS1
  EXPECT_DOUBLE_EQ(first.follower_speed_mps[1], 29.1);  // Speed2
  EXPECT_DOUBLE_EQ(first.leader_speed_mps[1], 30.1);    // Speed1
  EXPECT_EQ(contents.runs[1].size(), 2u);
  EXPECT_DOUBLE_EQ(contents.runs[1].time_s[0], 100.4);
}

TEST(RunCsv, WriteThenReadGivesTheSameRun)
{
  acc::CarFollowingRun run;
  for (int i = 0; i < 5; ++i)
  {
    run.time_s.push_back(0.1 * i + 1.0 / 3.0);
    run.space_gap_m.push_back(20.0 + 0.123456789012345 * i);
    run.follower_speed_mps.push_back(10.0 / 7.0 * i);
    run.leader_speed_mps.push_back(11.0 + 1e-9 * i);
  }
  const std::string path = testing::TempDir() + "/run_csv_roundtrip.csv";
  acc::writeRunCsv(path, run);
  const auto runs = acc::readRuns(path);
  std::remove(path.c_str());
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].time_s, run.time_s);
  EXPECT_EQ(runs[0].space_gap_m, run.space_gap_m);
  EXPECT_EQ(runs[0].follower_speed_mps, run.follower_speed_mps);
  EXPECT_EQ(runs[0].leader_speed_mps, run.leader_speed_mps);
}

TEST(RunCsv, UnreadableFilesThrowWithTheReason)
{
  EXPECT_THROW(acc::readRunFile(kDataDir + "/does_not_exist.csv"), acc::RunReadError);
  const std::string path = testing::TempDir() + "/run_csv_no_header.csv";
  {
    FILE* file = std::fopen(path.c_str(), "w");
    std::fputs("a,b,c\n1,2,3\n", file);
    std::fclose(file);
  }
  try
  {
    acc::readRunFile(path);
    FAIL() << "expected RunReadError";
  }
  catch (const acc::RunReadError& error)
  {
    EXPECT_NE(std::string(error.what()).find("no header"), std::string::npos) << error.what();
  }
  std::remove(path.c_str());
}

/// Whether text contains part; reads better in an EXPECT with the text as the message.
bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

TEST(RunCsvPlausibility, ImpossibleFollowerSpeedIsRejectedWithItsLineAndColumnAndSplitsTheRun)
{
  const auto contents = acc::readRunFile(kDataDir + "/canonical_implausible_speed.csv");
  EXPECT_EQ(contents.data_rows, 7u);
  EXPECT_EQ(contents.rejected_rows, 1u);
  EXPECT_EQ(contents.implausible_rows, 1u);
  EXPECT_EQ(contents.time_holes, 0u);
  ASSERT_EQ(contents.problems.size(), 1u);
  EXPECT_TRUE(contains(contents.problems[0], "canonical_implausible_speed.csv:5: follower_speed_mps 1e+09 "
                                             "outside [-1, 100] m/s; row rejected, run split here"))
      << contents.problems[0];
  // 0.0-0.2 s before the bad row (line 5, t = 0.3 s), 0.4-0.6 s after it.
  ASSERT_EQ(contents.runs.size(), 2u);
  EXPECT_EQ(contents.runs[0].size(), 3u);
  EXPECT_DOUBLE_EQ(contents.runs[0].time_s.back(), 0.2);
  EXPECT_EQ(contents.runs[1].size(), 3u);
  EXPECT_DOUBLE_EQ(contents.runs[1].time_s.front(), 0.4);
  for (const auto& run : contents.runs)
  {
    for (double speed_mps : run.follower_speed_mps)
    {
      EXPECT_LT(speed_mps, 100.0);
    }
  }
}

TEST(RunCsvPlausibility, NegativeGapAndNegativeLeaderSpeedAreRejectedLikewise)
{
  const auto contents = acc::readRunFile(kDataDir + "/canonical_implausible_gap_and_leader.csv");
  EXPECT_EQ(contents.data_rows, 8u);
  EXPECT_EQ(contents.rejected_rows, 2u);
  EXPECT_EQ(contents.implausible_rows, 2u);
  ASSERT_EQ(contents.problems.size(), 2u);
  EXPECT_TRUE(contains(contents.problems[0], ":4: space_gap_m -50 outside [-2, 1000] m; row rejected"))
      << contents.problems[0];
  EXPECT_TRUE(contains(contents.problems[1], ":7: leader_speed_mps -30 outside [-1, 100] m/s; row rejected"))
      << contents.problems[1];
  // Pieces 0.0-0.1 s, 0.3-0.4 s, 0.6-0.7 s.
  ASSERT_EQ(contents.runs.size(), 3u);
  EXPECT_DOUBLE_EQ(contents.runs[1].time_s.front(), 0.3);
  EXPECT_DOUBLE_EQ(contents.runs[2].time_s.front(), 0.6);
  for (const auto& run : contents.runs)
  {
    EXPECT_EQ(run.size(), 2u);
  }
}

TEST(RunCsvPlausibility, ValuesJustInsideTheBoundsAreAcceptedAndJustOutsideRejected)
{
  // Lines 2-5 are inside or on the bounds (speeds -0.5, -1, 99, 100 m/s, leader -0.9 and 100 m/s,
  // gaps -1.5, -2, 999, 1000 m); lines 6, 9 and 12 are just outside, one quantity each.
  const auto contents = acc::readRunFile(kDataDir + "/canonical_near_bounds.csv");
  EXPECT_EQ(contents.data_rows, 13u);
  EXPECT_EQ(contents.rejected_rows, 3u);
  ASSERT_EQ(contents.problems.size(), 3u);
  EXPECT_TRUE(contains(contents.problems[0], ":6: space_gap_m -2.5 outside [-2, 1000] m")) << contents.problems[0];
  EXPECT_TRUE(contains(contents.problems[1], ":9: follower_speed_mps 100.5 outside [-1, 100] m/s"))
      << contents.problems[1];
  EXPECT_TRUE(contains(contents.problems[2], ":12: leader_speed_mps -1.5 outside [-1, 100] m/s"))
      << contents.problems[2];
  ASSERT_EQ(contents.runs.size(), 4u);
  const auto& inside = contents.runs[0];
  ASSERT_EQ(inside.size(), 4u);
  EXPECT_DOUBLE_EQ(inside.follower_speed_mps[0], -0.5);
  EXPECT_DOUBLE_EQ(inside.space_gap_m[0], -1.5);
  EXPECT_DOUBLE_EQ(inside.follower_speed_mps[2], 99.0);
  EXPECT_DOUBLE_EQ(inside.space_gap_m[3], 1000.0);
  EXPECT_DOUBLE_EQ(inside.follower_speed_mps[3], 100.0);
}

TEST(RunCsvPlausibility, HoleInTimeSplitsTheRunWithoutRejectingARow)
{
  // Rows at 1.0, 1.1, 11.1 and 11.2 s: one Euler step of 10 s unless split.
  const auto contents = acc::readRunFile(kDataDir + "/canonical_time_hole.csv");
  EXPECT_EQ(contents.data_rows, 4u);
  EXPECT_EQ(contents.rejected_rows, 0u);
  EXPECT_EQ(contents.time_holes, 1u);
  ASSERT_EQ(contents.problems.size(), 1u);
  EXPECT_TRUE(contains(contents.problems[0],
                       "canonical_time_hole.csv:4: hole of 10 s before this row (max 0.5 s); run split"))
      << contents.problems[0];
  ASSERT_EQ(contents.runs.size(), 2u);
  EXPECT_EQ(contents.runs[0].size(), 2u);
  EXPECT_DOUBLE_EQ(contents.runs[0].time_s.back(), 1.1);
  EXPECT_EQ(contents.runs[1].size(), 2u);
  EXPECT_DOUBLE_EQ(contents.runs[1].time_s.front(), 11.1);
  EXPECT_EQ(contents.runs[1].name, "canonical_time_hole#2");
}

TEST(RunCsvPlausibility, BoundsPassedByTheCallerAreHonoured)
{
  acc::RunPlausibilityBounds wide;
  wide.max_speed_mps = 2e9;
  wide.max_time_step_s = 20.0;
  const auto widened_speed = acc::readRunFile(kDataDir + "/canonical_implausible_speed.csv", wide);
  EXPECT_EQ(widened_speed.rejected_rows, 0u);
  ASSERT_EQ(widened_speed.runs.size(), 1u);
  EXPECT_EQ(widened_speed.runs[0].size(), 7u);
  const auto widened_step = acc::readRunFile(kDataDir + "/canonical_time_hole.csv", wide);
  EXPECT_EQ(widened_step.time_holes, 0u);
  ASSERT_EQ(widened_step.runs.size(), 1u);
  EXPECT_EQ(widened_step.runs[0].size(), 4u);

  acc::RunPlausibilityBounds wider_values;
  wider_values.min_speed_mps = -2.0;
  wider_values.max_speed_mps = 101.0;
  wider_values.min_space_gap_m = -3.0;
  const auto widened_values = acc::readRunFile(kDataDir + "/canonical_near_bounds.csv", wider_values);
  EXPECT_EQ(widened_values.rejected_rows, 0u);
  ASSERT_EQ(widened_values.runs.size(), 1u);
  EXPECT_EQ(widened_values.runs[0].size(), 13u);

  acc::RunPlausibilityBounds narrow;
  narrow.min_speed_mps = 0.0;
  const auto narrowed = acc::readRunFile(kDataDir + "/canonical_near_bounds.csv", narrow);
  EXPECT_EQ(narrowed.rejected_rows, 5u);  // lines 2 and 3 (follower -0.5 and -1 m/s) as well
  ASSERT_FALSE(narrowed.problems.empty());
  EXPECT_TRUE(contains(narrowed.problems[0], ":2: follower_speed_mps -0.5 outside [0, 100] m/s"))
      << narrowed.problems[0];
}

TEST(RunCsvPlausibility, UnusableBoundsAreRefusedBeforeAnyRow)
{
  acc::RunPlausibilityBounds crossed;
  crossed.min_space_gap_m = 10.0;
  crossed.max_space_gap_m = 5.0;
  EXPECT_THROW(acc::readRunFile(kDataDir + "/canonical_near_bounds.csv", crossed), std::invalid_argument);
  acc::RunPlausibilityBounds no_step;
  no_step.max_time_step_s = 0.0;
  EXPECT_THROW(acc::readRunFile(kDataDir + "/canonical_near_bounds.csv", no_step), std::invalid_argument);
  // Infinite bounds switch a check off; NaN is never plausible.
  acc::RunPlausibilityBounds unbounded;
  unbounded.max_speed_mps = std::numeric_limits<double>::infinity();
  EXPECT_EQ(acc::describeBoundsProblem(unbounded), "");
  EXPECT_EQ(acc::describeImplausibleValue(20.0, 1e12, 10.0, unbounded), "");
  EXPECT_NE(acc::describeImplausibleValue(std::numeric_limits<double>::quiet_NaN(), 10.0, 10.0, unbounded), "");
}

TEST(RunCsvPlausibility, OpenAccImpossibleSpeed2IsRejectedLikewise)
{
  const auto contents = acc::readRunFile(kDataDir + "/openacc_implausible_speed2.csv");
  EXPECT_EQ(contents.data_rows, 5u);
  EXPECT_EQ(contents.rejected_rows, 1u);
  EXPECT_EQ(contents.implausible_rows, 1u);
  ASSERT_EQ(contents.problems.size(), 1u);
  EXPECT_TRUE(contains(contents.problems[0], "openacc_implausible_speed2.csv:9: follower_speed_mps 1e+09 "
                                             "outside [-1, 100] m/s; row rejected, run split here"))
      << contents.problems[0];
  ASSERT_EQ(contents.runs.size(), 2u);
  EXPECT_DOUBLE_EQ(contents.runs[0].time_s.back(), 100.1);
  EXPECT_DOUBLE_EQ(contents.runs[1].time_s.front(), 100.3);
  EXPECT_DOUBLE_EQ(contents.runs[1].follower_speed_mps[0], 29.3);  // Speed2
}

TEST(RunCsvPlausibility, ReadRunsCountsImplausibleRowsAndHolesOnStderr)
{
  testing::internal::CaptureStderr();
  const auto speed_runs = acc::readRuns(kDataDir + "/canonical_implausible_speed.csv");
  const auto hole_runs = acc::readRuns(kDataDir + "/canonical_time_hole.csv");
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_EQ(speed_runs.size(), 2u);
  EXPECT_EQ(hole_runs.size(), 2u);
  EXPECT_TRUE(contains(log, ":5: follower_speed_mps 1e+09 outside [-1, 100] m/s")) << log;
  EXPECT_TRUE(contains(log, "canonical_implausible_speed.csv: 1 of 7 rows rejected (1 outside the plausibility "
                            "bounds, 0 duplicates), 0 holes in time split a run"))
      << log;
  EXPECT_TRUE(contains(log, ":4: hole of 10 s before this row (max 0.5 s); run split")) << log;
  EXPECT_TRUE(contains(log, "canonical_time_hole.csv: 0 of 4 rows rejected (0 outside the plausibility bounds, "
                            "0 duplicates), 1 holes in time split a run"))
      << log;
}

TEST(RunCsv, RealOpenAccCopyReadsWhole)
{
  const auto runs = acc::readRuns(kDataDir + "/casale_part4.csv");
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].size(), 1151u);
  EXPECT_NEAR(runs[0].durationS(), 115.0, 1e-6);
}

/// Writes text to a file in the test's temporary folder; returns its path.
std::string writeTemporary(const std::string& name, const std::string& text)
{
  const std::string path = testing::TempDir() + "/" + name;
  FILE* file = std::fopen(path.c_str(), "w");
  std::fwrite(text.data(), 1, text.size(), file);  // whole, NUL bytes too
  std::fclose(file);
  return path;
}

TEST(RunCsv, AnExactDuplicateRowIsRejectedAndCountedWithoutSplittingTheRun)
{
  const std::string path = writeTemporary("run_csv_duplicate.csv",
                                          "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n"
                                          "0.0,20.0,10.0,10.5\n0.1,20.05,10.01,10.5\n0.1,20.05,10.01,10.5\n"
                                          "0.2,20.1,10.02,10.5\n0.2,20.2,10.02,10.5\n0.3,20.15,10.03,10.5\n"
                                          "0.4,20.2,10.04,10.5\n");
  const auto contents = acc::readRunFile(path);
  EXPECT_EQ(contents.data_rows, 7u);
  // Line 4 repeats line 3: dropped, counted, the run goes on. Line 6 repeats line 5's time with
  // another gap: which one is right is unknown, so it is rejected and splits, as before.
  EXPECT_EQ(contents.rejected_rows, 2u);
  EXPECT_EQ(contents.duplicate_rows, 1u);
  ASSERT_EQ(contents.problems.size(), 2u);
  EXPECT_TRUE(contains(contents.problems[0], ":4: the same time and values as the row before; duplicate row "
                                             "rejected, run not split"))
      << contents.problems[0];
  EXPECT_TRUE(contains(contents.problems[1], ":6: time 0.2 s does not increase")) << contents.problems[1];
  ASSERT_EQ(contents.runs.size(), 2u);
  EXPECT_EQ(contents.runs[0].time_s, (std::vector<double>{0.0, 0.1, 0.2}));
  EXPECT_EQ(contents.runs[1].time_s, (std::vector<double>{0.3, 0.4}));
  std::remove(path.c_str());
}

// Cells and headers a reader could take the wrong way, each said rather than read silently: a
// column named twice (which one holds the data?), a hexadecimal cell (strtod reads 0x25 as 37),
// and a tab-separated export (named as a ';' one is).
TEST(RunCsv, AColumnNamedTwiceAHexadecimalCellAndTabsAreSaid)
{
  // The RunReadError of reading the file, or a note that it was read.
  const auto refusalOf = [](const std::string& path) -> std::string {
    try
    {
      acc::readRunFile(path);
    }
    catch (const acc::RunReadError& error)
    {
      return error.what();
    }
    return "read";
  };
  const std::string twice = writeTemporary("run_csv_twice.csv",
                                           "time_s,space_gap_m,follower_speed_mps,leader_speed_mps,space_gap_m\n"
                                           "0.0,20.0,10.0,10.5,25.0\n0.1,20.0,10.0,10.5,25.0\n");
  const std::string twice_said = refusalOf(twice);
  EXPECT_TRUE(contains(twice_said, ":1: the header names column 'space_gap_m' twice")) << twice_said;
  const std::string hexadecimal = writeTemporary("run_csv_hex.csv",
                                                 "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n"
                                                 "0.0,20.0,10.0,10.5\n0.1,0x25,10.0,10.5\n0.2,20.0,10.0,10.5\n");
  const auto contents = acc::readRunFile(hexadecimal);
  EXPECT_EQ(contents.rejected_rows, 1u);  // line 3, not a gap of 37 m
  bool said = false;
  for (const std::string& problem : contents.problems)
    said = said || contains(problem, "run_csv_hex.csv:3: space gap is not a finite number: '0x25'");
  EXPECT_TRUE(said);
  const std::string tabs = writeTemporary("run_csv_tabs.csv",
                                          "time_s\tspace_gap_m\tfollower_speed_mps\tleader_speed_mps\n0.0\t20\t10\t10\n");
  const std::string tabs_said = refusalOf(tabs);
  EXPECT_TRUE(contains(tabs_said, "its fields are separated by tabs")) << tabs_said;
  // Files that are not comma-separated text are said to be what their first bytes show, not quoted.
  const std::string mac = writeTemporary("run_csv_mac.csv", "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\r"
                                                            "0.0,20,10,10\r0.1,20,10,10\r");
  const std::string mac_said = refusalOf(mac);
  EXPECT_TRUE(contains(mac_said, "its lines end in a carriage return alone")) << mac_said;
  EXPECT_FALSE(contains(mac_said, "its first line reads")) << mac_said;
  const std::string utf16_text("\xFF\xFEt\0i\0m\0e\0", 10);
  const std::string utf16 = writeTemporary("run_csv_utf16.csv", utf16_text);
  const std::string utf16_said = refusalOf(utf16);
  EXPECT_TRUE(contains(utf16_said, "it is UTF-16 text")) << utf16_said;
  const std::string bag = writeTemporary("run_csv_bag.csv", std::string("#ROSBAG V2.0\nE\0\0\0\x20", 18));
  const std::string bag_said = refusalOf(bag);
  EXPECT_TRUE(contains(bag_said, "it is a ROS bag")) << bag_said;
  for (const std::string& path : {mac, utf16, bag})
    std::remove(path.c_str());
  // A header that names the columns almost right is shown in the refusal.
  const std::string near = writeTemporary("run_csv_near.csv", "Time,Gap,FollowerSpeed,LeaderSpeed\n0.0,20,10,10\n");
  const std::string near_said = refusalOf(near);
  EXPECT_TRUE(contains(near_said, "(its first line reads 'Time,Gap,FollowerSpeed,LeaderSpeed')")) << near_said;
  // The same name in two cases is one column named twice.
  const std::string cases = writeTemporary("run_csv_cases.csv",
                                           "time_s,space_gap_m,follower_speed_mps,leader_speed_mps,Space_Gap_M\n"
                                           "0.0,20.0,10.0,10.5,25.0\n");
  const std::string cases_said = refusalOf(cases);
  EXPECT_TRUE(contains(cases_said, "the header names column 'Space_Gap_M' twice")) << cases_said;
  for (const std::string& path : {twice, hexadecimal, tabs, near, cases})
    std::remove(path.c_str());
}

// A number too small for a double is the nearest one (strtod flags it out of range, yet it is what
// the text says: a speed of 1e-320 m/s is a standing car); one too large is not finite.
TEST(RunCsv, NumbersBeyondADoublesRangeAreReadAsTheirNearestOrNotFinite)
{
  const std::string path = writeTemporary("run_csv_range.csv",
                                          "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n"
                                          "0.0,20.0,1e-320,0.0\n0.1,20.0,0.0,-1e-400\n0.2,20.0,0.0,0.0\n"
                                          "0.3,1e400,0.0,0.0\n");
  const auto contents = acc::readRunFile(path);
  std::remove(path.c_str());
  EXPECT_EQ(contents.rejected_rows, 1u);
  ASSERT_EQ(contents.problems.size(), 1u);
  EXPECT_TRUE(contains(contents.problems[0], "run_csv_range.csv:5: space gap is not a finite number: '1e400'"))
      << contents.problems[0];
  ASSERT_EQ(contents.runs.size(), 1u);
  ASSERT_EQ(contents.runs[0].size(), 3u);
  EXPECT_GT(contents.runs[0].follower_speed_mps[0], 0.0);
  EXPECT_LT(contents.runs[0].follower_speed_mps[0], 1e-300);
  EXPECT_EQ(contents.runs[0].leader_speed_mps[1], 0.0);
}

// Speeds in km/h above the plausible bound reject every row: the refusal says km/h, and the log
// lists the first rows and counts the rest instead of a line per row (1,140 on a Casale run).
TEST(RunCsv, SpeedsTooFastInMostRowsAreSaidToBeKilometresPerHour)
{
  std::string text = "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n";
  for (int k = 0; k < 200; ++k)
    text += std::to_string(0.1 * k) + ",40.0," + std::to_string(3.6 * (30.0 + 0.01 * k)) + "," +
            std::to_string(3.6 * 31.0) + "\n";  // each row's own value: one line each
  const std::string path = writeTemporary("run_csv_kmh.csv", text);
  acc::RunFileContents contents = acc::readRunFile(path);
  EXPECT_EQ(contents.too_fast_rows, 200u);
  std::ostringstream log;
  try
  {
    acc::reportAndTakeRuns(path, contents, log);
    ADD_FAILURE() << "no run should be usable";
  }
  catch (const acc::RunReadError& error)
  {
    EXPECT_TRUE(contains(error.what(), "the speeds are likely in km/h; convert them to m/s")) << error.what();
  }
  const std::string said = log.str();
  EXPECT_TRUE(contains(said, "190 more such lines not listed (most rows too fast; counted below)")) << said;
  EXPECT_LT(std::count(said.begin(), said.end(), '\n'), 15) << said;
  std::remove(path.c_str());
}

// The canonical columns are read in any case (the unit is in the name), and a note says which.
TEST(RunCsv, TheCanonicalColumnsAreReadInAnyCaseAndSaid)
{
  const std::string plain = writeTemporary("run_csv_lower.csv",
                                           "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n"
                                           "0.0,20.0,10.0,10.5\n0.1,20.05,10.01,10.5\n");
  const std::string capitals = writeTemporary("run_csv_capitals.csv",
                                              "Time_s,SPACE_GAP_M,follower_speed_mps,Leader_Speed_mps\n"
                                              "0.0,20.0,10.0,10.5\n0.1,20.05,10.01,10.5\n");
  const acc::RunFileContents expected = acc::readRunFile(plain);
  const acc::RunFileContents contents = acc::readRunFile(capitals);
  ASSERT_EQ(contents.runs.size(), 1u);
  EXPECT_EQ(contents.runs[0].space_gap_m, expected.runs[0].space_gap_m);
  EXPECT_EQ(contents.runs[0].leader_speed_mps, expected.runs[0].leader_speed_mps);
  EXPECT_TRUE(expected.notes.empty());
  ASSERT_EQ(contents.notes.size(), 1u);
  EXPECT_TRUE(contains(contents.notes[0], "columns read in another case: 'Time_s' as time_s, 'SPACE_GAP_M' as "
                                          "space_gap_m, 'Leader_Speed_mps' as leader_speed_mps"))
      << contents.notes[0];
  for (const std::string& path : {plain, capitals})
    std::remove(path.c_str());
}

TEST(RunCsv, SpreadsheetExportsReadAsThePlainFile)
{
  // A byte-order mark before the header, quoted fields (one with a comma inside a quoted note
  // column), Windows line ends: the same four values as the plain file.
  const std::string plain = writeTemporary("run_csv_plain.csv",
                                           "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n"
                                           "0.0,20.0,10.0,10.5\n0.1,20.05,10.01,10.5\n0.2,20.1,10.02,10.5\n");
  const std::string exported = writeTemporary(
      "run_csv_exported.csv",
      "\xEF\xBB\xBF\"time_s\",\"space_gap_m\",\"follower_speed_mps\",\"leader_speed_mps\",\"note\"\r\n"
      "\"0.0\",\"20.0\",\"10.0\",\"10.5\",\"start, on \"\"ACC\"\"\"\r\n"
      "0.1,20.05,10.01,10.5,\r\n\"0.2\", 20.1 ,10.02,10.5,x\r\n");
  const auto b = acc::readRunFile(exported);
  EXPECT_EQ(b.rejected_rows, 0u);
  acc_test::expectTheSameSingleRun(acc::readRunFile(plain), b);
  std::remove(plain.c_str());
  std::remove(exported.c_str());
}

// Consecutive lines of one file with one reason are one entry naming the range; another reason, a
// line that does not follow on, another file or a problem of another form ends it. Fails when
// stretches are merged across reasons or gaps, or a problem is lost or reordered.
TEST(ProblemLines, ConsecutiveLinesWithOneReasonAreOneRange)
{
  const std::vector<std::string> problems = {
      "a.csv:7: IVS1 empty; row rejected", "a.csv:8: IVS1 empty; row rejected", "a.csv:9: IVS1 empty; row rejected",
      "a.csv:10: Speed2 NaN; row rejected",  "a.csv:12: Speed2 NaN; row rejected", "b.csv:13: Speed2 NaN; row rejected",
      "a.csv: 5 of 90 rows rejected",       "C:/runs/c.csv:4: x: y",            "C:/runs/c.csv:5: x: y"};
  EXPECT_EQ(acc::condenseProblemLines(problems),
            (std::vector<std::string>{"a.csv:7-9 (3 lines): IVS1 empty; row rejected",
                                      "a.csv:10: Speed2 NaN; row rejected", "a.csv:12: Speed2 NaN; row rejected",
                                      "b.csv:13: Speed2 NaN; row rejected", "a.csv: 5 of 90 rows rejected",
                                      "C:/runs/c.csv:4-5 (2 lines): x: y"}));
  EXPECT_TRUE(acc::condenseProblemLines({}).empty());
}

// A stretch of empty gap cells is one warning on the log, while the contents keep one problem per
// row and the counts stay whole. Fails when the log lists every row again, or the reader's own
// problems are condensed.
TEST(ProblemLines, AStretchOfBadRowsIsOneWarningOnTheLog)
{
  const std::string path = (std::filesystem::temp_directory_path() / "acc_stretch_of_bad_rows.csv").string();
  {
    std::ofstream file(path);
    file << "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n";
    for (int i = 0; i < 20; ++i)
      file << 0.1 * i << "," << (i >= 5 && i < 12 ? std::string() : std::string("20")) << ",10,10\n";
  }
  acc::RunFileContents contents = acc::readRunFile(path);
  EXPECT_EQ(contents.rejected_rows, 7u);
  EXPECT_EQ(contents.problems.size(), 7u);
  std::ostringstream log;
  const std::vector<acc::CarFollowingRun> runs = acc::reportAndTakeRuns(path, contents, log);
  EXPECT_EQ(runs.size(), 2u);
  EXPECT_TRUE(contains(log.str(), "warning: " + path + ":7-13 (7 lines): space gap"));
  EXPECT_TRUE(contains(log.str(), "7 of 20 rows rejected")) << log.str();
  EXPECT_FALSE(contains(log.str(), path + ":8:")) << log.str();
  std::remove(path.c_str());
}

// The optional valid column (nmea_to_csv writes the pairing's verdict in it): a row marked 0 is a
// split point whatever its values, counted with the reason beside it; 0.0, 1.0 (as pandas writes a
// flag column with a gap) and TRUE are flags too; a flag that is neither is a malformed row. Fails when the column is ignored (the NaN row would be rejected as
// not a number, the 50 m row used).
TEST(RunCsv, ARowTheValidColumnMarksZeroSplitsTheRunWithItsReason)
{
  const std::string path = (std::filesystem::temp_directory_path() / "acc_valid_column.csv").string();
  {
    std::ofstream file(path);
    file << "time_s,space_gap_m,follower_speed_mps,leader_speed_mps,valid,invalid_reason\n";
    for (int i = 0; i < 12; ++i)
    {
      const bool jump = i == 4, unknown = i == 5, bad_flag = i == 9;
      file << 0.1 * i << "," << (jump ? "50" : unknown ? "" : "20") << ",10,10,"
           << (jump ? "0" : unknown ? "0.0" : bad_flag ? "maybe" : i == 2 ? "TRUE" : i == 3 ? "1.0" : "1") << ","
           << (jump ? "\"gap jump of 30 m, too fast\"" : "\"\"") << "\n";
    }
  }
  const acc::RunFileContents contents = acc::readRunFile(path);
  std::remove(path.c_str());
  EXPECT_EQ(contents.data_rows, 12u);
  EXPECT_EQ(contents.marked_invalid_rows, 2u);
  EXPECT_EQ(contents.rejected_rows, 3u);
  ASSERT_EQ(contents.problems.size(), 3u);
  EXPECT_TRUE(contains(contents.problems[0], ":6: marked invalid: gap jump of 30 m, too fast; row rejected"))
      << contents.problems[0];
  EXPECT_TRUE(contains(contents.problems[1], ":7: marked invalid; row rejected")) << contents.problems[1];
  EXPECT_TRUE(contains(contents.problems[2], ":11: valid is neither 0 nor 1 (nor false or true): 'maybe'")) << contents.problems[2];
  ASSERT_EQ(contents.runs.size(), 3u);  // 0.0-0.3, 0.6-0.8, 1.0-1.1
  EXPECT_EQ(contents.runs[0].size(), 4u);
  EXPECT_EQ(contents.runs[1].size(), 3u);
  EXPECT_EQ(contents.runs[2].size(), 2u);
}
}  // namespace

// A 10 Hz file whose time is in milliseconds: every step is 100 "s". That is no coarse receiver, and
// the advice to raise the largest step would fit nonsense: the text says the time is not in
// seconds. Fails when it gives the 1 Hz advice.
TEST(RunCsvPlausibility, AFileWhoseTimeIsInMillisecondsIsToldSo)
{
  std::string text = "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n";
  for (int k = 0; k < 40; ++k)
    text += std::to_string(1600000 + 100 * k) + ",20.0,10.0,10.0\n";
  const std::string path = writeTemporary("run_csv_ms.csv", text);
  const auto contents = acc::readRunFile(path);
  EXPECT_EQ(contents.shortest_step_s, 100.0);
  const std::string said = acc::describeCoarseSteps(contents);
  EXPECT_TRUE(contains(said, "even the shortest step is 100: no car-following log steps that coarsely, so the time is "
                             "not in seconds")) << said;
  EXPECT_FALSE(contains(said, "set it above their step")) << said;
  std::remove(path.c_str());
}

// A 10 Hz run whose rows are shuffled: half go back in time and are rejected, and the forward
// steps between the rest are holes. The counts said the data were recorded coarsely and advised a
// larger --max-gap; they now say the rows are not in time order, and nothing of the rate.
TEST(RunCsvPlausibility, AFileWhoseRowsAreShuffledIsToldToSortThem)
{
  std::vector<int> order(300);
  for (int k = 0; k < 300; ++k)
    order[static_cast<std::size_t>(k)] = (k * 7919) % 300;  // a fixed permutation (7919 is prime)
  std::string text = "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n";
  for (const int k : order)
    text += std::to_string(0.1 * k) + ",20.0,10.0,10.0\n";
  const std::string path = writeTemporary("run_csv_shuffled.csv", text);
  const auto contents = acc::readRunFile(path);
  EXPECT_GT(10 * contents.time_back_rows, contents.data_rows);
  const std::string order_said = acc::describeTimeOrder(contents);
  EXPECT_TRUE(contains(order_said, " rows go back in time from the row before: the rows are not in time order; sort "
                                   "them by time")) << order_said;
  EXPECT_EQ(acc::describeCoarseSteps(contents), "");
  EXPECT_EQ(acc::describeTimeOrder(acc::readRunFile(kDataDir + "/canonical_time_hole.csv")), "");
  std::remove(path.c_str());
}

// Speeds negated throughout (a sign error) fail the lower bound on every row: said once as what
// it likely is, the row lines capped as for speeds in km/h (2,523 lines once, and no hint).
TEST(RunCsvPlausibility, AFileWhoseSpeedsAreNegatedIsAskedAboutTheSign)
{
  std::string text = "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n";
  for (int k = 0; k < 200; ++k)
    text += std::to_string(0.1 * k) + ",20.0," + std::to_string(-10.0 - 0.01 * k) + ",-10.5\n";  // lines differ
  const std::string path = writeTemporary("run_csv_negated.csv", text);
  auto contents = acc::readRunFile(path);
  EXPECT_EQ(contents.negative_rows, 200u);
  EXPECT_TRUE(contains(acc::describeSign(contents), "200 of its 200 rows have a speed or a gap below its bound: a "
                                                    "sign error?")) << acc::describeSign(contents);
  std::ostringstream log;
  EXPECT_THROW(acc::reportAndTakeRuns(path, contents, log), acc::RunReadError);
  EXPECT_TRUE(contains(log.str(), "190 more such lines not listed (most rows below a bound; counted below)"))
      << log.str();
  EXPECT_EQ(acc::describeSign(acc::readRunFile(kDataDir + "/canonical_time_hole.csv")), "");
  std::remove(path.c_str());
}

// Every pair of a 1 Hz OpenACC platoon read at once: the steps are counted over the pairs too, so
// the file's counts say it is coarse (they once summed the holes but not the steps, and said nothing).
TEST(RunCsvPlausibility, EveryPairOfACoarseOpenAccFileIsSaidToBeCoarse)
{
  std::string text = "Date,8,10,2019\nVehicle_order,A,B,C\nNumber_of_vehicles,3\nACC,1\nDistance_setting,S\n"
                     "Time,Speed1,Speed2,Speed3,IVS1,IVS2\n";
  for (int k = 0; k < 30; ++k)
    text += std::to_string(100 + k) + ",10.0,10.0,10.0,20.0,20.0\n";
  const std::string path = writeTemporary("openacc_1hz.csv", text);
  const auto contents = acc::readRunFile(path, acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::all());
  EXPECT_EQ(contents.time_steps, 58u);  // 29 per pair
  EXPECT_EQ(contents.time_holes, 58u);
  EXPECT_TRUE(contains(acc::describeCoarseSteps(contents), "; 58 of its 58 steps are such holes"))
      << acc::describeCoarseSteps(contents);
  std::remove(path.c_str());
}

// A 1 Hz file against the default 0.5 s max gap: every step is a hole, every row alone. The counts
// and the error say that the data are coarser than a run may step, and what to set.
TEST(RunCsvPlausibility, AFileCoarserThanTheMaxGapIsSaidToBeSo)
{
  std::string text = "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n";
  for (int k = 0; k < 40; ++k)
    text += std::to_string(k) + ",20.0,10.0,10.0\n";
  const std::string path = writeTemporary("run_csv_1hz.csv", text);
  const auto contents = acc::readRunFile(path);
  EXPECT_EQ(contents.time_steps, 39u);
  EXPECT_EQ(contents.time_holes, 39u);
  EXPECT_TRUE(contents.runs.empty());
  const std::string hint = "; 39 of its 39 steps are such holes: the data are recorded more coarsely than the largest "
                           "step a run may hold (a receiver at 1 Hz against the default 0.5 s); set it above their "
                           "step (the tools' --max-gap, Python's max_gap_s, the identifier's ~max_gap_s)";
  EXPECT_EQ(acc::describeCoarseSteps(contents), hint);
  EXPECT_TRUE(contains(acc::describeRowCounts(path, contents), hint));
  testing::internal::CaptureStderr();
  try
  {
    acc::readRuns(path);
    ADD_FAILURE() << "no run is usable, so readRuns must throw";
  }
  catch (const acc::RunReadError& error)
  {
    EXPECT_TRUE(contains(error.what(), "no usable run (40 data rows")) << error.what();
    EXPECT_TRUE(contains(error.what(), hint)) << error.what();
  }
  testing::internal::GetCapturedStderr();
  // Raised above the step, the same file is one run; and a file with one hole in many steps gets no hint.
  acc::RunPlausibilityBounds wide;
  wide.max_time_step_s = 2.5;
  EXPECT_EQ(acc::readRunFile(path, wide).runs.size(), 1u);
  EXPECT_EQ(acc::describeCoarseSteps(acc::readRunFile(kDataDir + "/canonical_time_hole.csv")), "");
  std::remove(path.c_str());
}
