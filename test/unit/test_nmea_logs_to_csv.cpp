// nmea_to_csv's library: two receivers' NMEA logs paired in batch as relative_state_node pairs
// them live, written as a run CSV whose invalid rows the run readers split at. Real data: JRC
// OpenACC Casale part 3 ((c) European Union, CC BY 4.0) converted to the two receivers' logs.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
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

/// Casale part 3's two receivers' logs, as they recorded it, into folder's L.nmea and F.nmea.
void writeCasaleLogs(const TemporaryFolder& folder)
{
  const acc::OpenAccPairTrack track = acc::readOpenAccPairTrack(std::string(ACC_OPENACC_DATA_DIR) + "/part3.csv");
  ASSERT_EQ(track.error, "");
  std::string error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("L.nmea"), acc::openAccFixes(track, 1), "GN", error)) << error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("F.nmea"), acc::openAccFixes(track, 2), "GN", error)) << error;
}

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

// The two logs of a real drive given the wrong way round pair as well as the right way (the gap is
// a distance, the same either way), but the gap then grows where the Doppler speeds say the cars
// close in: refused with the slope that shows it, and nothing written; the right order passes.
// Fails if swapped logs give a run, which would hold the two cars' speeds exchanged.
TEST(NmeaLogsToCsv, LogsGivenTheWrongWayRoundAreRefusedAndNothingIsWritten)
{
  TemporaryFolder folder("nmea_logs_swapped");
  writeCasaleLogs(folder);
  ASSERT_FALSE(HasFatalFailure());
  EXPECT_EQ(acc::pairNmeaLogs(folder.file("L.nmea"), folder.file("F.nmea"), casaleSettings()).error, "");
  const acc::RelativeStateLogs swapped =
      acc::pairNmeaLogsToCsv(folder.file("F.nmea"), folder.file("L.nmea"), folder.file("run.csv"), casaleSettings());
  EXPECT_NE(swapped.error.find("the LEADER log is of the car behind. Are the two logs swapped?"), std::string::npos)
      << swapped.error;
  EXPECT_NE(swapped.error.find("slope -"), std::string::npos) << swapped.error;
  EXPECT_NE(swapped.error.find("Give the car ahead's log first"), std::string::npos) << swapped.error;  // whole
  EXPECT_FALSE(fs::exists(folder.file("run.csv")));
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

namespace
{
/// Casale part 3's two receivers' fixes, changed by `change` (leader, follower), paired from logs.
template <typename Change>
acc::RelativeStateLogs pairChangedLogs(const std::string& name, Change change,
                                       const acc::RelativeStateSettings& settings = casaleSettings())
{
  const acc::OpenAccPairTrack track = acc::readOpenAccPairTrack(std::string(ACC_OPENACC_DATA_DIR) + "/part3.csv");
  std::vector<acc::GnssFix> leader = acc::openAccFixes(track, 1), follower = acc::openAccFixes(track, 2);
  change(leader, follower);
  TemporaryFolder folder(name);
  std::string error;
  EXPECT_TRUE(acc::writeNmeaLog(folder.file("L.nmea"), leader, "GN", error)) << error;
  EXPECT_TRUE(acc::writeNmeaLog(folder.file("F.nmea"), follower, "GN", error)) << error;
  return acc::pairNmeaLogs(folder.file("L.nmea"), folder.file("F.nmea"), settings);
}
}  // namespace

// The clocks of the two logs, as the batch feeds them: a log played twice pairs twice, loop by loop
// (the two loops' times no longer interleave: half the epochs were lost); a follower whose clock
// goes back alone pairs nothing after it (its positions would meet the leader's of another moment:
// gaps hundreds of metres off, all valid); a few fixes stamped far back are no new clock.
TEST(NmeaLogsToCsv, EachLogsClocksArePairedAsTheyRan)
{
  const acc::RelativeStateLogs loop = pairChangedLogs("nmea_logs_loop", [](auto& leader, auto& follower) {
    const std::size_t n = leader.size();
    leader.insert(leader.end(), leader.begin(), leader.begin() + static_cast<std::ptrdiff_t>(n));
    follower.insert(follower.end(), follower.begin(), follower.begin() + static_cast<std::ptrdiff_t>(n));
  });
  EXPECT_EQ(loop.pairing.follower_unpaired, 0u);
  EXPECT_EQ(loop.pairing.follower_time_resets, 1u);
  const std::size_t half = loop.states.size() / 2;
  // Each drive pairs as it does alone: no epoch of the second clock fed with the first's stretch.
  const acc::RelativeStateLogs once = pairChangedLogs("nmea_logs_once", [](auto&, auto&) {});
  EXPECT_EQ(loop.states.size(), 2 * once.states.size());
  EXPECT_EQ(loop.pairing.follower_stray_stamps + loop.pairing.leader_stray_stamps, 0u);
  // The same with the follower's receiver started 2 s after the leader's and stopped 3 s before it:
  // each log's clock goes back at another fix, and each loop still pairs as the shortened drive alone.
  const auto shortened = [](auto&, auto& follower) {
    follower.erase(follower.end() - 30, follower.end());
    follower.erase(follower.begin(), follower.begin() + 20);
  };
  const acc::RelativeStateLogs shortened_once = pairChangedLogs("nmea_logs_short_once", shortened);
  const acc::RelativeStateLogs shortened_loop = pairChangedLogs("nmea_logs_short_loop", [&](auto& leader, auto& follower) {
    shortened(leader, follower);
    const auto l = static_cast<std::ptrdiff_t>(leader.size()), f = static_cast<std::ptrdiff_t>(follower.size());
    leader.insert(leader.end(), leader.begin(), leader.begin() + l);
    follower.insert(follower.end(), follower.begin(), follower.begin() + f);
  });
  EXPECT_EQ(shortened_once.states.size(), once.states.size() - 50);
  EXPECT_EQ(shortened_loop.states.size(), 2 * shortened_once.states.size());
  EXPECT_EQ(shortened_loop.pairing.follower_unpaired, 0u);
  EXPECT_EQ(shortened_loop.pairing.leader_time_resets, 1u);
  EXPECT_EQ(shortened_loop.pairing.follower_time_resets, 1u);
  EXPECT_EQ(shortened_loop.pairing.follower_stray_stamps + shortened_loop.pairing.leader_stray_stamps, 0u);
  const acc::RelativeStateLogs jumped = pairChangedLogs("nmea_logs_jump", [&](auto&, auto& follower) {
    for (std::size_t i = follower.size() / 2; i < follower.size(); ++i)
      follower[i].gnss_time_s -= 20.0;
  });
  EXPECT_EQ(jumped.error, "");
  EXPECT_EQ(jumped.pairing.follower_time_resets, 1u);
  EXPECT_EQ(jumped.states.size() + jumped.pairing.follower_unpaired, half);
  EXPECT_LE(jumped.states.size(), half / 2 + 1);
  for (const acc::RelativeState& state : jumped.states)
    EXPECT_LT(state.space_gap_m, 100.0) << "at " << state.time_s;
  const acc::RelativeStateLogs stray = pairChangedLogs("nmea_logs_stray", [](auto&, auto& follower) {
    for (std::size_t i = 1000; i < 1003; ++i)
      follower[i].gnss_time_s -= 3600.0;
  });
  EXPECT_EQ(stray.pairing.follower_stray_stamps, 3u);
  EXPECT_EQ(stray.pairing.follower_unpaired, 0u);
  EXPECT_EQ(stray.pairing.follower_time_resets, 0u);
  EXPECT_EQ(stray.states.size(), half - 3);
  // Six in a row, but on no one clock (an hour back, two hours back, in turn): stray stamps for the
  // batch's split as for the pairing (one rule, ClockResetRule). The split once took them for a
  // new clock while the pairing did not, and fed the rest of the follower's log after all of the
  // leader's: every later epoch unpaired once the leader's fixes had outrun the pairing's buffer
  // (200 fixes here, against this short log's 1200).
  acc::RelativeStateSettings small_buffer = casaleSettings();
  small_buffer.pairing.max_buffered_fixes = 200;
  const acc::RelativeStateLogs two_clocks = pairChangedLogs("nmea_logs_two_clocks", [](auto&, auto& follower) {
    for (std::size_t i = 1000; i < 1006; ++i)
      follower[i].gnss_time_s -= i % 2 == 0 ? 3600.0 : 7200.0;
  }, small_buffer);
  EXPECT_EQ(two_clocks.pairing.follower_stray_stamps, 6u);
  EXPECT_EQ(two_clocks.pairing.follower_time_resets, 0u);
  EXPECT_EQ(two_clocks.pairing.follower_unpaired, 0u);
  EXPECT_EQ(two_clocks.states.size(), half - 6);
  // One follower fix stamped 10 s, one leader fix an hour, ahead: stray stamps. Such a stamp was
  // taken for the stream's time, which the next fixes then seemed to fall back from: a reset, and
  // more than half the epochs unpaired (audit).
  const acc::RelativeStateLogs ahead = pairChangedLogs("nmea_logs_ahead", [](auto& leader, auto& follower) {
    follower[1000].gnss_time_s += 10.0;
    leader[500].gnss_time_s += 3600.0;
  });
  EXPECT_EQ(ahead.pairing.follower_stray_stamps, 1u);
  EXPECT_EQ(ahead.pairing.leader_stray_stamps, 1u);
  EXPECT_EQ(ahead.pairing.follower_time_resets + ahead.pairing.leader_time_resets, 0u);
  EXPECT_LE(ahead.pairing.follower_unpaired, 1u);  // the follower epoch at the leader's stray, if any
  EXPECT_GE(ahead.states.size(), half - 2);
}

// A log that cannot be read is an error, and nothing is paired.
TEST(NmeaLogsToCsv, AMissingLogIsAnError)
{
  const acc::RelativeStateLogs logs = acc::pairNmeaLogs("/nonexistent/L.nmea", "/nonexistent/F.nmea", casaleSettings());
  EXPECT_NE(logs.error.find("/nonexistent/L.nmea"), std::string::npos) << logs.error;
  EXPECT_TRUE(logs.states.empty());
}

// Logs an hour apart pair nothing: that is said with the fixes each gave, and no CSV is written
// (a header alone would read as a run file that holds nothing); a CSV that cannot be written is an
// error.
TEST(NmeaLogsToCsv, LogsThatNeverMeetAreSaidToAndAnUnwritableCsvIsAnError)
{
  const acc::OpenAccPairTrack track = acc::readOpenAccPairTrack(std::string(ACC_OPENACC_DATA_DIR) + "/part3.csv");
  ASSERT_EQ(track.error, "");
  std::vector<acc::GnssFix> leader = acc::openAccFixes(track, 1);
  for (acc::GnssFix& fix : leader)
    fix.gnss_time_s += 3600.0;
  TemporaryFolder folder("nmea_logs_to_csv_apart");
  std::string error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("L.nmea"), leader, "GN", error)) << error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("F.nmea"), acc::openAccFixes(track, 2), "GN", error)) << error;
  const acc::RelativeStateLogs apart =
      acc::pairNmeaLogsToCsv(folder.file("L.nmea"), folder.file("F.nmea"), folder.file("out.csv"), casaleSettings());
  EXPECT_EQ(apart.error, "");
  EXPECT_TRUE(apart.states.empty());
  const std::string reason = acc::noStateReason(apart);
  EXPECT_NE(reason.find("no follower epoch could be paired"), std::string::npos) << reason;
  EXPECT_NE(reason.find(std::to_string(track.rows.size()) + " follower"), std::string::npos) << reason;
  EXPECT_FALSE(fs::exists(folder.file("out.csv")));

  ASSERT_TRUE(acc::writeNmeaLog(folder.file("L.nmea"), acc::openAccFixes(track, 1), "GN", error)) << error;
  const acc::RelativeStateLogs unwritable = acc::pairNmeaLogsToCsv(
      folder.file("L.nmea"), folder.file("F.nmea"), "/nonexistent/out.csv", casaleSettings());
  EXPECT_NE(unwritable.error.find("/nonexistent/out.csv"), std::string::npos) << unwritable.error;
}

