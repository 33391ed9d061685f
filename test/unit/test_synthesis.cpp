// The synthetic drive: deterministic from its seed, a truth that obeys the ACC model, logs that
// parse back, a road with curves, and unmodelled effects that change the follower as they should.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/gnss/nmea_log.h"
#include "acc_identification/gnss/utc_date.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/reproduction/lead_profiles.h"
#include "acc_identification/synthesis/road_centreline.h"
#include "acc_identification/synthesis/synthesis.h"
#include "acc_identification/synthesis/synthesis_output.h"

namespace acc
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

std::string tempPath(const std::string& name)
{
  return testing::TempDir() + "synthesis_" + name;
}

std::string readFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream content;
  content << in.rdbuf();
  return content.str();
}

SynthesisOptions shortDrive(std::uint64_t seed, const AccParameters& parameters = paperMinimumSetting())
{
  SynthesisOptions options;
  options.profile = 'F';
  options.parameters = parameters;
  options.seed = seed;
  options.duration_s = 120.0;
  return options;
}

double maxAbsDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
    worst = std::max(worst, std::abs(a[k] - b[k]));
  return worst;
}

TEST(Synthesis, SameSeedGivesIdenticalBytesAndAnotherSeedDoesNot)
{
  std::string logs[3];
  const std::uint64_t seeds[3] = {7, 7, 8};
  for (int i = 0; i < 3; ++i)
  {
    const SynthesizedDrive drive = synthesizeDrive(shortDrive(seeds[i]));
    std::string error;
    const std::string path = tempPath("det_" + std::to_string(i) + ".nmea");
    ASSERT_TRUE(writeNmeaLog(path, drive.leader_fixes, "GN", error)) << error;
    logs[i] = readFile(path);
  }
  EXPECT_FALSE(logs[0].empty());
  EXPECT_EQ(logs[0], logs[1]);
  EXPECT_NE(logs[0], logs[2]);
}

TEST(Synthesis, TruthIsThePaperModelFinerThanTheFit)
{
  const SynthesizedDrive drive = synthesizeDrive(shortDrive(3));
  const CarFollowingRun& truth = drive.truth.run;
  ASSERT_EQ(truth.size(), 1201u);  // 120 s at 10 Hz
  ASSERT_EQ(describeRunProblem(truth), "");
  // The lead column is profile F itself.
  const std::vector<double> lead = leadProfile('F', 0.1);
  for (std::size_t k = 0; k < truth.size(); ++k)
    ASSERT_EQ(truth.leader_speed_mps[k], lead[k]);
  // Started in equilibrium, and the rest is the paper's model integrated ten times finer than the
  // 10 Hz Euler recursion a calibration fits: close to that recursion, but not it (no inverse
  // crime, so a calibration of the truth is not exact by construction).
  const AccParameters p = paperMinimumSetting();
  EXPECT_NEAR(truth.space_gap_m[0], p.eta_m + p.tau_e_s * lead[0], 1e-12);
  EXPECT_EQ(truth.follower_speed_mps[0], lead[0]);
  const SimulatedFollower replay = simulateFollower(p, truth);
  EXPECT_GT(maxAbsDifference(replay.speed_mps, truth.follower_speed_mps), 1e-3);
  EXPECT_LT(maxAbsDifference(replay.speed_mps, truth.follower_speed_mps), 0.1);
  EXPECT_GT(maxAbsDifference(replay.space_gap_m, truth.space_gap_m), 1e-3);
  EXPECT_LT(maxAbsDifference(replay.space_gap_m, truth.space_gap_m), 0.5);
  // Positions advance with the same fine integration: the bumpers are the gap apart.
  for (std::size_t k = 0; k < truth.size(); ++k)
    ASSERT_NEAR(drive.truth.leader_rear_bumper_m[k] - drive.truth.follower_front_bumper_m[k], truth.space_gap_m[k], 1e-9);
  // The follower really follows: its speed changes with the lead's oscillation.
  const auto [low, high] = std::minmax_element(truth.follower_speed_mps.begin(), truth.follower_speed_mps.end());
  EXPECT_GT(*high - *low, 3.0);
}

