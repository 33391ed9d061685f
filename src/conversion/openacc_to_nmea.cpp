#include <acc_identification/conversion/openacc_to_nmea.h>
#include <acc_identification/model/angles.h>

#include <acc_identification/gnss/nmea_writer.h>
#include <acc_identification/gnss/utc_date.h>
#include <acc_identification/io/run_csv.h>
#include <acc_identification/io/run_plausibility.h>
#include <acc_identification/model/number_text.h>

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

namespace acc
{
namespace
{
// Rows further apart than this are not neighbours (the database removed tolls and tunnels).
constexpr double kMaxNeighbourSpacing_s = 0.25;
constexpr double kMinCourseSpeed_mps = 0.5;
constexpr double kMinCourseMotion_m = 0.05;

bool neighbours(const OpenAccRow& a, const OpenAccRow& b)
{
  double step = b.time_of_day_s - a.time_of_day_s;
  return step > 0.0 && step <= kMaxNeighbourSpacing_s;
}

/// Course over ground at row i [rad, clockwise from true north], NaN when not meaningful.
double courseAt(const std::vector<OpenAccRow>& rows, std::size_t i, int v)
{
  std::size_t from = (i > 0 && neighbours(rows[i - 1], rows[i])) ? i - 1 : i;
  std::size_t to = (i + 1 < rows.size() && neighbours(rows[i], rows[i + 1])) ? i + 1 : i;
  if (from == to || rows[i].speed_mps[v] < kMinCourseSpeed_mps)
    return std::nan("");
  double distance = 0, azimuth1 = 0, azimuth2 = 0;
  GeographicLib::Geodesic::WGS84().Inverse(rows[from].latitude_deg[v], rows[from].longitude_deg[v],
                                           rows[to].latitude_deg[v], rows[to].longitude_deg[v], distance, azimuth1,
                                           azimuth2);
  if (distance < kMinCourseMotion_m)
    return std::nan("");
  // A central difference over 0.2 s (at most 9 m) is straight: the azimuth at its start will do.
  double azimuth_deg = to == i ? azimuth2 : azimuth1;
  return std::fmod(azimuth_deg / kRadToDeg + 2.0 * kPi, 2.0 * kPi);
}
}  // namespace

namespace
{
/// Why row i cannot give a row of the pair ("" when it can): the row unread, or a bad cell among
/// the ones the fixes need. Other cars' cells do not matter.
std::string pairRowProblem(const OpenAccFile& file, const OpenAccPair& pair, std::size_t i)
{
  std::vector<std::string> columns{"Time", "IVS" + std::to_string(pair.leader_position)};
  for (int k : {pair.leader_position, pair.follower_position})
    for (const char* quantity : {"Speed", "Lat", "Lon"})
      columns.push_back(quantity + std::to_string(k));
  return file.rowProblem(i, columns);
}
/// The end of a row's problem for a speed above the plausible bound, which the count of such rows
/// looks for (describeUnwritableTrack: most rows so, speeds in km/h?).
constexpr const char* kTooFastForACar = "no car under ACC drives that fast";

/// Why a row whose cells are numbers still cannot be written as the receivers' fixes: a speed an
/// RMC cannot carry (below 0: speed over ground has no sign) or no car drives (above the run
/// readers' bound), or a time that does not follow the last row written (a log runs forward).
std::string rowValueProblem(const OpenAccFile& file, const OpenAccVehicle* const cars[2], std::size_t i,
                            const std::vector<OpenAccRow>& written)
{
  const RunPlausibilityBounds bounds;
  for (int v = 0; v < 2; ++v)
  {
    const double speed = cars[v]->speed_mps[i];
    const std::string column = "Speed" + std::to_string(cars[v]->position);
    if (speed < 0.0)
      return column + " " + significant(speed, 6) + " below 0: an RMC's speed over ground has no sign";
    if (speed > bounds.max_speed_mps)
      return column + " " + significant(speed, 6) + " above " + significant(bounds.max_speed_mps) + " m/s: " +
             kTooFastForACar;
  }
  const double time_s = file.time_s[i];
  if (!written.empty() && !(time_s > written.back().time_of_day_s))
    return "Time " + significant(time_s, 10) + " s not after the last row written (" +
           significant(written.back().time_of_day_s, 10) + " s, line " + std::to_string(written.back().line) +
           "): a receiver's log runs forward";
  // A time too far forward (one corrupt cell) would make every row after it look late: it is the
  // one left out when the next row's time lies between the last row written and it.
  const double last_s = written.empty() ? -std::numeric_limits<double>::infinity() : written.back().time_of_day_s;
  if (i + 1 < file.rows() && file.time_s[i + 1] > last_s && file.time_s[i + 1] < time_s)
    return "Time " + significant(time_s, 10) + " s after the next row's (" + significant(file.time_s[i + 1], 10) +
           " s, line " + std::to_string(file.line[i + 1]) + "): a receiver's log runs forward";
  return "";
}

/// Why the rows kept cannot be a receiver's log ("" when they can): fewer than two (every row
/// skipped: speeds in km/h, say), or steps no receiver takes (a Time column in milliseconds steps by
/// 100 at 10 Hz: the logs would span days, their sentences dated wrongly).
std::string describeUnwritableTrack(const OpenAccPairTrack& track, std::size_t file_rows)
{
  if (track.rows.size() < 2)
  {
    std::size_t too_fast = 0;
    for (const std::string& skipped : track.skipped_rows)
      too_fast += skipped.find(kTooFastForACar) != std::string::npos ? 1 : 0;
    return track.pairName() + ": " + std::to_string(track.rows.size()) + " of " + std::to_string(file_rows) +
           " rows usable (each skipped one is listed above): nothing a receiver's log holds" +
           (2 * too_fast > track.skipped_rows.size() ? "; most rows are too fast: are the speeds in km/h? OpenACC's "
                                                       "are in m/s"
                                                     : "");
  }
  // A handful of rows far apart is an excerpt; the unit shows in a log's many steps.
  constexpr std::size_t kStepsToJudgeTheUnit = 10;
  double shortest_step_s = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < track.rows.size(); ++i)
    shortest_step_s = std::min(shortest_step_s, track.rows[i].time_of_day_s - track.rows[i - 1].time_of_day_s);
  if (track.rows.size() > kStepsToJudgeTheUnit && shortest_step_s >= kImplausibleShortestStepS)
    return track.pairName() + ": even the shortest step of Time is " + significant(shortest_step_s, 6) +
           " s: no receiver logs that coarsely, so Time is not in seconds (milliseconds step by 100 at 10 Hz); "
           "convert it to seconds";
  return "";
}
}  // namespace