// One log given as both receivers' once gave the antenna offset as every gap (-5.6 m), each state
// valid; antenna offsets far too large give gaps below what a run reader accepts, said with a count.
TEST(NmeaLogsToCsv, OneLogTwiceIsRefusedAndImplausibleGapsAreCounted)
{
  TemporaryFolder folder("nmea_logs_implausible");
  writeCasaleLogs(folder);
  ASSERT_FALSE(HasFatalFailure());
  const acc::RelativeStateLogs same =
      acc::pairNmeaLogsToCsv(folder.file("L.nmea"), folder.file("./L.nmea"), folder.file("run.csv"), casaleSettings());
  EXPECT_NE(same.error.find("LEADER and FOLLOWER are the same log"), std::string::npos) << same.error;
  EXPECT_FALSE(fs::exists(folder.file("run.csv")));

  acc::RelativeStateSettings far = casaleSettings();
  far.geometry.leader_antenna_to_rear_bumper_m = 60.0;  // the gaps come out tens of metres below 0
  const acc::RelativeStateLogs logs = acc::pairNmeaLogs(folder.file("L.nmea"), folder.file("F.nmea"), far);
  ASSERT_EQ(logs.error, "");
  EXPECT_GT(acc::implausibleGapStates(logs), logs.states.size() / 2);
  EXPECT_NE(acc::describeImplausibleGaps(logs).find("which the run readers reject as implausible"), std::string::npos);
  EXPECT_EQ(acc::implausibleGapStates(acc::pairNmeaLogs(folder.file("L.nmea"), folder.file("F.nmea"), casaleSettings())),
            0u);
  EXPECT_EQ(acc::relativeStateLogsJson(logs)["implausible_gap_states"], acc::implausibleGapStates(logs));
}

