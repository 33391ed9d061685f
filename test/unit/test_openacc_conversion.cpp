// The OpenACC reader and the NMEA it writes, on five rows of the Casale data (one made bad).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/gnss/nmea_log.h"
#include "acc_identification/gnss/nmea_writer.h"
#include "acc_identification/relative_state/relative_state_estimator.h"

namespace fs = std::filesystem;

namespace
{
const std::string kSmall = std::string(ACC_RELSTATE_TEST_DATA) + "/openacc_small.csv";

std::vector<std::string> linesOf(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line))
    lines.push_back(line);
  return lines;
}

fs::path freshDirectory(const std::string& name)
{
  fs::path dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}
}  // namespace

TEST(OpenAccReader, ReadsDateColumnsRadiansAndReportsABadRowByLine)
{
  auto file = acc::readOpenAccPairTrack(kSmall);
  ASSERT_TRUE(file.error.empty()) << file.error;
  EXPECT_EQ(file.year, 2020);
  EXPECT_EQ(file.month, 10);
  EXPECT_EQ(file.day, 27);
  EXPECT_EQ(file.pair.leader_name, "Rexton");
  EXPECT_EQ(file.pair.follower_name, "Hyundai");
  ASSERT_EQ(file.rows.size(), 4u);
  ASSERT_EQ(file.skipped_rows.size(), 1u);
  EXPECT_EQ(file.skipped_rows[0], kSmall + ":9: Speed1 not a number: 'not-a-number'");
  // Radians in the file, degrees here: the same product as the conversion has always made.
  EXPECT_EQ(file.rows[0].latitude_deg[0], 0.7988238643223201 * (180.0 / 3.14159265358979323846));
  EXPECT_TRUE(std::isnan(file.rows[0].altitude_m[0]));  // the leader has no altitude column
  EXPECT_NEAR(file.rows[0].altitude_m[1], 312.172, 1e-9);
  EXPECT_NEAR(file.rows[3].ivs_m, 33.086162397550545, 1e-12);
  // 27 October 2020 00:00 UTC
  EXPECT_DOUBLE_EQ(file.dayStartUnixS(), 1603756800.0);
}

/// A row of the small file with field k replaced.
std::string withField(const std::string& row, std::size_t k, const std::string& text)
{
  std::vector<std::string> fields;
  std::size_t begin = 0;
  for (std::size_t end; (end = row.find(',', begin)) != std::string::npos; begin = end + 1)
    fields.push_back(row.substr(begin, end - begin));
  fields.push_back(row.substr(begin));
  fields[k] = text;
  std::string joined;
  for (const std::string& field : fields)
    joined += (joined.empty() ? "" : ",") + field;
  return joined;
}

// Numbers an RMC cannot carry or no car drives, and times that run back, are rows skipped and
// listed, not fixes written (a negative speed came out as negative knots, and a time 76 s back
// as a log that jumps back). One time too far forward is the row left out, not every row after it.
TEST(OpenAccReader, ImpossibleValuesAndTimesAreRowsSkipped)
{
  const std::vector<std::string> lines = linesOf(kSmall);  // 6 lines before the data, rows on 7-11
  std::vector<std::string> out(lines.begin(), lines.begin() + 6);
  out.push_back(lines[6]);                                   // line 7: kept
  out.push_back(withField(lines[7], 1, "-3"));               // line 8: Speed1 below 0
  out.push_back(withField(lines[9], 0, "99999"));            // line 9: a time far forward
  out.push_back(withField(lines[10], 6, "1e9"));             // line 10: Speed2 no car drives
  out.push_back(lines[10]);                                  // line 11: kept
  out.push_back(withField(lines[6], 0, "55000"));            // line 12: a time back
  const fs::path dir = freshDirectory("openacc_impossible");
  const std::string path = (dir / "impossible.csv").string();
  {
    std::ofstream file(path);
    for (const std::string& line : out)
      file << line << "\n";
  }
  const acc::OpenAccPairTrack track = acc::readOpenAccPairTrack(path);
  ASSERT_EQ(track.error, "");
  ASSERT_EQ(track.rows.size(), 2u);
  EXPECT_EQ(track.rows[0].line, 7u);
  EXPECT_EQ(track.rows[1].line, 11u);
  ASSERT_EQ(track.skipped_rows.size(), 4u);
  EXPECT_NE(track.skipped_rows[0].find(":8: Speed1 -3 below 0"), std::string::npos) << track.skipped_rows[0];
  EXPECT_NE(track.skipped_rows[1].find(":9: Time 99999 s after the next row's"), std::string::npos)
      << track.skipped_rows[1];
  EXPECT_NE(track.skipped_rows[2].find(":10: Speed2 1e+09 above 100 m/s"), std::string::npos) << track.skipped_rows[2];
  EXPECT_NE(track.skipped_rows[3].find(":12: Time 55000 s not after the last row written"), std::string::npos)
      << track.skipped_rows[3];
  fs::remove_all(dir);
}