double OpenAccPairTrack::dayStartUnixS() const
{
  return static_cast<double>(daysFromCivil(year, static_cast<unsigned>(month), static_cast<unsigned>(day))) *
         kSecondsPerDay;
}

std::string OpenAccPairTrack::pairName() const
{
  return pair.follower_name + " (" + std::to_string(pair.follower_position) + ") behind " + pair.leader_name + " (" +
         std::to_string(pair.leader_position) + ")";
}

OpenAccPairTrack openAccPairTrack(const OpenAccFile& file, const OpenAccPair& pair)
{
  OpenAccPairTrack track;
  track.pair = pair;
  track.year = file.metadata.year;
  track.month = file.metadata.month;
  track.day = file.metadata.day;
  track.angle_unit_note = file.angle_unit_reason;
  track.notes = file.notes;
  if (!file.metadata.lines_present)
  {
    // Without a Date line the sentences would carry day 0: refused rather than misdated.
    track.error = file.path + ": no Date line (the file starts with its header): NMEA sentences need the day";
    return track;
  }
  const OpenAccVehicle* cars[2] = {file.vehicle(pair.leader_position), file.vehicle(pair.follower_position)};
  for (const OpenAccVehicle* car : cars)
    if (car == nullptr || !car->has_lat_lon)
    {
      track.error = file.path + ": " + track.pairName() + ": " +
                    (car ? car->label() : std::string("a car")) + " has no Lat/Lon columns: no positions to convert";
      return track;
    }
  for (std::size_t i = 0; i < file.rows(); ++i)
  {
    std::string problem = pairRowProblem(file, pair, i);
    if (problem.empty())
      problem = rowValueProblem(file, cars, i, track.rows);
    if (!problem.empty())
    {
      track.skipped_rows.push_back(file.path + ":" + std::to_string(file.line[i]) + ": " + problem);
      continue;
    }
    OpenAccRow row;
    row.line = file.line[i];
    row.time_of_day_s = file.time_s[i];
    for (int v = 0; v < 2; ++v)
    {
      row.speed_mps[v] = cars[v]->speed_mps[i];
      row.latitude_deg[v] = cars[v]->latitude_deg[i];
      row.longitude_deg[v] = cars[v]->longitude_deg[i];
      row.altitude_m[v] = cars[v]->altitude_m[i];
      row.east_m[v] = cars[v]->east_m[i];
      row.north_m[v] = cars[v]->north_m[i];
    }
    row.ivs_m = cars[0]->gap_to_follower_m[i];
    track.rows.push_back(row);
  }
  track.error = describeUnwritableTrack(track, file.rows());
  return track;
}