// A receiver without satellites (or in simulation mode, as a Garmin GPSmap 76S logs) writes
// fixes with no usable position: the logs meet in time, and the reason nothing pairs is that, not
// the overlap. Every follower fix is in the one-line account.
TEST(NmeaLogsToCsv, AFollowerWithoutAFixIsSaidToAndEveryFixIsAccounted)
{
  const acc::OpenAccPairTrack track = acc::readOpenAccPairTrack(std::string(ACC_OPENACC_DATA_DIR) + "/part3.csv");
  ASSERT_EQ(track.error, "");
  std::vector<acc::GnssFix> follower = acc::openAccFixes(track, 2);
  for (acc::GnssFix& fix : follower)
    fix.valid_fields &= ~acc::GnssFix::kValidPosition;
  TemporaryFolder folder("nmea_logs_to_csv_no_fix");
  std::string error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("L.nmea"), acc::openAccFixes(track, 1), "GN", error)) << error;
  ASSERT_TRUE(acc::writeNmeaLog(folder.file("F.nmea"), follower, "GN", error)) << error;
  const acc::RelativeStateLogs logs =
      acc::pairNmeaLogsToCsv(folder.file("L.nmea"), folder.file("F.nmea"), folder.file("out.csv"), casaleSettings());
  ASSERT_EQ(logs.error, "");
  const std::string reason = acc::noStateReason(logs);
  EXPECT_NE(reason.find("none of the follower's " + std::to_string(track.rows.size()) + " fixes has a usable position"),
            std::string::npos)
      << reason;
  const std::string account = acc::fixAccount(logs.pairing);
  EXPECT_NE(account.find(std::to_string(track.rows.size()) + " follower and 0 leader fixes without a usable position"),
            std::string::npos)
      << account;
}