TEST(Synthesis, AOneHertzReceiverReportsEverySecondOfATruthStillSimulatedTenTimesFiner)
{
  SynthesisOptions options = shortDrive(3);
  options.epoch_step_s = 1.0;
  const SynthesizedDrive drive = synthesizeDrive(options);
  const CarFollowingRun& truth = drive.truth.run;
  ASSERT_EQ(truth.size(), 121u);  // 120 s at 1 Hz
  ASSERT_EQ(drive.leader_fixes.size(), 121u);
  ASSERT_EQ(drive.follower_fixes.size(), 121u);
  for (std::size_t k = 1; k < truth.size(); ++k)
  {
    ASSERT_EQ(truth.time_s[k] - truth.time_s[k - 1], 1.0);
    ASSERT_NEAR(drive.follower_fixes[k].gnss_time_s - drive.follower_fixes[k - 1].gnss_time_s, 1.0, 1e-6);
  }
  // The paper's Euler recursion at the recorded 1 s step departs from the truth far more than at
  // 10 Hz: the bias calibrate's Euler step line measures.
  const SimulatedFollower replay = simulateFollower(paperMinimumSetting(), truth);
  const CarFollowingRun truth_10hz = synthesizeDrive(shortDrive(3)).truth.run;
  const SimulatedFollower replay_10hz = simulateFollower(paperMinimumSetting(), truth_10hz);
  EXPECT_GT(maxAbsDifference(replay.speed_mps, truth.follower_speed_mps),
            5.0 * maxAbsDifference(replay_10hz.speed_mps, truth_10hz.follower_speed_mps));
  const auto [low, high] = std::minmax_element(truth.follower_speed_mps.begin(), truth.follower_speed_mps.end());
  EXPECT_GT(*high - *low, 3.0);
}

TEST(Synthesis, TruthCsvHoldsTheSimulationExactly)
{
  const SynthesizedDrive drive = synthesizeDrive(shortDrive(3));
  const std::string path = tempPath("truth.csv");
  std::string error;
  ASSERT_TRUE(writeTruthCsv(path, drive.truth.run, &error)) << error;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time_s,space_gap_m,follower_speed_mps,leader_speed_mps");
  std::size_t k = 0;
  while (std::getline(in, line))
  {
    double t, s, v, u;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &t, &s, &v, &u), 4) << line;
    ASSERT_LT(k, drive.truth.run.size());
    EXPECT_EQ(s, drive.truth.run.space_gap_m[k]);
    EXPECT_EQ(v, drive.truth.run.follower_speed_mps[k]);
    ++k;
  }
  EXPECT_EQ(k, drive.truth.run.size());
}

TEST(Synthesis, LogsParseBackWithNoBadSentence)
{
  const SynthesisOptions options = shortDrive(5);
  const SynthesizedDrive drive = synthesizeDrive(options);
  const std::vector<GnssFix>* fixes[2] = {&drive.leader_fixes, &drive.follower_fixes};
  for (int i = 0; i < 2; ++i)
  {
    const std::string path = tempPath("parse_" + std::to_string(i) + ".nmea");
    std::string error;
    ASSERT_TRUE(writeNmeaLog(path, *fixes[i], "GN", error)) << error;
    const NmeaLogResult log = readNmeaLog(path);
    ASSERT_EQ(log.error, "");
    EXPECT_EQ(log.statistics.rejected(), 0u);
    EXPECT_EQ(log.statistics.sentences_ok, 2 * fixes[i]->size());
    ASSERT_EQ(log.fixes.size(), fixes[i]->size());
    for (std::size_t k = 0; k < log.fixes.size(); ++k)
    {
      const GnssFix& read = log.fixes[k];
      ASSERT_TRUE(read.has_date);
      EXPECT_NEAR(read.gnss_time_s, options.start_time_unix_s + 0.1 * static_cast<double>(k), 1e-3);
      EXPECT_NEAR(read.latitude_deg, (*fixes[i])[k].latitude_deg, 1e-6);
      EXPECT_NEAR(read.speed_over_ground_mps, (*fixes[i])[k].speed_over_ground_mps, 1e-3);
    }
  }
}

