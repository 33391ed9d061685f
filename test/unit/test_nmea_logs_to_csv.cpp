// nmea_to_csv's library: two receivers' NMEA logs paired in batch as relative_state_node pairs
// them live, written as a run CSV whose invalid rows the run readers split at. Real data: JRC
// OpenACC Casale part 3 ((c) European Union, CC BY 4.0) converted to the two receivers' logs.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "acc_identification/conversion/nmea_logs_to_csv.h"
#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/model/sample_statistics.h"

namespace fs = std::filesystem;

namespace
{
class TemporaryFolder
{
public:
  explicit TemporaryFolder(const std::string& name)
    : path_(fs::temp_directory_path() / (name + "_" + std::to_string(::getpid())))
  {
    fs::create_directories(path_);
  }
  ~TemporaryFolder() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
  fs::path path_;
};

acc::RelativeStateSettings casaleSettings()
{
  acc::RelativeStateSettings settings;
  settings.geometry.leader_antenna_to_rear_bumper_m = 5.60;  // hypot(E1-E2, N1-N2) - IVS1 on every row
  return settings;
}
}  // namespace

// Every epoch of a real drive paired, one receiver's position jumping 40 m for one epoch: that
// state is invalid, written with its reason, and the CSV reader splits the run there and counts it.
TEST(NmeaLogsToCsv, ARealDriveRoundTripsThroughTheRunReaderWithItsInvalidStateAsASplitPoint)
{
  const acc::OpenAccPairTrack track = acc::readOpenAccPairTrack(std::string(ACC_OPENACC_DATA_DIR) + "/part3.csv");
  ASSERT_EQ(track.error, "");
  std::vector<acc::GnssFix> follower = acc::openAccFixes(track, 2);
  const std::size_t jumped = follower.size() / 2;
  follower[jumped].latitude_deg += 40.0 / 111e3;  // 40 m north for one epoch
  TemporaryFolder folder("nmea_logs_to_csv");
  std::string error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("L.nmea"), acc::openAccFixes(track, 1), "GN", error)) << error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("F.nmea"), follower, "GN", error)) << error;

  const acc::RelativeStateLogs logs = acc::pairNmeaLogs(folder.file("L.nmea"), folder.file("F.nmea"), casaleSettings());
  ASSERT_EQ(logs.error, "");
  ASSERT_EQ(logs.states.size(), track.rows.size());  // every epoch paired, the last ones too
  EXPECT_EQ(logs.pairing.follower_unpaired, 0u);
  std::size_t invalid = 0;
  for (const acc::RelativeState& state : logs.states)
    invalid += state.valid ? 0 : 1;
  EXPECT_EQ(invalid, logs.estimator.invalid_states);
  EXPECT_GE(invalid, 1u);
  EXPECT_FALSE(logs.states[jumped].valid);
  EXPECT_NE(logs.states[jumped].invalid_reason.find("gap jump"), std::string::npos) << logs.states[jumped].invalid_reason;
  const nlohmann::json json = acc::relativeStateLogsJson(logs);
  EXPECT_EQ(json["states"], logs.states.size());
  EXPECT_EQ(json["valid_states"], logs.states.size() - invalid);
  EXPECT_EQ(json["pairing"]["follower_fixes"], track.rows.size());

  ASSERT_TRUE(acc::writeRelativeStateCsv(folder.file("run.csv"), logs.states, error)) << error;
  const acc::RunFileContents read = acc::readRunFile(folder.file("run.csv"));
  EXPECT_EQ(read.data_rows, logs.states.size());
  EXPECT_EQ(read.marked_invalid_rows, invalid);
  EXPECT_EQ(read.rejected_rows, invalid);
  EXPECT_EQ(acc::sampleCount(read.runs), logs.states.size() - invalid);
  EXPECT_GE(read.runs.size(), 2u);  // split at the jump
  bool reason_listed = false;
  for (const std::string& problem : read.problems)
    reason_listed = reason_listed || problem.find("marked invalid: gap jump") != std::string::npos;
  EXPECT_TRUE(reason_listed);
  // The values as written: the gap to the millimetre, the speeds to 0.1 mm/s.
  const acc::CarFollowingRun& first = read.runs.front();
  EXPECT_NEAR(first.space_gap_m[10], logs.states[10].space_gap_m, 0.0006);
  EXPECT_NEAR(first.follower_speed_mps[10], logs.states[10].follower_speed_mps, 0.00006);
  EXPECT_NEAR(first.time_s[10], logs.states[10].time_s, 0.0006);
}

// The leader's log stops 2 s before the follower's: the follower's last epochs, which live would
// wait for leader data, are counted unpaired at the end of the logs, never left out unsaid.
TEST(NmeaLogsToCsv, FollowerEpochsAfterTheLeadersLogEndsAreCountedUnpaired)
{
  const acc::OpenAccPairTrack track = acc::readOpenAccPairTrack(std::string(ACC_OPENACC_DATA_DIR) + "/part3.csv");
  ASSERT_EQ(track.error, "");
  std::vector<acc::GnssFix> leader = acc::openAccFixes(track, 1);
  leader.resize(leader.size() - 20);
  TemporaryFolder folder("nmea_logs_to_csv_end");
  std::string error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("L.nmea"), leader, "GN", error)) << error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("F.nmea"), acc::openAccFixes(track, 2), "GN", error)) << error;
  const acc::RelativeStateLogs logs = acc::pairNmeaLogs(folder.file("L.nmea"), folder.file("F.nmea"), casaleSettings());
  EXPECT_EQ(logs.pairing.follower_unpaired, 20u);
  EXPECT_EQ(logs.states.size() + logs.pairing.follower_unpaired, track.rows.size());
  EXPECT_GE(logs.epoch_events, 20u);
}

// A log that cannot be read is an error, and nothing is paired.
TEST(NmeaLogsToCsv, AMissingLogIsAnError)
{
  const acc::RelativeStateLogs logs = acc::pairNmeaLogs("/nonexistent/L.nmea", "/nonexistent/F.nmea", casaleSettings());
  EXPECT_NE(logs.error.find("/nonexistent/L.nmea"), std::string::npos) << logs.error;
  EXPECT_TRUE(logs.states.empty());
}
