// The one OpenACC reader (io/openacc_file.h) and the runs read from it (io/run_csv.h), on small
// inline files of each layout: a ZalaZone platoon in degrees, a platoon in radians, cars with
// absent or empty columns, NaN cells inside and outside the pair read.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include "acc_identification/io/distance_setting.h"
#include "acc_identification/io/mixed_setting_listing.h"
#include "acc_identification/io/openacc_file.h"
#include "acc_identification/io/run_csv.h"
#include "line_matchers.h"
#include "run_matchers.h"

namespace fs = std::filesystem;

namespace
{
using acc_test::anyContains;

std::string joined(const std::vector<std::string>& lines)
{
  std::string text;
  for (const std::string& line : lines)
  {
    text += line + "\n";
  }
  return text;
}

class OpenAccFileTest : public testing::Test
{
protected:
  void SetUp() override
  {
    dir_ = fs::temp_directory_path() / ("openacc_file_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const
  {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  fs::path dir_;
};

const std::string kPlatoonMetadata =
    "Date,8,10,2019\n"
    "Vehicle_order,SMART_TARGET,TESLA_MODELX,TESLA_MODEL3,BMW_I3,AUDI_A4,\n"
    "Number_of_vehicles,5\n"
    "ACC,1\n"
    "Distance_setting,S\n";

/// One data row of the platoon file below: cars 1, 2, 4 and 5 with Speed, E, N, Lon, Lat, Alt (car
/// 3, TESLA_MODEL3, has its columns absent), then IVS1, IVS2, IVS3, IVS4. Each car moves 1 m
/// north per 0.1 s; lat/lon in degrees or radians.
std::string platoonRow(int i, bool degrees, const std::string& speed4 = "", const std::string& ivs3 = "10.0",
                       const std::string& speed2 = "")
{
  const double lat_deg = 46.89 + i * 1.0 / 111195.0;  // 1 m north per row
  const double lon_deg = 16.84;
  const double scale = degrees ? 1.0 : M_PI / 180.0;
  char row[1024];
  auto car = [&](double speed, const std::string& speed_text) {
    char cells[256];
    std::snprintf(cells, sizeof cells, "%s,0.0,%.3f,%.12f,%.12f,240.0",
                  speed_text.empty() ? std::to_string(speed).c_str() : speed_text.c_str(), 1.0 * i, lon_deg * scale,
                  lat_deg * scale);
    return std::string(cells);
  };
  std::snprintf(row, sizeof row, "%.1f,%s,%s,%s,%s,20.0,NaN,%s,12.0\n", 100.0 + 0.1 * i, car(10.0, "").c_str(),
                car(10.1, speed2).c_str(), car(10.2, speed4).c_str(), car(10.3, "").c_str(), ivs3.c_str());
  return row;
}

const std::string kPlatoonHeader =
    "Time,Speed1,E1,N1,Lon1,Lat1,Alt1,Speed2,E2,N2,Lon2,Lat2,Alt2,Speed4,E4,N4,Lon4,Lat4,Alt4,"
    "Speed5,E5,N5,Lon5,Lat5,Alt5,IVS1,IVS2,IVS3,IVS4\n";

/// A ZalaZone-like platoon: degrees (beyond radians), car 3 absent, IVS2 NaN throughout.
std::string platoonFile(bool degrees)
{
  std::string text = kPlatoonMetadata + kPlatoonHeader;
  for (int i = 0; i < 10; ++i)
  {
    text += platoonRow(i, degrees);
  }
  return text;
}

TEST_F(OpenAccFileTest, ZalaZoneLayoutInDegreesIsDetectedAndSaid)
{
  const acc::OpenAccFile file = acc::readOpenAccFile(write("dynamic_part1.csv", platoonFile(true)));
  ASSERT_EQ(file.error, "");
  EXPECT_EQ(file.name, "dynamic_part1");
  EXPECT_EQ(file.rows(), 10u);
  EXPECT_EQ(file.metadata.vehicle_order.size(), 5u);  // the trailing comma names no car
  EXPECT_EQ(file.metadata.number_of_vehicles, 5);
  EXPECT_EQ(file.metadata.acc, 1);
  EXPECT_EQ(file.metadata.distance_setting, "S");
  EXPECT_EQ(file.angle_unit, acc::OpenAccAngleUnit::kDegrees);
  EXPECT_TRUE(anyContains(file.notes, {"Lat/Lon in degrees", "beyond radians"})) << joined(file.notes);
  ASSERT_NE(file.vehicle(1), nullptr);
  EXPECT_DOUBLE_EQ(file.vehicle(1)->latitude_deg[0], 46.89);  // kept in degrees
}

TEST_F(OpenAccFileTest, RadiansLayoutIsToldByTheEastNorthMotion)
{
  const acc::OpenAccFile file = acc::readOpenAccFile(write("radians.csv", platoonFile(false)));
  ASSERT_EQ(file.error, "");
  EXPECT_EQ(file.angle_unit, acc::OpenAccAngleUnit::kRadians);
  EXPECT_TRUE(anyContains(file.notes, {"Lat/Lon in radians", "read as degrees"})) << joined(file.notes);
  EXPECT_NEAR(file.vehicle(1)->latitude_deg[0], 46.89, 1e-9);  // converted to degrees
}

/// A row of the platoon file with one field replaced.
std::string withField(std::string row, std::size_t field, const std::string& text)
{
  std::size_t begin = 0;
  for (std::size_t k = 0; k < field; ++k)
    begin = row.find(',', begin) + 1;
  const std::size_t end = row.find(',', begin);
  return row.replace(begin, end - begin, text);
}

/// A speed as a cell, to the last digit of a double.
std::string printed(double speed_mps)
{
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", speed_mps);
  return text;
}

/// A varying speed with a little deterministic noise, as a Doppler speed varies (m/s).
double varyingSpeed(int i) { return 10.0 + 2.0 * std::sin(0.05 * i) + 0.01 * std::sin(1.7 * i * i); }

TEST_F(OpenAccFileTest, OneCorruptAngleNeitherDecidesTheUnitNorBecomesAPosition)
{
  // A file in radians whose Lat1 is 7 in one row: once read as "beyond radians, so degrees",
  // which put every fix of the file near the equator.
  std::string text = kPlatoonMetadata + kPlatoonHeader;
  for (int i = 0; i < 10; ++i)
    text += i == 4 ? withField(platoonRow(i, false), 5, "7") : platoonRow(i, false);
  const acc::OpenAccFile file = acc::readOpenAccFile(write("radians_one_bad.csv", text));
  ASSERT_EQ(file.error, "");
  EXPECT_EQ(file.angle_unit, acc::OpenAccAngleUnit::kRadians) << file.angle_unit_reason;
  EXPECT_TRUE(anyContains(file.notes, {"1 of 40 fixes beyond radians"})) << joined(file.notes);
  EXPECT_NEAR(file.vehicle(1)->latitude_deg[0], 46.89, 1e-9);
  EXPECT_TRUE(std::isnan(file.vehicle(1)->latitude_deg[4]));  // set aside, not a position
  // Listed among the bad cells in row order (after the IVS2 NaN of rows 0-4, before row 5's) and
  // counted; every row already had a bad cell (IVS2 is NaN throughout), so no row more is bad.
  ASSERT_EQ(file.bad_cells.size(), 11u);
  EXPECT_EQ(file.bad_cells[5].describe(), "Lat1 7: not a latitude in radians, the file's unit");
  EXPECT_EQ(file.bad_cells[5].row, 4u);
  EXPECT_EQ(file.bad_cells[6].row, 5u);
  EXPECT_EQ(file.bad_rows, 10u);
  EXPECT_TRUE(anyContains(file.problems, {"radians_one_bad.csv:", "Lat1 7: not a latitude"})) << joined(file.problems);
  EXPECT_TRUE(anyContains(file.notes, {"11 cells without a usable number in 10 of 10 rows (IVS2 10, Lat1 1)"}))
      << joined(file.notes);
}

TEST_F(OpenAccFileTest, ImpossibleAnglesAreListedInRowOrderOneLinePerRow)
{
  // Row 2 has IVS2 NaN and a Lon2 of 9 (radians); row 7 has no other bad cell (IVS2 a number)
  // and a Lat1 of 7; row 8 has both of car 2's angles impossible.
  std::string text = kPlatoonMetadata + kPlatoonHeader;
  for (int i = 0; i < 10; ++i)
  {
    std::string row = platoonRow(i, false);
    if (i == 2)
      row = withField(row, 10, "9");
    if (i == 7)
      row = withField(withField(row, 26, "10.0"), 5, "7");
    if (i == 8)
      row = withField(withField(row, 10, "-9"), 11, "2");
    text += row;
  }
  const acc::OpenAccFile file = acc::readOpenAccFile(write("radians_bad_rows.csv", text));
  ASSERT_EQ(file.error, "");
  EXPECT_EQ(file.angle_unit, acc::OpenAccAngleUnit::kRadians) << file.angle_unit_reason;
  ASSERT_EQ(file.problems.size(), 10u) << joined(file.problems);  // one line per row, rows 0-9
  for (std::size_t i = 0; i < 10; ++i)
    EXPECT_TRUE(anyContains({file.problems[i]}, {"radians_bad_rows.csv:" + std::to_string(file.line[i]) + ": "}))
        << i << ": " << joined(file.problems);
  EXPECT_TRUE(anyContains({file.problems[2]}, {"IVS2 NaN; Lon2 9: not a longitude in radians"})) << file.problems[2];
  EXPECT_TRUE(anyContains({file.problems[7]}, {": Lat1 7: not a latitude in radians, the file's unit (NaN)"}))
      << file.problems[7];
  EXPECT_TRUE(anyContains({file.problems[8]}, {"Lon2 -9: not a longitude", "; Lat2 2: not a latitude"}))
      << file.problems[8];
  EXPECT_EQ(file.bad_rows, 10u);  // row 7's only bad cell is its angle
  ASSERT_EQ(file.bad_cells.size(), 9u + 4u);
  for (std::size_t k = 1; k < file.bad_cells.size(); ++k)
    EXPECT_LE(file.bad_cells[k - 1].row, file.bad_cells[k].row) << k;
  EXPECT_EQ(file.bad_cells_by_column.at("Lon2"), 2u);
  EXPECT_EQ(file.bad_cells_by_column.at("Lat2"), 1u);
  EXPECT_EQ(file.bad_cells_by_column.at("Lat1"), 1u);
}

/// A speed cell: NaN as the database writes an empty measurement.
std::string speedCell(double speed_mps) { return std::isnan(speed_mps) ? "NaN" : printed(speed_mps); }

/// The platoon file over 200 rows with the speeds of SMART_TARGET (1), TESLA_MODELX (2) and
/// AUDI_A4 (5) given per row.
std::string platoonFileWithSpeeds(const std::function<double(int)>& speed1, const std::function<double(int)>& speed2,
                                  const std::function<double(int)>& speed5)
{
  std::string text = kPlatoonMetadata + kPlatoonHeader;
  for (int i = 0; i < 200; ++i)
  {
    const std::string row = platoonRow(i, true, "", "10.0", speedCell(speed2(i)));
    text += withField(withField(row, 19, speedCell(speed5(i))), 1, speedCell(speed1(i)));
  }
  return text;
}

/// The platoon file over 200 rows with varying speeds: SMART_TARGET (1) at 10 m/s, TESLA_MODELX (2)
/// at 10 + 2 sin(0.05 i) m/s with a little noise; AUDI_A4 (5) drives `speed5(i)`.
std::string varyingPlatoonFile(const std::function<double(int)>& speed5)
{
  return platoonFileWithSpeeds([](int) { return 10.0; }, varyingSpeed, speed5);
}

TEST_F(OpenAccFileTest, ACarWhoseSpeedsAreAnotherCarsColumnIsACopiedColumnAndNoPairsCar)
{
  // AUDI_A4's column is TESLA_MODELX's, row for row: a copy, not a car of its own.
  const acc::OpenAccFile file =
      acc::readOpenAccFile(write("copied.csv", varyingPlatoonFile([](int i) { return varyingSpeed(i); })));
  ASSERT_EQ(file.error, "");
  ASSERT_NE(file.vehicle(5), nullptr);
  EXPECT_TRUE(file.vehicle(2)->copied_column.empty());
  EXPECT_NE(file.vehicle(5)->copied_column.find("equal TESLA_MODELX (2)'s on every row"), std::string::npos)
      << file.vehicle(5)->copied_column;
  EXPECT_FALSE(file.vehicle(5)->has_speed);  // set aside: no reader takes it for a measurement
  EXPECT_EQ(file.vehicle(5)->speed_values, 0u);
  EXPECT_TRUE(std::isnan(file.vehicle(5)->speed_mps[100]));
  EXPECT_TRUE(anyContains(file.notes, {"AUDI_A4 (5) has no pair", "equal TESLA_MODELX (2)'s on every row",
                                       "the later one is not read"}))
      << joined(file.notes);
  const std::vector<acc::OpenAccPair> pairs = acc::availablePairs(file);
  ASSERT_EQ(pairs.size(), 1u) << acc::describeAvailablePairs(file);
  EXPECT_EQ(pairs[0].follower_position, 2);
}

TEST_F(OpenAccFileTest, SpeedsThatDifferSomewhereOrAreShiftedAreTwoCars)
{
  // The same profile, but one value in the last digit off: two measurements.
  const acc::OpenAccFile close = acc::readOpenAccFile(
      write("close.csv", varyingPlatoonFile([](int i) { return varyingSpeed(i) + (i == 150 ? 1e-9 : 0.0); })));
  ASSERT_EQ(close.error, "");
  EXPECT_TRUE(close.vehicle(5)->copied_column.empty()) << close.vehicle(5)->copied_column;
  EXPECT_EQ(acc::availablePairs(close).size(), 2u) << acc::describeAvailablePairs(close);
  // Three rows later (Newell's copy of a car ahead, simulated without noise): two series too.
  const acc::OpenAccFile shifted = acc::readOpenAccFile(
      write("shifted.csv", varyingPlatoonFile([](int i) { return varyingSpeed(std::max(0, i - 3)); })));
  EXPECT_TRUE(shifted.vehicle(5)->copied_column.empty()) << shifted.vehicle(5)->copied_column;
  // Equal while one of them is steady (a standstill, a held value) decides nothing.
  const acc::OpenAccFile steady = acc::readOpenAccFile(write("steady.csv", varyingPlatoonFile([](int) { return 10.0; })));
  EXPECT_TRUE(steady.vehicle(5)->copied_column.empty());
  // Equal everywhere but in the last row: two measurements.
  const acc::OpenAccFile last = acc::readOpenAccFile(
      write("last.csv", varyingPlatoonFile([](int i) { return varyingSpeed(i) + (i == 199 ? 0.5 : 0.0); })));
  EXPECT_TRUE(last.vehicle(5)->copied_column.empty()) << last.vehicle(5)->copied_column;
}

TEST_F(OpenAccFileTest, EqualColumnsDecideNothingOnTooFewRowsOrChanges)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Equal on 60 rows (AUDI_A4 has no measurement on the others): too few to call a copy.
  const acc::OpenAccFile short_overlap = acc::readOpenAccFile(
      write("short.csv", varyingPlatoonFile([nan](int i) { return i < 60 ? varyingSpeed(i) : nan; })));
  ASSERT_EQ(short_overlap.error, "");
  EXPECT_TRUE(short_overlap.vehicle(5)->copied_column.empty()) << short_overlap.vehicle(5)->copied_column;
  // Equal on every row, stepping 0.5 m/s every 20 rows: 9 changes, a held value more than a drive.
  const auto steps = [](int i) { return 10.0 + 0.5 * (i / 20); };
  const acc::OpenAccFile stepped =
      acc::readOpenAccFile(write("stepped.csv", platoonFileWithSpeeds([](int) { return 10.0; }, steps, steps)));
  ASSERT_EQ(stepped.error, "");
  EXPECT_TRUE(stepped.vehicle(5)->copied_column.empty()) << stepped.vehicle(5)->copied_column;
}

TEST_F(OpenAccFileTest, ACopyIsFoundThroughEmptyCellsAndBehindTheFirstCar)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // The copy and the original each miss a few cells (the database's NaN cells): the rows where both
  // hold a number decide.
  const acc::OpenAccFile holes = acc::readOpenAccFile(write(
      "holes.csv", platoonFileWithSpeeds([](int) { return 10.0; },
                                         [nan](int i) { return i == 150 ? nan : varyingSpeed(i); },
                                         [nan](int i) { return i == 10 || i == 77 ? nan : varyingSpeed(i); })));
  ASSERT_EQ(holes.error, "");
  EXPECT_NE(holes.vehicle(5)->copied_column.find("equal TESLA_MODELX (2)'s"), std::string::npos)
      << holes.vehicle(5)->copied_column;
  // The first car's column written again as the second's.
  const acc::OpenAccFile first =
      acc::readOpenAccFile(write("first.csv", platoonFileWithSpeeds(varyingSpeed, varyingSpeed, [](int i) {
                                   return 8.0 + std::cos(0.07 * i);
                                 })));
  ASSERT_EQ(first.error, "");
  EXPECT_NE(first.vehicle(2)->copied_column.find("equal SMART_TARGET (1)'s"), std::string::npos)
      << first.vehicle(2)->copied_column;
  EXPECT_TRUE(first.vehicle(5)->copied_column.empty());
}

TEST_F(OpenAccFileTest, CarsWithAbsentOrEmptyColumnsHaveNoPairAndTheNotesSayWhy)
{
  // Car 3 (TESLA_MODEL3) absent; car 5 (AUDI_A4) with its columns present but every cell empty.
  std::string text = kPlatoonMetadata + kPlatoonHeader;
  for (int i = 0; i < 10; ++i)
  {
    std::string row = platoonRow(i, true);
    // Empty car 5's six cells: fields 19..24 (Speed5..Alt5).
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (std::size_t comma; (comma = row.find(',', start)) != std::string::npos; start = comma + 1)
    {
      fields.push_back(row.substr(start, comma - start));
    }
    fields.push_back(row.substr(start));
    for (std::size_t f = 19; f <= 24; ++f)
    {
      fields[f] = "";
    }
    row.clear();
    for (std::size_t f = 0; f < fields.size(); ++f)
    {
      row += (f ? "," : "") + fields[f];
    }
    text += row;
  }
  const acc::OpenAccFile file = acc::readOpenAccFile(write("holes.csv", text));
  ASSERT_EQ(file.error, "");
  EXPECT_EQ(file.vehicle(3), nullptr);
  EXPECT_EQ(file.vehicle(5), nullptr);
  EXPECT_TRUE(anyContains(file.notes, {"no data for", "TESLA_MODEL3 (3, no columns)",
                                       "AUDI_A4 (5, every cell of its columns empty)"}))
      << joined(file.notes);
  // BMW_I3 (4) is behind the absent TESLA_MODEL3: no pair, and never the car further ahead.
  EXPECT_TRUE(anyContains(file.notes, {"BMW_I3 (4) has no pair", "TESLA_MODEL3 (3)", "its columns are absent",
                                       "never taken as its leader"}))
      << joined(file.notes);
  const std::vector<acc::OpenAccPair> pairs = acc::availablePairs(file);
  // TESLA_MODELX (2) behind SMART_TARGET (1) only: IVS2 is NaN, 3 and 5 have no data.
  ASSERT_EQ(pairs.size(), 1u) << acc::describeAvailablePairs(file);
  EXPECT_EQ(pairs[0].follower_position, 2);
  EXPECT_NE(acc::describePairlessFollower(file, 5).find("its columns are empty"), std::string::npos)
      << acc::describePairlessFollower(file, 5);
  EXPECT_NE(acc::describePairlessFollower(file, 4).find("its columns are absent"), std::string::npos)
      << acc::describePairlessFollower(file, 4);
}

TEST_F(OpenAccFileTest, NaNInAnotherCarsColumnDoesNotTouchThePairRead)
{
  // IVS2 is NaN in every row, Speed4 (BMW_I3) NaN in row 3: the default pair (2 behind 1) reads whole.
  std::string text = kPlatoonMetadata + kPlatoonHeader;
  for (int i = 0; i < 10; ++i)
  {
    text += platoonRow(i, true, i == 3 ? "NaN" : "");
  }
  const std::string path = write("other_nan.csv", text);
  const acc::OpenAccFile file = acc::readOpenAccFile(path);
  EXPECT_EQ(file.cellProblem(3, "Speed4"), "Speed4 NaN");
  EXPECT_GT(file.bad_cells.size(), 10u);  // IVS2 in every row, Speed4 once
  const acc::RunFileContents contents = acc::readRunFile(path);
  EXPECT_EQ(contents.rejected_rows, 0u);
  EXPECT_TRUE(contents.problems.empty()) << joined(contents.problems);
  ASSERT_EQ(contents.runs.size(), 1u);
  EXPECT_EQ(contents.runs[0].size(), 10u);
  EXPECT_EQ(contents.runs[0].name, "other_nan TESLA_MODELX");
  EXPECT_DOUBLE_EQ(contents.runs[0].space_gap_m[0], 20.0);          // IVS1
  EXPECT_DOUBLE_EQ(contents.runs[0].follower_speed_mps[0], 10.1);  // Speed2
  EXPECT_DOUBLE_EQ(contents.runs[0].leader_speed_mps[0], 10.0);    // Speed1
  // The default pair is said, never silently.
  EXPECT_TRUE(anyContains(contents.notes, {"pair read: TESLA_MODELX behind SMART_TARGET", "no follower chosen"}))
      << joined(contents.notes);
  ASSERT_EQ(contents.pairs.size(), 1u);
  EXPECT_EQ(contents.run_pairs, (std::vector<std::size_t>{0}));
}

TEST_F(OpenAccFileTest, NaNInThePairsOwnCellIsRejectedCountedAndSplitsTheRun)
{
  // Speed2, the follower's speed of the default pair, is NaN in row 4 (line 11).
  std::string text = kPlatoonMetadata + kPlatoonHeader;
  for (int i = 0; i < 10; ++i)
  {
    text += platoonRow(i, true, "", "10.0", i == 4 ? "NaN" : "");
  }
  const acc::RunFileContents contents = acc::readRunFile(write("own_nan.csv", text));
  EXPECT_EQ(contents.data_rows, 10u);
  EXPECT_EQ(contents.rejected_rows, 1u);
  ASSERT_EQ(contents.problems.size(), 1u);
  EXPECT_NE(contents.problems[0].find("own_nan.csv:11: Speed2 NaN; row rejected, run split here"), std::string::npos)
      << contents.problems[0];
  ASSERT_EQ(contents.runs.size(), 2u);
  EXPECT_EQ(contents.runs[0].size(), 4u);
  EXPECT_EQ(contents.runs[1].size(), 5u);
  EXPECT_EQ(contents.runs[1].name, "own_nan TESLA_MODELX#2");
}

TEST_F(OpenAccFileTest, FollowerByNameOrPositionAndUnknownFollowerListsThePairs)
{
  // Pairs: TESLA_MODELX (2) behind SMART_TARGET (1) and AUDI_A4 (5) behind BMW_I3 (4); BMW_I3's
  // leader, TESLA_MODEL3 (3), is absent although their gap IVS3 has values.
  const std::string path = write("choose.csv", platoonFile(true));
  const acc::RunFileContents by_name =
      acc::readRunFile(path, acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::byFollower("audi_a4"));
  ASSERT_EQ(by_name.runs.size(), 1u);
  EXPECT_EQ(by_name.runs[0].name, "choose AUDI_A4");
  EXPECT_DOUBLE_EQ(by_name.runs[0].space_gap_m[0], 12.0);          // IVS4
  EXPECT_DOUBLE_EQ(by_name.runs[0].follower_speed_mps[0], 10.3);  // Speed5
  EXPECT_DOUBLE_EQ(by_name.runs[0].leader_speed_mps[0], 10.2);    // Speed4
  EXPECT_TRUE(anyContains(by_name.notes, {"pair read: AUDI_A4 behind BMW_I3", "follower 'audi_a4' chosen"}))
      << joined(by_name.notes);
  const acc::RunFileContents by_position =
      acc::readRunFile(path, acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::byFollower("2"));
  ASSERT_EQ(by_position.pairs.size(), 1u);
  EXPECT_EQ(by_position.pairs[0].follower_name, "TESLA_MODELX");
  EXPECT_EQ(by_position.runs[0].name, "choose TESLA_MODELX");
  try
  {
    acc::readRunFile(path, acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::byFollower("NO_SUCH_CAR"));
    FAIL() << "expected RunReadError";
  }
  catch (const acc::RunReadError& error)
  {
    const std::string what = error.what();
    EXPECT_NE(what.find("no car 'NO_SUCH_CAR' in Vehicle_order"), std::string::npos) << what;
    EXPECT_NE(what.find("pairs in this file: TESLA_MODELX behind SMART_TARGET, positions 2/1; AUDI_A4 behind "
                        "BMW_I3, positions 5/4"),
              std::string::npos)
        << what;
  }
  // BMW_I3 (4) is a car of the file, but its leader (3) is absent: an error, with the reason.
  try
  {
    acc::readRunFile(path, acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::byFollower("4"));
    FAIL() << "expected RunReadError";
  }
  catch (const acc::RunReadError& error)
  {
    EXPECT_NE(std::string(error.what()).find("the car directly ahead of it, TESLA_MODEL3 (3), has no data"),
              std::string::npos)
        << error.what();
  }
  // A number too large to be a position is named as written, not as position 0.
  try
  {
    acc::readRunFile(path, acc::RunPlausibilityBounds{},
                     acc::OpenAccPairSelector::byFollower("99999999999999999999"));
    FAIL() << "expected RunReadError";
  }
  catch (const acc::RunReadError& error)
  {
    EXPECT_NE(std::string(error.what()).find("no car at position 99999999999999999999"), std::string::npos)
        << error.what();
  }
}

TEST_F(OpenAccFileTest, AllPairsReadsEveryPairAndNamesItsRuns)
{
  const std::string path = write("all.csv", platoonFile(true));
  const acc::RunFileContents contents =
      acc::readRunFile(path, acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::all());
  ASSERT_EQ(contents.pairs.size(), 2u);
  ASSERT_EQ(contents.runs.size(), 2u);
  EXPECT_EQ(contents.runs[0].name, "all TESLA_MODELX");
  EXPECT_EQ(contents.runs[1].name, "all AUDI_A4");
  EXPECT_EQ(contents.run_pairs, (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(contents.data_rows, 20u);  // summed over the pairs
  EXPECT_TRUE(anyContains(contents.notes, {"every pair read (2)"})) << joined(contents.notes);

  const acc::AllPairRuns all = acc::readAllPairRuns(path);
  ASSERT_EQ(all.pairs.size(), 2u);
  EXPECT_EQ(all.pairs[1].pair.follower_name, "AUDI_A4");
  EXPECT_EQ(all.pairs[1].contents.data_rows, 10u);
  ASSERT_EQ(all.pairs[1].contents.runs.size(), 1u);
  EXPECT_EQ(all.pairs[1].contents.runs[0].name, "all AUDI_A4");
}

TEST_F(OpenAccFileTest, WithoutADriverColumnTheAccLineTells)
{
  std::string manual = platoonFile(true);
  manual.replace(manual.find("ACC,1"), 5, "ACC,0");
  const acc::RunFileContents contents = acc::readRunFile(write("manual.csv", manual));
  EXPECT_EQ(contents.acc_off_rows, 10u);
  EXPECT_TRUE(contents.runs.empty());
  EXPECT_TRUE(anyContains(contents.notes, {"no Driver2 column and the ACC line is 0"})) << joined(contents.notes);
  EXPECT_THROW(acc::readRuns(write("manual2.csv", manual)), acc::RunReadError);
}

/// A Casale-like two-vehicle file of two rows, both on ACC.
const std::string kTwoVehicleFile =
    "Date,27,10,2020\n"
    "Vehicle_order,Rexton,Hyundai\n"
    "Number_of_vehicles,2\n"
    "ACC,1\n"
    "Distance_setting,min\n"
    "Time,Speed1,Lat1,Lon1,E1,N1,Speed2,Lat2,Lon2,Alt2,E2,N2,U2,IVS1,Driver2\n"
    "100.0,30.0,0,0,0,0,29.0,0,0,0,0,0,0,40.0,ACC\n"
    "100.1,30.1,0,0,0,0,29.1,0,0,0,0,0,0,40.1,ACC\n";

TEST_F(OpenAccFileTest, MetadataDistanceSettingAndTwoVehicleLayout)
{
  const std::string path = write("part9.csv", kTwoVehicleFile);
  const acc::OpenAccFile file = acc::readOpenAccFile(path);
  ASSERT_EQ(file.error, "");
  EXPECT_EQ(file.metadata.distance_setting, "min");
  EXPECT_EQ(file.metadata.year, 2020);
  ASSERT_NE(file.vehicle(2), nullptr);
  EXPECT_TRUE(file.vehicle(2)->has_driver);
  const acc::RunFileContents contents = acc::readRunFile(path);
  ASSERT_EQ(contents.runs.size(), 1u);
  EXPECT_EQ(contents.runs[0].name, "part9 Hyundai");
  EXPECT_TRUE(anyContains(contents.notes, {"ACC on where Driver2 is ACC"})) << joined(contents.notes);
}

// Rows where the follower was driven by hand are not used, and said: how many and where (file lines
// and times of each stretch), as every row not used is. Fails if they are only counted.
TEST_F(OpenAccFileTest, RowsWithTheAccOffAreNamedByTheirLinesAndTimes)
{
  std::string text = kTwoVehicleFile;
  for (int k = 2; k < 12; ++k)
  {
    const double t = 100.0 + 0.1 * k;
    const bool by_hand = (k >= 4 && k < 7) || k == 9;
    text += std::to_string(t) + ",30,0,0,0,0,29,0,0,0,0,0,0,40," + (by_hand ? "Human" : "ACC") + "\n";
  }
  const acc::RunFileContents contents = acc::readRunFile(write("by_hand.csv", text));
  EXPECT_EQ(contents.acc_off_rows, 4u);
  EXPECT_TRUE(anyContains(contents.notes, {"4 rows with the follower's ACC off (driven by hand) not used",
                                           "lines 11-13 (t = 100.4 to 100.6 s), lines 16-16 (t = 100.9 to 100.9 s)"}))
      << joined(contents.notes);
}

// A Number_of_vehicles of -1 is no count (and -1 is what the reader keeps for "unknown"): said.
TEST_F(OpenAccFileTest, ANegativeNumberOfVehiclesIsSaid)
{
  std::string text = kTwoVehicleFile;
  text.replace(text.find("Number_of_vehicles,2"), 20, "Number_of_vehicles,-1");
  const acc::OpenAccFile file = acc::readOpenAccFile(write("negative_count.csv", text));
  EXPECT_TRUE(anyContains(file.notes, {"Number_of_vehicles is not a count: 'Number_of_vehicles,-1'"}))
      << joined(file.notes);
}

TEST_F(OpenAccFileTest, ASpreadsheetExportReadsAsTheDatabasesFile)
{
  // The same two-vehicle file as a spreadsheet writes it back: a byte-order mark, Windows line
  // ends, every field quoted, and the Driver2 cells in lower case.
  const std::string plain =
      write("plain.csv", kTwoVehicleFile + "100.2,30.2,0,0,0,0,29.2,0,0,0,0,0,0,40.2,Human\n");
  std::string exported = "\xEF\xBB\xBF";
  std::ifstream in(plain);
  for (std::string line; std::getline(in, line);)
  {
    std::string quoted = "\"";
    for (const char c : line)
      quoted += c == ',' ? std::string("\",\"") : std::string(1, c);
    exported += quoted + "\"\r\n";
  }
  const std::string acc_upper = "\"ACC\"";
  for (auto at = exported.find(acc_upper, exported.find("\"Time\"")); at != std::string::npos;
       at = exported.find(acc_upper, at))
    exported.replace(at, acc_upper.size(), "\"acc\"");
  const acc::OpenAccFile file = acc::readOpenAccFile(write("exported.csv", exported));
  ASSERT_EQ(file.error, "");
  EXPECT_EQ(file.metadata.distance_setting, "min");
  EXPECT_EQ(file.vehicleName(2), "Hyundai");
  const acc::RunFileContents b = acc::readRunFile(write("exported2.csv", exported));
  EXPECT_EQ(b.acc_off_rows, 1u);
  acc_test::expectTheSameSingleRun(acc::readRunFile(plain), b);
}

// Column names in another case ("time", "speed1", "ivs1", as a script or a spreadsheet may write
// them) are the database's columns: the file reads as the plain one, and a note says so. Fails
// when "time" is not taken for a header ("no header line with a Time column").
TEST_F(OpenAccFileTest, ColumnNamesInAnotherCaseReadAsTheDatabasesColumns)
{
  const std::string plain = write("plain_case.csv", kTwoVehicleFile);
  std::string text = kTwoVehicleFile;
  const std::size_t header = text.find("Time,");
  const std::size_t header_end = text.find('\n', header);
  for (std::size_t i = header; i < header_end; ++i)
    text[i] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[i])));
  const acc::OpenAccFile file = acc::readOpenAccFile(write("lower_case.csv", text));
  ASSERT_EQ(file.error, "");
  EXPECT_TRUE(anyContains(file.notes, {"columns written in another case", "time as Time", "ivs1 as IVS1"}))
      << joined(file.notes);
  acc_test::expectTheSameSingleRun(acc::readRunFile(plain), acc::readRunFile(write("lower_case2.csv", text)));
}

TEST_F(OpenAccFileTest, AFileWithoutAPairSaysWhichCarHasNoData)
{
  // Every cell of the follower's empty, as the database leaves a car whose data are missing.
  const std::string text = kTwoVehicleFile.substr(0, kTwoVehicleFile.find("100.0,")) +
                           "100.0,30.0,0,0,0,0,,,,,,,,40.0,\n100.1,30.1,0,0,0,0,,,,,,,,40.1,\n";
  try
  {
    acc::readRunFile(write("empty_follower.csv", text));
    FAIL() << "a file without a pair read";
  }
  catch (const acc::RunReadError& error)
  {
    EXPECT_NE(std::string(error.what()).find("no leader-follower pair"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find(": Hyundai (2) has no data"), std::string::npos) << error.what();
  }
}

TEST_F(OpenAccFileTest, AnAccLineThatContradictsTheDriverColumnIsSaidAndTheColumnFollowed)
{
  std::string text = kTwoVehicleFile;
  text.replace(text.find("ACC,1"), 5, "ACC,0");
  const acc::RunFileContents contents = acc::readRunFile(write("acc_zero.csv", text));
  ASSERT_EQ(contents.runs.size(), 1u);
  EXPECT_EQ(contents.runs[0].size(), 2u);
  EXPECT_TRUE(anyContains(contents.notes, {"ACC on where Driver2 is ACC", "the ACC line says 0"}))
      << joined(contents.notes);
  // The file itself says it once, among the problems of its metadata (what a campaign passes on);
  // and the other way round: ACC 1 while no Driver cell says ACC.
  const acc::OpenAccFile file = acc::readOpenAccFile(write("acc_zero_file.csv", text));
  EXPECT_TRUE(anyContains(file.metadata_problems, {"the ACC line says 0 (manual driving) but Driver2 mark rows ACC"}))
      << joined(file.metadata_problems);
  std::string human = kTwoVehicleFile;
  for (auto at = human.find(",ACC\n"); at != std::string::npos; at = human.find(",ACC\n", at))
    human.replace(at, 5, ",Human\n");
  const acc::OpenAccFile all_human = acc::readOpenAccFile(write("acc_one_human.csv", human));
  EXPECT_TRUE(anyContains(all_human.metadata_problems, {"the ACC line says 1 (ACC on) but no cell of Driver2 says ACC"}))
      << joined(all_human.metadata_problems);
  EXPECT_TRUE(acc::readOpenAccFile(write("plain_acc.csv", kTwoVehicleFile)).metadata_problems.empty());
}

// An ACC line the database never writes (7), and a Distance_setting line that names no setting,
// are metadata problems said, not passed silently (the campaign grouped such cars as '?').
TEST_F(OpenAccFileTest, AnAccLineOfNoMeaningAndAnEmptySettingAreSaid)
{
  std::string text = kTwoVehicleFile;
  text.replace(text.find("ACC,1"), 5, "ACC,7");
  text.replace(text.find("Distance_setting,min"), 20, "Distance_setting,");
  const acc::OpenAccFile file = acc::readOpenAccFile(write("acc_seven.csv", text));
  EXPECT_EQ(file.metadata.acc, -1);
  EXPECT_TRUE(anyContains(file.metadata_problems, {"the ACC line says 7, none of 0 (manual), 1 (ACC) and 2 (mixed)"}))
      << joined(file.metadata_problems);
  EXPECT_TRUE(anyContains(file.metadata_problems, {"the Distance_setting line names no setting"}))
      << joined(file.metadata_problems);
  std::string mixed = kTwoVehicleFile;
  mixed.replace(mixed.find("ACC,1"), 5, "ACC,2");
  EXPECT_TRUE(acc::readOpenAccFile(write("acc_two.csv", mixed)).metadata_problems.empty());
}

TEST_F(OpenAccFileTest, SemicolonSeparatedFieldsAreNamedInTheError)
{
  std::string text = kTwoVehicleFile;
  for (char& c : text)
    c = c == ',' ? ';' : c;
  try
  {
    acc::readRunFile(write("semicolons.csv", text));
    FAIL() << "a semicolon-separated file read";
  }
  catch (const acc::RunReadError& error)
  {
    EXPECT_NE(std::string(error.what()).find("its fields are separated by ';'"), std::string::npos) << error.what();
  }
}

TEST_F(OpenAccFileTest, ChoosingAFollowerInACanonicalCsvIsAnError)
{
  const std::string path = write("canonical.csv", "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n"
                                                  "0.0,20,10,10\n0.1,20,10,10\n");
  EXPECT_EQ(acc::readRunFile(path, acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::all()).runs.size(), 1u);
  EXPECT_THROW(acc::readRunFile(path, acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::byFollower("2")),
               acc::RunReadError);
  EXPECT_TRUE(acc::readRunFile(path).notes.empty());
}

/// An AstaZero file as the database's derived sets ship it: no metadata, the header first; three
/// cars (Speedk, Ek, Nk), the gaps IVS1 and IVS2, then each car's acceleration Ak.
std::string astaZeroFile(int rows)
{
  std::string text = "Time,Speed1,E1,N1,Speed2,E2,N2,Speed3,E3,N3,IVS1,IVS2,A1,A2,A3\n";
  for (int i = 0; i < rows; ++i)
  {
    const double t = 0.1 * i, north1 = 100.0 + i;
    text += std::to_string(t) + ",10.0,0," + std::to_string(north1) + ",10.5,0," + std::to_string(north1 - 25.0) +
            ",11.0,0," + std::to_string(north1 - 55.0) + ",21.0,26.0,0.0,0.1,0.2\n";
  }
  return text;
}

TEST_F(OpenAccFileTest, AstaZeroLayoutWithoutMetadataIsReadByItsColumnsAndSaid)
{
  const std::string path = write("ASta_platoon1.csv", astaZeroFile(12));
  EXPECT_TRUE(acc::looksLikeOpenAccFile(path));
  const acc::OpenAccFile file = acc::readOpenAccFile(path);
  ASSERT_TRUE(file.error.empty()) << file.error;
  EXPECT_FALSE(file.metadata.lines_present);
  ASSERT_EQ(file.vehicles.size(), 3u);
  EXPECT_EQ(file.vehicles[2].name, "vehicle 3");
  EXPECT_EQ(file.rows(), 12u);
  EXPECT_TRUE(anyContains(file.notes, {"no metadata lines", "3 cars from the columns", "named by position"}))
      << joined(file.notes);
  EXPECT_TRUE(anyContains(file.notes, {"columns not used: A1, A2, A3"})) << joined(file.notes);
  EXPECT_FALSE(anyContains(file.notes, {"but Vehicle_order names"})) << joined(file.notes);
  EXPECT_EQ(acc::describeAvailablePairs(file),
            "vehicle 2 behind vehicle 1, positions 2/1; vehicle 3 behind vehicle 2, positions 3/2");

  const acc::RunFileContents contents =
      acc::readRunFile(path, acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::byFollower("3"));
  EXPECT_TRUE(contents.problems.empty()) << joined(contents.problems);
  ASSERT_EQ(contents.runs.size(), 1u);
  EXPECT_EQ(contents.runs[0].size(), 12u);
  EXPECT_EQ(contents.runs[0].name, "ASta_platoon1 vehicle 3");
  EXPECT_DOUBLE_EQ(contents.runs[0].space_gap_m[0], 26.0);          // IVS2
  EXPECT_DOUBLE_EQ(contents.runs[0].follower_speed_mps[0], 11.0);  // Speed3
  EXPECT_DOUBLE_EQ(contents.runs[0].leader_speed_mps[0], 10.5);    // Speed2
}

TEST_F(OpenAccFileTest, AHeaderFirstNeedsTimeAndACarsSpeedToBeOpenAcc)
{
  // A canonical run CSV, and a CSV with a Time column but no car's speed, are not OpenACC files.
  EXPECT_FALSE(acc::looksLikeOpenAccFile(
      write("canonical_first.csv", "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n0.0,20,10,10\n")));
  EXPECT_FALSE(acc::looksLikeOpenAccFile(write("other.csv", "Time,Temperature\n0.0,20\n")));
  // Metadata lines before the header but no Date or Vehicle_order: still refused, as before.
  const acc::OpenAccFile partial = acc::readOpenAccFile(write("partial.csv", "ACC,1\n" + astaZeroFile(3)));
  EXPECT_NE(partial.error.find("metadata missing before the header"), std::string::npos) << partial.error;
}

// An export with a carriage return alone between lines (Excel's "CSV (Macintosh)") is one line
// to the reader: the error says so, and quotes the start of that line, not the whole file.
TEST_F(OpenAccFileTest, AFileWithCarriageReturnsAloneIsSaidToBeSoAndNotQuotedWhole)
{
  std::string text = kPlatoonMetadata + astaZeroFile(3);
  std::replace(text.begin(), text.end(), '\n', '\r');
  const acc::OpenAccFile file = acc::readOpenAccFile(write("mac.csv", text));
  EXPECT_NE(file.error.find("its lines end in a carriage return alone"), std::string::npos) << file.error;
  EXPECT_LT(file.error.size(), 500u) << file.error;
}

// The database's table of mixed-setting runs is known by its header, whatever its name; the
// setting it lists is its header's first word. Fails when another CSV passes for one, or when a
// header naming no known setting is taken for one setting.
TEST_F(OpenAccFileTest, AMixedSettingListingIsKnownByItsHeaderAndNamesItsSetting)
{
  const std::string medium = write("m.csv", "\n filename , Medium timegap setting\nhandling_part3,AUDI_A4 / MAZDA_3/\n");
  EXPECT_TRUE(acc::looksLikeMixedSettingListing(medium));
  const acc::MixedSettingListing read = acc::readMixedSettingListing(medium);
  EXPECT_EQ(read.listed_setting, "M");
  ASSERT_EQ(read.cars_by_run.count("handling_part3"), 1u);
  EXPECT_EQ(read.cars_by_run.at("handling_part3"), (std::vector<std::string>{"AUDI_A4", "MAZDA_3"}));
  EXPECT_TRUE(read.problems.empty()) << joined(read.problems);
  const acc::MixedSettingListing odd = acc::readMixedSettingListing(write("o.csv", "filename,Odd setting\nx,CAR\n"));
  EXPECT_EQ(odd.listed_setting, "");
  EXPECT_TRUE(anyContains(odd.problems, {"line 1: 'Odd setting' names no setting known"})) << joined(odd.problems);
  EXPECT_FALSE(acc::looksLikeMixedSettingListing(write("v.csv", "filename,vehicle\nx,CAR\n")));
  EXPECT_FALSE(acc::looksLikeMixedSettingListing(write("p.csv", kPlatoonMetadata)));
  EXPECT_TRUE(anyContains(acc::readMixedSettingListing((dir_ / "absent.csv").string()).problems, {"cannot open"}));
}
// The campaigns' words for one setting are one letter; a number, a mixed setting or an unknown word
// is none. Fails when min/max are not read as S/L, or case matters, or a mixed "SL" is taken for one.
TEST(DistanceSetting, TheCampaignsWordsForOneSettingAreOneLetter)
{
  for (const char* word : {"S", "s", "short", "Shortest", "min", "MINIMUM"})
    EXPECT_EQ(acc::distanceSettingLetter(word), "S") << word;
  for (const char* word : {"M", "medium", "Mid", "middle"})
    EXPECT_EQ(acc::distanceSettingLetter(word), "M") << word;
  for (const char* word : {"L", "long", "LONGEST", "max", "Maximum"})
    EXPECT_EQ(acc::distanceSettingLetter(word), "L") << word;
  for (const char* word : {"", "SL", "2", "minimal", "?"})
    EXPECT_EQ(acc::distanceSettingLetter(word), "") << word;
  EXPECT_EQ(acc::describeDistanceSetting("S"), "the shortest setting");
  EXPECT_EQ(acc::describeDistanceSetting("SL"), "");
}
}  // namespace