OpenAccPairTrack readOpenAccPairTrack(const std::string& path, const OpenAccPairSelector& selector)
{
  const OpenAccFile file = readOpenAccFile(path);
  OpenAccPairTrack failed;
  failed.notes = file.notes;
  if (!file.error.empty())
  {
    failed.error = file.error;
    return failed;
  }
  if (selector.kind == OpenAccPairSelector::Kind::kAll)
  {
    failed.error = path + ": one pair at a time: choose a follower (" + describeAvailablePairs(file) + ")";
    return failed;
  }
  const OpenAccPairChoice choice = selectOpenAccPairs(file, selector);
  if (!choice.error.empty())
  {
    failed.error = choice.error;
    return failed;
  }
  OpenAccPairTrack track = openAccPairTrack(file, choice.pairs.front());
  track.notes.push_back(choice.note);
  return track;
}

std::vector<GnssFix> openAccFixes(const OpenAccPairTrack& file, int vehicle)
{
  const int v = vehicle == 1 ? 0 : 1;
  std::vector<GnssFix> fixes;
  fixes.reserve(file.rows.size());
  const double day_start_s = file.dayStartUnixS();
  for (std::size_t i = 0; i < file.rows.size(); ++i)
  {
    const OpenAccRow& row = file.rows[i];
    GnssFix fix;
    fix.gnss_time_s = day_start_s + row.time_of_day_s;
    fix.has_date = true;
    fix.receive_time_s = fix.gnss_time_s;
    fix.latitude_deg = row.latitude_deg[v];
    fix.longitude_deg = row.longitude_deg[v];
    fix.speed_over_ground_mps = row.speed_mps[v];
    fix.course_rad = courseAt(file.rows, i, v);
    fix.fix_quality = 1;
    fix.valid_fields = GnssFix::kValidPosition | GnssFix::kValidSpeed | GnssFix::kValidDate;
    if (std::isfinite(fix.course_rad))
      fix.valid_fields |= GnssFix::kValidCourse;
    if (std::isfinite(row.altitude_m[v]))
    {
      fix.altitude_m = row.altitude_m[v];
      fix.valid_fields |= GnssFix::kValidAltitude;
    }
    fixes.push_back(fix);
  }
  return fixes;
}

bool writeNmeaLog(const std::string& path, const std::vector<GnssFix>& fixes, const std::string& talker,
                  std::string& error)
{
  std::ofstream out(path, std::ios::binary);
  if (!out)
  {
    error = "cannot write " + path;
    return false;
  }
  for (const GnssFix& fix : fixes)
    out << formatGga(fix, talker) << "\r\n" << formatRmc(fix, talker) << "\r\n";
  out.flush();
  if (!out)
  {
    error = "write error on " + path;
    return false;
  }
  return true;
}

}  // namespace acc