TEST(Synthesis, RoadHasCurvesAndTheCarsFollowIt)
{
  SynthesisOptions options = shortDrive(9);
  options.duration_s = 0.0;  // all of profile F, about 430 s, 8 km
  const SynthesizedDrive drive = synthesizeDrive(options);
  double min_course = 10.0, max_course = -10.0;
  for (const GnssFix& fix : drive.follower_fixes)
  {
    ASSERT_TRUE(fix.has(GnssFix::kValidCourse));
    // Unwrapped around the start heading (1 rad): the pattern turns at most 50 deg either way.
    const double course = std::remainder(fix.course_rad - options.start_heading_rad, 2.0 * kPi);
    min_course = std::min(min_course, course);
    max_course = std::max(max_course, course);
  }
  EXPECT_GT(max_course - min_course, 40.0 * kPi / 180.0);
  // The straight-line gap between the true antennas is the model's gap, within the chord's
  // shortening on the arcs (a few cm).
  double worst = 0.0;
  for (std::size_t k = 0; k < drive.truth.run.size(); ++k)
    worst = std::max(worst, std::abs(drive.straight_line_gap_m[k] - drive.truth.run.space_gap_m[k]));
  EXPECT_LT(worst, 0.05);
  EXPECT_GT(worst, 0.0);  // curved, so the chord is not the arc somewhere
}

TEST(RoadCentreline, ArcsAreExact)
{
  // A quarter circle of radius 100 m turning right from north ends 100 m east and 100 m north.
  const RoadCentreline road({{100.0 * kPi / 2.0, 0.01}}, 1.0, 0.0);
  const RoadPoint end = road.at(100.0 * kPi / 2.0);
  EXPECT_NEAR(end.east_m, 100.0, 1e-9);
  EXPECT_NEAR(end.north_m, 100.0, 1e-9);
  EXPECT_NEAR(end.heading_rad, kPi / 2.0, 1e-12);
  const RoadPoint behind = road.at(-10.0);
  EXPECT_NEAR(behind.north_m, -10.0, 1e-12);
  EXPECT_THROW(RoadCentreline({}, 1.0, 0.0), std::invalid_argument);
}

TEST(SynthesisEffects, ActuationLagSlowsTheFollowerAndIsTheAugmentedModel)
{
  const SynthesizedDrive base = synthesizeDrive(shortDrive(2));
  SynthesisOptions options = shortDrive(2);
  std::string error;
  ASSERT_TRUE(addEffectOption("actuation_lag=1.0", &options.effects, &error)) << error;
  const SynthesizedDrive lagged = synthesizeDrive(options);
  const CarFollowingRun& run = lagged.truth.run;
  // Same leader, different follower; the truth is the diagnosis's augmented model, integrated
  // finer than its 10 Hz recursion: close to it, far closer than to the model without the lag.
  EXPECT_EQ(run.leader_speed_mps, base.truth.run.leader_speed_mps);
  EXPECT_GT(maxAbsDifference(run.follower_speed_mps, base.truth.run.follower_speed_mps), 0.2);
  const SimulatedFollower replay = simulateFollower(options.parameters, options.effects, run);
  EXPECT_GT(maxAbsDifference(replay.speed_mps, run.follower_speed_mps), 0.0);
  EXPECT_LT(maxAbsDifference(replay.speed_mps, run.follower_speed_mps), 0.1);
  // A lag makes the follower react later: its first speed drop after the lead's first one comes later.
  auto firstDrop = [](const std::vector<double>& v) {
    for (std::size_t k = 1; k < v.size(); ++k)
      if (v[k] < v[0] - 0.5)
        return k;
    return v.size();
  };
  EXPECT_GT(firstDrop(run.follower_speed_mps), firstDrop(base.truth.run.follower_speed_mps));
}

TEST(SynthesisEffects, AccelerationLimitsBoundTheFollower)
{
  SynthesisOptions options = shortDrive(2);
  std::string error;
  ASSERT_TRUE(addEffectOption("acceleration_limits=0.4,0.6", &options.effects, &error)) << error;
  auto extremes = [](const CarFollowingRun& run) {
    double up = 0.0, down = 0.0;
    for (std::size_t k = 1; k < run.size(); ++k)
    {
      const double a = (run.follower_speed_mps[k] - run.follower_speed_mps[k - 1]) / 0.1;
      up = std::max(up, a);
      down = std::min(down, a);
    }
    return std::make_pair(up, down);
  };
  const auto limited = extremes(synthesizeDrive(options).truth.run);
  const auto free = extremes(synthesizeDrive(shortDrive(2)).truth.run);
  EXPECT_LE(limited.first, 0.4 + 1e-9);
  EXPECT_GE(limited.second, -0.6 - 1e-9);
  EXPECT_GT(free.first, 0.5);
  EXPECT_LT(free.second, -0.7);
}

