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
#include "acc_identification/gnss/nmea_log.h"
#include "acc_identification/gnss/nmea_writer.h"

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
  auto file = acc::readOpenAccTrajectories(kSmall);
  ASSERT_TRUE(file.error.empty()) << file.error;
  EXPECT_EQ(file.year, 2020);
  EXPECT_EQ(file.month, 10);
  EXPECT_EQ(file.day, 27);
  ASSERT_EQ(file.vehicle_order.size(), 2u);
  EXPECT_EQ(file.vehicle_order[0], "Rexton");
  ASSERT_EQ(file.rows.size(), 4u);
  ASSERT_EQ(file.rejected_rows.size(), 1u);
  EXPECT_EQ(file.rejected_rows[0], "line 9: column Speed1 is not a number");
  EXPECT_NEAR(file.rows[0].latitude_rad[0], 0.7988238643223201, 1e-16);
  EXPECT_TRUE(std::isnan(file.rows[0].altitude_m[0]));  // the leader has no altitude column
  EXPECT_NEAR(file.rows[0].altitude_m[1], 312.172, 1e-9);
  EXPECT_NEAR(file.rows[3].ivs_m, 33.086162397550545, 1e-12);
  // 27 October 2020 00:00 UTC
  EXPECT_DOUBLE_EQ(file.dayStartUnixS(), 1603756800.0);
}

TEST(OpenAccReader, RefusesAFileWithoutDateOrColumns)
{
  fs::path dir = freshDirectory("openacc_reader");
  std::ofstream(dir / "nodate.csv") << "Time,Speed1,Lat1,Lon1,Speed2,Lat2,Lon2\n1,2,0.1,0.1,2,0.1,0.1\n";
  std::ofstream(dir / "nocolumns.csv") << "Date,27,10,2020\nTime,Speed\n1,2\n";
  EXPECT_NE(acc::readOpenAccTrajectories((dir / "nodate.csv").string()).error.find("no Date line"), std::string::npos);
  EXPECT_NE(acc::readOpenAccTrajectories((dir / "nocolumns.csv").string()).error.find("no column Speed1"),
            std::string::npos);
  EXPECT_NE(acc::readOpenAccTrajectories((dir / "missing.csv").string()).error.find("cannot open"), std::string::npos);
  fs::remove_all(dir);
}

TEST(OpenAccToNmea, WritesGgaAndRmcAsAUbloxWouldAndReadsBack)
{
  auto file = acc::readOpenAccTrajectories(kSmall);
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