// A pair with no two rows to write, or a Time column in milliseconds, is an error, not an empty or
// misdated log: openacc_to_nmea wrote two empty files for speeds in km/h, and logs spanning days
// for milliseconds, each with exit status 0.
TEST(OpenAccReader, APairWithNothingToWriteOrTimesInMillisecondsIsRefused)
{
  const std::vector<std::string> lines = linesOf(kSmall);  // 6 lines before the data, rows on 7-11
  const fs::path dir = freshDirectory("openacc_unwritable");
  const auto write = [&](const std::string& name, auto change) {
    const std::string path = (dir / name).string();
    std::ofstream file(path);
    for (std::size_t i = 0; i < lines.size(); ++i)
      file << (i < 6 ? lines[i] : change(lines[i])) << "\n";
    return path;
  };
  const acc::OpenAccPairTrack kmh = acc::readOpenAccPairTrack(
      write("kmh.csv", [](const std::string& line) { return withField(line, 1, "150"); }));
  EXPECT_TRUE(kmh.rows.empty());
  EXPECT_EQ(kmh.skipped_rows.size(), 5u);
  EXPECT_NE(kmh.error.find("0 of 5 rows usable"), std::string::npos) << kmh.error;
  EXPECT_NE(kmh.error.find("are the speeds in km/h?"), std::string::npos) << kmh.error;
  // Casale part 3 with its Time in milliseconds; a few rows far apart (this excerpt, 0.1 s and
  // 252.6 s steps; two rows kept of it above) are no evidence of the unit.
  const std::vector<std::string> casale = linesOf(std::string(ACC_OPENACC_DATA_DIR) + "/part3.csv");
  const std::string ms_path = (dir / "ms.csv").string();
  {
    std::ofstream file(ms_path);
    for (std::size_t i = 0; i < casale.size(); ++i)
      file << (i < 6 || casale[i].empty()
                   ? casale[i]
                   : withField(casale[i], 0, acc::significant(1000.0 * std::stod(casale[i]), 12)))
           << "\n";
  }
  const acc::OpenAccPairTrack ms = acc::readOpenAccPairTrack(ms_path);
  EXPECT_GT(ms.rows.size(), 1000u);
  EXPECT_NE(ms.error.find("even the shortest step of Time is 100 s"), std::string::npos) << ms.error;
  EXPECT_NE(ms.error.find("Time is not in seconds"), std::string::npos) << ms.error;
  EXPECT_EQ(acc::readOpenAccPairTrack(kSmall).error, "");
  fs::remove_all(dir);
}

TEST(OpenAccReader, RefusesAFileWithoutDateOrColumns)
{
  fs::path dir = freshDirectory("openacc_reader");
  std::ofstream(dir / "nodate.csv") << "Vehicle_order,A,B\nTime,Speed1,Lat1,Lon1,Speed2,Lat2,Lon2\n1,2,0.1,0.1,2,0.1,0.1\n";
  std::ofstream(dir / "nocolumns.csv") << "Date,27,10,2020\nVehicle_order,A,B\nTime,Speed\n1,2\n";
  EXPECT_NE(acc::readOpenAccPairTrack((dir / "nodate.csv").string()).error.find("no Date,DD,MM,YYYY line"),
            std::string::npos);
  EXPECT_NE(acc::readOpenAccPairTrack((dir / "nocolumns.csv").string()).error.find("no leader-follower pair"),
            std::string::npos);
  EXPECT_NE(acc::readOpenAccPairTrack((dir / "missing.csv").string()).error.find("cannot open"), std::string::npos);
  fs::remove_all(dir);
}

TEST(OpenAccReader, RefusesToDateSentencesOfAFileWithoutMetadata)
{
  // The AstaZero layout (the header first) reads, but has no Date line for the NMEA sentences.
  fs::path dir = freshDirectory("openacc_reader_no_metadata");
  std::ofstream(dir / "asta.csv") << "Time,Speed1,Lat1,Lon1,E1,N1,Speed2,Lat2,Lon2,E2,N2,IVS1\n"
                                     "0.0,10,0.79,0.14,0,0,10,0.79,0.14,0,-20,15\n"
                                     "0.1,10,0.79,0.14,0,1,10,0.79,0.14,0,-19,15\n";
  const acc::OpenAccPairTrack track = acc::readOpenAccPairTrack((dir / "asta.csv").string());
  EXPECT_NE(track.error.find("no Date line (the file starts with its header)"), std::string::npos) << track.error;
  EXPECT_TRUE(track.rows.empty());
  fs::remove_all(dir);
}

