#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "acc_identification/io/run_csv.h"

namespace aci = acc_identification;

namespace
{
const std::string kDataDir = ACC_TEST_DATA_DIR;

TEST(RunCsv, CanonicalBadRowsAreRejectedWithLineNumbersAndSplitTheRun)
{
  const auto contents = aci::readRunFile(kDataDir + "/canonical_with_bad_rows.csv");
  EXPECT_EQ(contents.data_rows, 11u);
  // Line 5: not a number; line 8: time repeats; line 10: a field is missing.
  ASSERT_EQ(contents.rejected_rows, 3u);
  // ... and the one sample (0.7 s) left between two rejected rows is too short to simulate.
  ASSERT_EQ(contents.problems.size(), 4u);
  EXPECT_NE(contents.problems[0].find(":5: space gap is not a finite number: 'abc'"), std::string::npos)
      << contents.problems[0];
  EXPECT_NE(contents.problems[1].find(":8: time 0.5 s does not increase"), std::string::npos)
      << contents.problems[1];
  EXPECT_NE(contents.problems[2].find(":10: expected 4 fields, found 3"), std::string::npos)
      << contents.problems[2];
  EXPECT_NE(contents.problems[3].find("a piece of one sample (t = 0.7 s)"), std::string::npos)
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
    EXPECT_EQ(aci::describeRunProblem(run), "");
  }
}

TEST(RunCsv, OpenAccColumnsAreMappedByNameAndAccOffSplits)
{
  const auto contents = aci::readRunFile(kDataDir + "/openacc_excerpt.csv");
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
  aci::CarFollowingRun run;
  for (int i = 0; i < 5; ++i)
  {
    run.time_s.push_back(0.1 * i + 1.0 / 3.0);
    run.space_gap_m.push_back(20.0 + 0.123456789012345 * i);
    run.follower_speed_mps.push_back(10.0 / 7.0 * i);
    run.leader_speed_mps.push_back(11.0 + 1e-9 * i);
  }
  const std::string path = testing::TempDir() + "/run_csv_roundtrip.csv";
  aci::writeRunCsv(path, run);
  const auto runs = aci::readRuns(path);
  std::remove(path.c_str());
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].time_s, run.time_s);
  EXPECT_EQ(runs[0].space_gap_m, run.space_gap_m);
  EXPECT_EQ(runs[0].follower_speed_mps, run.follower_speed_mps);
  EXPECT_EQ(runs[0].leader_speed_mps, run.leader_speed_mps);
}

TEST(RunCsv, UnreadableFilesThrowWithTheReason)
{
  EXPECT_THROW(aci::readRunFile(kDataDir + "/does_not_exist.csv"), aci::RunReadError);
  const std::string path = testing::TempDir() + "/run_csv_no_header.csv";
  {
    FILE* file = std::fopen(path.c_str(), "w");
    std::fputs("a,b,c\n1,2,3\n", file);
    std::fclose(file);
  }
  try
  {
    aci::readRunFile(path);
    FAIL() << "expected RunReadError";
  }
  catch (const aci::RunReadError& error)
  {
    EXPECT_NE(std::string(error.what()).find("no header"), std::string::npos) << error.what();
  }
  std::remove(path.c_str());
}

TEST(RunCsv, RealOpenAccCopyReadsWhole)
{
  const auto runs = aci::readRuns(kDataDir + "/casale_part4.csv");
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].size(), 1151u);
  EXPECT_NEAR(runs[0].durationS(), 115.0, 1e-6);
}
}  // namespace