TEST(SynthesisEffects, SensorTimeOffsetShiftsTheRecordedLeader)
{
  SynthesisOptions options = shortDrive(2);
  std::string error;
  ASSERT_TRUE(addEffectOption("sensor_time_offset=0.5", &options.effects, &error)) << error;
  const SynthesizedDrive drive = synthesizeDrive(options);
  const std::vector<double> lead = leadProfile('F', 0.1);
  // The leader's receiver tags the truth 0.5 s late: recorded(t) = true(t - 0.5).
  for (std::size_t k = 5; k < drive.truth.run.size(); ++k)
    ASSERT_NEAR(drive.truth.run.leader_speed_mps[k], lead[k - 5], 1e-9);
  // The follower reacted to the true leader, so the base model on the recorded data misfits.
  const SimulatedFollower base = simulateFollower(options.parameters, drive.truth.run);
  EXPECT_GT(maxAbsDifference(base.speed_mps, drive.truth.run.follower_speed_mps), 0.05);
}

TEST(SynthesisEffects, EffectOptionsAreCheckedAndCombine)
{
  EffectSettings settings;
  std::string error;
  EXPECT_FALSE(addEffectOption("warp_drive=1", &settings, &error));
  EXPECT_NE(error.find("actuation_lag"), std::string::npos);  // the message lists the names
  EXPECT_FALSE(addEffectOption("acceleration_limits=1.0", &settings, &error));
  EXPECT_FALSE(addEffectOption("actuation_lag=abc", &settings, &error));
  EXPECT_FALSE(addEffectOption("actuation_lag=-1", &settings, &error));
  ASSERT_TRUE(addEffectOption("actuation_lag=0.5", &settings, &error)) << error;
  ASSERT_TRUE(addEffectOption("set_speed_cruise=25,0.3", &settings, &error)) << error;
  EXPECT_FALSE(addEffectOption("actuation_lag=0.7", &settings, &error));
  EXPECT_EQ(settings.actuation_lag_s, 0.5);
  EXPECT_EQ(settings.set_speed_mps, 25.0);
  EXPECT_EQ(settings.cruise_gain_per_s, 0.3);
  const std::vector<EffectKind> on = effectsOn(settings);
  ASSERT_EQ(on.size(), 2u);
  SynthesisOptions options;
  options.effects = settings;
  options.parameters = paperMaximumSetting();
  const std::string json = synthesisJson(options, "max");
  EXPECT_NE(json.find("\"actuation_lag\""), std::string::npos);
  EXPECT_NE(json.find("\"set_speed_cruise\""), std::string::npos);
  EXPECT_NE(json.find("\"k1_per_s2\""), std::string::npos);
}