TEST(OpenAccToNmea, WritesGgaAndRmcAsAUbloxWouldAndReadsBack)
{
  auto file = acc::readOpenAccPairTrack(kSmall);
  fs::path dir = freshDirectory("openacc_nmea");
  std::string error;
  auto leader = acc::openAccFixes(file, 1);
  auto follower = acc::openAccFixes(file, 2);
  ASSERT_TRUE(acc::writeNmeaLog((dir / "leader.nmea").string(), leader, "GN", error)) << error;
  ASSERT_TRUE(acc::writeNmeaLog((dir / "follower.nmea").string(), follower, "GN", error)) << error;

  auto lines = linesOf((dir / "leader.nmea").string());
  ASSERT_EQ(lines.size(), 8u);
  // 55287.1 s of day = 15:21:27.10; 0.7988238643223201 rad = 45 deg 46.15416 min (u-blox: 5 decimals).
  EXPECT_EQ(lines[0].substr(0, 31), "$GNGGA,152127.10,4546.15416,N,0");
  EXPECT_NE(lines[1].find(",271020,"), std::string::npos) << lines[1];
  for (const std::string& line : lines)
  {
    ASSERT_GE(line.size(), 5u);
    EXPECT_EQ(line.back(), '\r');
    std::string body = line.substr(1, line.size() - 5);
    EXPECT_EQ(acc::nmeaChecksum(body), line.substr(line.size() - 3, 2)) << line;
  }
  // 0.1718 m/s = 0.334 knots; too slow for a course: the field is empty.
  EXPECT_NE(lines[1].find(",0.334,,271020,"), std::string::npos) << lines[1];

  auto back = acc::readNmeaLog((dir / "follower.nmea").string());
  ASSERT_TRUE(back.error.empty()) << back.error;
  EXPECT_EQ(back.statistics.rejected(), 0u);
  ASSERT_EQ(back.fixes.size(), follower.size());
  for (std::size_t i = 0; i < follower.size(); ++i)
  {
    EXPECT_NEAR(back.fixes[i].gnss_time_s, follower[i].gnss_time_s, 0.006);
    EXPECT_TRUE(back.fixes[i].has_date);
    EXPECT_NEAR(back.fixes[i].latitude_deg, follower[i].latitude_deg, 1e-5 / 60.0);
    EXPECT_NEAR(back.fixes[i].longitude_deg, follower[i].longitude_deg, 1e-5 / 60.0);
    EXPECT_NEAR(back.fixes[i].speed_over_ground_mps, follower[i].speed_over_ground_mps, 0.0005 * 1852.0 / 3600.0 + 1e-9);
    EXPECT_NEAR(back.fixes[i].altitude_m, follower[i].altitude_m, 0.05 + 1e-9);
  }
  // Driving at 16.7 m/s: a course, from the Lat/Lon of the neighbouring row.
  EXPECT_TRUE(follower[3].has(acc::GnssFix::kValidCourse));
  EXPECT_NEAR(back.fixes[3].course_rad, follower[3].course_rad, 0.01 * M_PI / 180.0);
  fs::remove_all(dir);
}