namespace
{
/// A parameter file with the given text, in a folder of its own (name: the file's and the folder's).
struct ParameterFile
{
  ParameterFile(const std::string& name, const std::string& text) : folder("nmea_logs_to_csv_" + name), name(name)
  {
    std::ofstream(path()) << text;
  }
  std::string path() const { return folder.file(name + ".yaml"); }
  TemporaryFolder folder;
  std::string name;
};
}  // namespace

// The node's own parameter file gives the settings the node would pair with, its geometry
// included; the options override it, and its keys are read whole (the node's own too).
TEST(NmeaLogsToCsv, TheNodesParameterFileSetsThePairingAndTheOptionsOverrideIt)
{
  acc::NmeaPairingOptions options;
  options.params_path = std::string(ACC_CONFIG_DIR) + "/relative_state.yaml";
  acc::RelativeStateSettings settings;
  settings.geometry = {-7.0, -7.0};
  std::string note = "not yet";
  ASSERT_EQ(acc::pairingSettingsFrom(options, settings, note), "");
  EXPECT_EQ(note, "") << "every key of the shipped file is the node's";
  EXPECT_NEAR(settings.geometry.combinedOffset(), 5.60, 1e-12);  // the file places the antennas

  const ParameterFile one_hertz("one_hertz", "antenna_offset_m: 4.0\ndropout_gap_s: 2.5\nmax_interpolation_skew_s: 1.2\n"
                                "gap_mode: along_track\nmax_gap: 3.0\n");
  options.params_path = one_hertz.path();
  options.antennas.leader_antenna_to_rear_bumper_m = 1.0;
  options.antennas.follower_antenna_to_front_bumper_m = 2.5;
  options.gap_mode = "straight_line";
  settings = acc::RelativeStateSettings{};
  ASSERT_EQ(acc::pairingSettingsFrom(options, settings, note), "");
  EXPECT_EQ(settings.pairing.dropout_gap_s, 2.5);
  EXPECT_EQ(settings.pairing.max_interpolation_skew_s, 1.2);
  EXPECT_EQ(settings.gap_mode, acc::GapMode::kStraightLine) << "the option overrides the file";
  EXPECT_EQ(settings.geometry.leader_antenna_to_rear_bumper_m, 1.0);
  EXPECT_EQ(settings.geometry.follower_antenna_to_front_bumper_m, 2.5);
  EXPECT_NE(note.find("~max_gap is set but never read"), std::string::npos) << note;
}