// A file that cannot be written takes the ones written before it along: the logs of a drive whose
// truth never reached its CSV were left behind, looking like a whole synthesis.
TEST(Synthesis, ADriveIsWrittenWholeOrNotAtAll)
{
  const SynthesisOptions options = shortDrive(3);
  const SynthesizedDrive drive = synthesizeDrive(options);
  SynthesisFiles files{tempPath("whole_L.nmea"), tempPath("whole_F.nmea"), "/nonexistent/truth.csv", ""};
  std::ostringstream log;
  EXPECT_FALSE(writeSynthesisFiles(drive, options, "min", files, log));
  EXPECT_NE(log.str().find("/nonexistent/truth.csv"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("were removed"), std::string::npos) << log.str();
  EXPECT_FALSE(std::ifstream(files.leader_log).good());
  EXPECT_FALSE(std::ifstream(files.follower_log).good());
  files.truth_csv = tempPath("whole_truth.csv");
  EXPECT_TRUE(writeSynthesisFiles(drive, options, "min", files, log)) << log.str();
  EXPECT_TRUE(std::ifstream(files.leader_log).good());
  for (const std::string& path : {files.leader_log, files.follower_log, files.truth_csv})
    std::remove(path.c_str());
}

TEST(Synthesis, UtcTimesParse)
{
  double t = 0.0;
  ASSERT_TRUE(parseUtcTime("2026-05-12T10:00:00Z", &t));
  EXPECT_EQ(t, 1778580000.0);
  ASSERT_TRUE(parseUtcTime("1970-01-01T00:00:01.5", &t));
  EXPECT_EQ(t, 1.5);
  EXPECT_FALSE(parseUtcTime("2026-02-30T10:00:00", &t));
  EXPECT_FALSE(parseUtcTime("2026-05-12 10:00:00", &t));
  EXPECT_FALSE(parseUtcTime("2026-05-12T10:00:00+02", &t));
}

// A log's two-digit year holds 1980-2079 (the readers' rule, nmeaYear): a start outside would be
// read back a century off, as 1969 once came back as 2069.
TEST(Synthesis, StartTimesOutsideTheNmeaYearsAreTold)
{
  double t = 0.0;
  ASSERT_TRUE(parseUtcTime("1969-12-31T23:59:00Z", &t));
  EXPECT_FALSE(fitsNmeaYears(t));
  ASSERT_TRUE(parseUtcTime("2080-01-01T00:00:00Z", &t));
  EXPECT_FALSE(fitsNmeaYears(t));
  ASSERT_TRUE(parseUtcTime("1980-01-01T00:00:00Z", &t));
  EXPECT_TRUE(fitsNmeaYears(t));
  ASSERT_TRUE(parseUtcTime("2079-12-31T23:59:59Z", &t));
  EXPECT_TRUE(fitsNmeaYears(t));
  EXPECT_EQ(nmeaYear(79), 2079);
  EXPECT_EQ(nmeaYear(80), 1980);
}

}  // namespace
}  // namespace acc

TEST(SynthesisParameters, ASettingValuesOverridingItOrAllFour)
{
  std::string name, error;
  acc::AccParameters p;
  ASSERT_TRUE(acc::chooseParameters("min", {}, &p, &name, &error)) << error;
  EXPECT_EQ(name, "min");
  EXPECT_DOUBLE_EQ(p.k1_per_s2, acc::findNamedSetting("min")->parameters.k1_per_s2);
  // One value overridden: the rest of the setting stays, the name says it is no longer the setting.
  ASSERT_TRUE(acc::chooseParameters("min", {std::nullopt, 0.9, std::nullopt, std::nullopt}, &p, &name, &error));
  EXPECT_EQ(name, "custom");
  EXPECT_DOUBLE_EQ(p.k2_per_s, 0.9);
  EXPECT_DOUBLE_EQ(p.eta_m, acc::findNamedSetting("min")->parameters.eta_m);
  ASSERT_TRUE(acc::chooseParameters("", {0.1, 0.5, 1.2, 6.0}, &p, &name, &error)) << error;
  EXPECT_DOUBLE_EQ(p.tau_e_s, 1.2);
  // Without a setting every value is needed, and the missing one is named.
  EXPECT_FALSE(acc::chooseParameters("", {0.1, 0.5, std::nullopt, 6.0}, &p, &name, &error));
  EXPECT_NE(error.find("no value for --tau-e"), std::string::npos) << error;
  EXPECT_FALSE(acc::chooseParameters("no_such_setting", {}, &p, &name, &error));
  EXPECT_NE(error.find("unknown setting"), std::string::npos) << error;
}

TEST(SynthesisWarnings, CollisionsAndReversingAreCountedFromTheirFirstTime)
{
  acc::CarFollowingRun run;
  for (int k = 0; k < 10; ++k)
  {
    run.time_s.push_back(0.1 * k);
    run.space_gap_m.push_back(k >= 4 && k <= 6 ? -0.5 : 10.0);
    run.follower_speed_mps.push_back(k == 8 ? -0.1 : 5.0);
    run.leader_speed_mps.push_back(5.0);
  }
  const std::vector<std::string> warnings = acc::implausibilityWarnings(run);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0], "the gap is negative (a collision) in 3 epochs, first at t = 0.4 s");
  EXPECT_NE(warnings[1].find("negative in 1 epochs, first at t = 0.8 s"), std::string::npos) << warnings[1];
  run.space_gap_m.assign(10, 10.0);
  run.follower_speed_mps.assign(10, 5.0);
  EXPECT_TRUE(acc::implausibilityWarnings(run).empty());
}