namespace
{
const std::string kZalaZone = std::string(ACC_OPENACC_TEST_DATA) + "/zalazone_dynamic_part26_excerpt.csv";

/// A platoon file (ZalaZone): degrees detected and said, the first pair by default and named,
/// rows with an empty gap of THAT pair skipped and listed.
TEST(OpenAccPlatoon, DefaultPairDegreesAndItsOwnBadRows)
{
  const auto file = acc::readOpenAccPairTrack(kZalaZone);
  ASSERT_TRUE(file.error.empty()) << file.error;
  EXPECT_EQ(file.pairName(), "BMW_I3 (2) behind SMART_TARGET (1)");
  EXPECT_NE(file.angle_unit_note.find("Lat/Lon in degrees"), std::string::npos) << file.angle_unit_note;
  EXPECT_EQ(file.rows.size(), 32u);  // 40 rows, 8 with an empty IVS1
  EXPECT_EQ(file.skipped_rows.size(), 8u);
  // Line 39 on: the BMW's position and the gap IVS1 are empty in the original.
  EXPECT_EQ(file.skipped_rows.front(), kZalaZone + ":39: IVS1 empty, Lat2 empty, Lon2 empty");
  // Degrees as the file holds them: 46.89 degrees north.
  EXPECT_EQ(file.rows.front().latitude_deg[0], 46.89365044467663);
  // The default is said, never silent.
  bool said = false;
  for (const std::string& note : file.notes)
    said = said || note.find("no follower chosen") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(OpenAccPlatoon, FollowerByNameOrPositionAndItsLeaderIsTheCarDirectlyAhead)
{
  const auto by_name = acc::readOpenAccPairTrack(kZalaZone, acc::OpenAccPairSelector::byFollower("tesla_model3"));
  ASSERT_TRUE(by_name.error.empty()) << by_name.error;
  EXPECT_EQ(by_name.pairName(), "TESLA_MODEL3 (6) behind TESLA_MODELX (5)");
  EXPECT_EQ(by_name.rows.size(), 40u);  // IVS5 is complete: another pair's empty cells do not matter
  const auto by_position = acc::readOpenAccPairTrack(kZalaZone, acc::OpenAccPairSelector::byFollower("7"));
  ASSERT_TRUE(by_position.error.empty()) << by_position.error;
  EXPECT_EQ(by_position.pair.leader_position, 6);
  // TESLA_MODELX (5): the car directly ahead (JAGUAR_I_PACE, 4) has no data; never a car further ahead.
  const auto missing_leader = acc::readOpenAccPairTrack(kZalaZone, acc::OpenAccPairSelector::byFollower("TESLA_MODELX"));
  EXPECT_NE(missing_leader.error.find("no pair with follower 'TESLA_MODELX' (position 5"), std::string::npos)
      << missing_leader.error;
  EXPECT_NE(missing_leader.error.find("JAGUAR_I_PACE (4), has no data"), std::string::npos) << missing_leader.error;
  EXPECT_NE(missing_leader.error.find("pairs in this file: BMW_I3 behind SMART_TARGET, positions 2/1; TESLA_MODEL3"),
            std::string::npos)
      << missing_leader.error;
  EXPECT_NE(acc::readOpenAccPairTrack(kZalaZone, acc::OpenAccPairSelector::byFollower("NO_SUCH_CAR"))
                .error.find("in Vehicle_order"),
            std::string::npos);
}

/// Run 26's BMW i3 repeats its position between updates (22 of its 32 usable rows, two or three at
/// a time at 8.2 m/s). Written as NMEA, read back as the driver reads it and paired, those samples
/// are invalid and counted, and no other is: the live path does not publish their gaps.
TEST(OpenAccPlatoon, ARepeatedPositionIsInvalidWhenReplayedLive)
{
  const auto file = acc::readOpenAccPairTrack(kZalaZone);
  ASSERT_TRUE(file.error.empty()) << file.error;
  fs::path dir = freshDirectory("openacc_held_position");
  std::string error;
  ASSERT_TRUE(acc::writeNmeaLog((dir / "leader.nmea").string(), acc::openAccFixes(file, 1), "GN", error)) << error;
  ASSERT_TRUE(acc::writeNmeaLog((dir / "follower.nmea").string(), acc::openAccFixes(file, 2), "GN", error)) << error;
  const auto leader = acc::readNmeaLog((dir / "leader.nmea").string());
  const auto follower = acc::readNmeaLog((dir / "follower.nmea").string());
  fs::remove_all(dir);
  ASSERT_EQ(follower.fixes.size(), 32u);
  acc::RelativeStateEstimator estimator;
  for (std::size_t i = 0; i < leader.fixes.size(); ++i)
  {
    estimator.addLeader(leader.fixes[i]);
    estimator.addFollower(follower.fixes[i]);
  }
  std::size_t invalid = 0;
  for (const acc::RelativeState& state : estimator.takeStates())
  {
    if (!state.valid)
      ++invalid;
    EXPECT_TRUE(state.valid || state.invalid_reason.rfind("follower position held", 0) == 0) << state.invalid_reason;
  }
  EXPECT_EQ(estimator.counters().held_positions, 22u);
  EXPECT_EQ(invalid, 22u);
}

/// A two-vehicle file (Casale) stays radians, checked against its E/N displacement.
TEST(OpenAccPlatoon, CasaleStaysRadians)
{
  const auto file = acc::readOpenAccPairTrack(kSmall);
  ASSERT_TRUE(file.error.empty()) << file.error;
  EXPECT_NE(file.angle_unit_note.find("Lat/Lon in radians"), std::string::npos) << file.angle_unit_note;
  EXPECT_EQ(file.pair.leader_position, 1);
  EXPECT_EQ(file.pair.follower_position, 2);
}
}  // namespace