// A file that does not place the antennas needs the options to; a value the node would refuse
// is refused with the node's words and the file's name.
TEST(NmeaLogsToCsv, AParameterFileIsReadAsTheNodeReadsIt)
{
  const ParameterFile unplaced("unplaced", "dropout_gap_s: 2.5\n");
  acc::NmeaPairingOptions options;
  options.params_path = unplaced.path();
  acc::RelativeStateSettings settings;
  std::string note;
  const std::string missing = acc::pairingSettingsFrom(options, settings, note);
  EXPECT_NE(missing.find("say where the antennas are"), std::string::npos) << missing;
  EXPECT_NE(missing.find("the parameter file does not say it"), std::string::npos) << missing;

  const ParameterFile slip("slip", "antenna_offset_m: 5.6\ntimeout_s: 1e6\n");
  options.params_path = slip.path();
  const std::string refused = acc::pairingSettingsFrom(options, settings, note);
  EXPECT_NE(refused.find(slip.path() + ": parameter ~timeout_s is the string \"1e6\", not a number"), std::string::npos)
      << refused;
  const ParameterFile both("both", "antenna_offset_m: 5.6\nleader_antenna_to_rear_bumper_m: 2.0\n");
  options.params_path = both.path();
  EXPECT_NE(acc::pairingSettingsFrom(options, settings, note).find("not both"), std::string::npos);
  // A tolerance near a receiver's step pairs neighbouring epochs (0.1 s at 10 Hz: one epoch off).
  const ParameterFile loose("loose", "antenna_offset_m: 5.6\nexact_match_tolerance_s: 0.1\n");
  options.params_path = loose.path();
  const std::string too_loose = acc::pairingSettingsFrom(options, settings, note);
  EXPECT_NE(too_loose.find("~exact_match_tolerance_s 0.1 must be at most 0.01 s"), std::string::npos) << too_loose;
  // A time_reset_s below the receiver's step takes every new clock for stray stamps: refused, in
  // the file and against an option that raises the dropout gap past it.
  const ParameterFile short_reset("short_reset", "antenna_offset_m: 5.6\ntime_reset_s: 0.8\ndropout_gap_s: 2.5\n");
  options.params_path = short_reset.path();
  settings = acc::RelativeStateSettings{};
  const std::string too_short = acc::pairingSettingsFrom(options, settings, note);
  EXPECT_NE(too_short.find("~time_reset_s 0.8 must exceed ~dropout_gap_s 2.5"), std::string::npos) << too_short;
  options.params_path.clear();
  options.antennas.combined_m = 5.6;
  options.dropout_gap_s = 6.0;
  settings = acc::RelativeStateSettings{};
  const std::string option_past = acc::pairingSettingsFrom(options, settings, note);
  EXPECT_NE(option_past.find("--dropout-gap-s 6: ~time_reset_s 5 must exceed ~dropout_gap_s 6"), std::string::npos)
      << option_past;
}
