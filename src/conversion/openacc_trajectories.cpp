#include <acc_identification/conversion/openacc_trajectories.h>

#include <acc_identification/gnss/utc_date.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

namespace acc
{
namespace
{
std::vector<std::string> splitCsv(const std::string& line)
{
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ','))
  {
    while (!cell.empty() && (cell.back() == '\r' || cell.back() == ' '))
      cell.pop_back();
    while (!cell.empty() && cell.front() == ' ')
      cell.erase(cell.begin());
    cells.push_back(cell);
  }
  return cells;
}

bool parseNumber(const std::string& text, double& value)
{
  if (text.empty())
    return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

/// Reads the "Date,DD,MM,YYYY" line; false when absent or not a real date.
bool parseDate(const std::vector<std::string>& cells, OpenAccTrajectories& file)
{
  double day = 0, month = 0, year = 0;
  if (cells.size() < 4 || cells[0] != "Date" || !parseNumber(cells[1], day) || !parseNumber(cells[2], month) ||
      !parseNumber(cells[3], year))
    return false;
  file.day = static_cast<int>(day);
  file.month = static_cast<int>(month);
  file.year = static_cast<int>(year);
  return isValidDate(file.year, static_cast<unsigned>(file.month), static_cast<unsigned>(file.day));
}

struct Columns
{
  std::map<std::string, std::size_t> index;
  bool has(const std::string& name) const { return index.count(name) > 0; }
};

/// A vehicle's columns are in the file (a missing car's columns are absent).
bool hasVehicle(const Columns& columns, int position)
{
  const std::string k = std::to_string(position);
  return columns.has("Speed" + k) && columns.has("Lat" + k) && columns.has("Lon" + k);
}

/// Followers whose leader (the car directly ahead) and gap are in the file too.
std::vector<int> availableFollowers(const Columns& columns, std::size_t vehicles)
{
  std::vector<int> positions;
  for (int k = 2; k <= static_cast<int>(std::max<std::size_t>(vehicles, 2)); ++k)
  {
    if (hasVehicle(columns, k) && hasVehicle(columns, k - 1) && columns.has("IVS" + std::to_string(k - 1)))
      positions.push_back(k);
  }
  return positions;
}

std::string upper(std::string text)
{
  for (char& c : text)
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

std::string describePairs(const OpenAccTrajectories& file)
{
  std::string text;
  for (int k : file.available_followers)
  {
    OpenAccTrajectories pair = file;
    pair.leader_position = k - 1;
    pair.follower_position = k;
    text += (text.empty() ? "" : ", ") + pair.pairName();
  }
  return text.empty() ? "none" : text;
}

/// The follower's position for a selection, or 0 with error set.
int selectFollower(const OpenAccTrajectories& file, const OpenAccPairSelection& selection, std::string& error)
{
  if (file.available_followers.empty())
  {
    error = "no leader-follower pair with Speed, Lat and Lon of both cars and their IVS gap";
    return 0;
  }
  if (selection.follower.empty())
    return file.available_followers.front();
  int position = 0;
  double number = 0.0;
  if (parseNumber(selection.follower, number))
    position = static_cast<int>(number);
  else
    for (std::size_t i = 0; i < file.vehicle_order.size(); ++i)
      if (upper(file.vehicle_order[i]) == upper(selection.follower))
        position = static_cast<int>(i) + 1;
  for (int k : file.available_followers)
    if (k == position)
      return k;
  error = "no pair with follower '" + selection.follower + "'" +
          (position > 0 ? " (position " + std::to_string(position) +
                              ": this car, the car directly ahead of it, or their gap has no columns here)"
                        : " in Vehicle_order") +
          "; pairs in this file: " + describePairs(file);
  return 0;
}

/// Fills row from cells for the selected pair; returns the first problem, or "" when it is good.
std::string parseRow(const std::vector<std::string>& cells, const Columns& columns, int leader, OpenAccRow& row)
{
  auto get = [&](const std::string& name, double& value, bool required) -> std::string {
    auto at = columns.index.find(name);
    if (at == columns.index.end() || (!required && (at->second >= cells.size() || cells[at->second].empty())))
    {
      value = std::nan("");
      return "";
    }
    if (at->second >= cells.size() || !parseNumber(cells[at->second], value))
      return "column " + name + " is not a number";
    return "";
  };
  std::string problem = get("Time", row.time_of_day_s, true);
  for (int v = 0; v < 2 && problem.empty(); ++v)
  {
    const std::string n = std::to_string(leader + v);
    for (const auto& [name, target, required] :
         {std::tuple<std::string, double*, bool>{"Speed" + n, &row.speed_mps[v], true},
          {"Lat" + n, &row.latitude_rad[v], true}, {"Lon" + n, &row.longitude_rad[v], true},
          {"Alt" + n, &row.altitude_m[v], false}, {"E" + n, &row.east_m[v], false},
          {"N" + n, &row.north_m[v], false}})
      if (problem.empty())
        problem = get(name, *target, required);
  }
  if (problem.empty())
    problem = get("IVS" + std::to_string(leader), row.ivs_m, true);
  return problem;
}

/// Small-distance length of a displacement between two positions read in the given unit [m].
double displacementM(const OpenAccRow& a, const OpenAccRow& b, double to_radians)
{
  constexpr double kEarthRadiusM = 6371000.0;
  const double dlat = (b.latitude_rad[0] - a.latitude_rad[0]) * to_radians;
  const double dlon = (b.longitude_rad[0] - a.longitude_rad[0]) * to_radians * std::cos(a.latitude_rad[0] * to_radians);
  return kEarthRadiusM * std::hypot(dlat, dlon);
}

/// Degrees or radians: values beyond +-pi/2 (latitude) or +-pi (longitude) cannot be radians;
/// otherwise, where E/N exist, the unit whose displacement matches theirs; else the notes' radians.
void detectAngleUnit(OpenAccTrajectories& file)
{
  double max_latitude = 0.0, max_longitude = 0.0;
  for (const OpenAccRow& row : file.rows)
    for (int v = 0; v < 2; ++v)
    {
      max_latitude = std::max(max_latitude, std::abs(row.latitude_rad[v]));
      max_longitude = std::max(max_longitude, std::abs(row.longitude_rad[v]));
    }
  char note[256];
  if (max_latitude > M_PI / 2 || max_longitude > M_PI)
  {
    file.positions_were_degrees = true;
    std::snprintf(note, sizeof note, "Lat/Lon in degrees (|Lat| up to %.4f, |Lon| up to %.4f: beyond radians)",
                  max_latitude, max_longitude);
  }
  else if (file.rows.size() >= 2 && std::isfinite(file.rows.front().east_m[0]) &&
           std::isfinite(file.rows.back().east_m[0]))
  {
    const OpenAccRow& a = file.rows.front();
    const OpenAccRow& b = file.rows.back();
    const double en_m = std::hypot(b.east_m[0] - a.east_m[0], b.north_m[0] - a.north_m[0]);
    const double as_radians_m = displacementM(a, b, 1.0), as_degrees_m = displacementM(a, b, M_PI / 180.0);
    file.positions_were_degrees = std::abs(std::log((as_degrees_m + 1.0) / (en_m + 1.0))) <
                                  std::abs(std::log((as_radians_m + 1.0) / (en_m + 1.0)));
    std::snprintf(note, sizeof note,
                  "Lat/Lon in %s (values fit both; the leader's E/N displacement %.0f m matches %.0f m as %s, not "
                  "%.0f m as %s)",
                  file.positions_were_degrees ? "degrees" : "radians", en_m,
                  file.positions_were_degrees ? as_degrees_m : as_radians_m,
                  file.positions_were_degrees ? "degrees" : "radians",
                  file.positions_were_degrees ? as_radians_m : as_degrees_m,
                  file.positions_were_degrees ? "radians" : "degrees");
  }
  else
  {
    std::snprintf(note, sizeof note, "Lat/Lon in radians (the database's unit; no E/N to check it against)");
  }
  file.angle_unit_note = note;
  if (file.positions_were_degrees)
    for (OpenAccRow& row : file.rows)
      for (int v = 0; v < 2; ++v)
      {
        row.latitude_rad[v] *= M_PI / 180.0;
        row.longitude_rad[v] *= M_PI / 180.0;
      }
}
}  // namespace

double OpenAccTrajectories::dayStartUnixS() const
{
  return static_cast<double>(daysFromCivil(year, static_cast<unsigned>(month), static_cast<unsigned>(day))) *
         kSecondsPerDay;
}

std::string OpenAccTrajectories::pairName() const
{
  auto name = [this](int position) {
    const std::size_t i = static_cast<std::size_t>(position - 1);
    return (position >= 1 && i < vehicle_order.size() && !vehicle_order[i].empty() ? vehicle_order[i]
                                                                                    : "vehicle " + std::to_string(position)) +
           " (" + std::to_string(position) + ")";
  };
  return name(follower_position) + " behind " + name(leader_position);
}

OpenAccTrajectories readOpenAccTrajectories(const std::string& path, const OpenAccPairSelection& selection)
{
  OpenAccTrajectories file;
  std::ifstream in(path);
  if (!in)
  {
    file.error = "cannot open " + path;
    return file;
  }
  std::string line;
  std::size_t number = 0;
  Columns columns;
  bool date_seen = false;
  std::vector<std::pair<std::size_t, std::vector<std::string>>> data;
  while (std::getline(in, line))
  {
    ++number;
    auto cells = splitCsv(line);
    if (cells.empty() || (cells.size() == 1 && cells[0].empty()))
      continue;
    if (!columns.index.empty())
    {
      data.emplace_back(number, std::move(cells));
      continue;
    }
    if (cells[0] == "Date")
    {
      date_seen = parseDate(cells, file);
      if (!date_seen)
        file.error = path + ":" + std::to_string(number) + ": Date line is not Date,DD,MM,YYYY of a real day";
    }
    else if (cells[0] == "Vehicle_order")
    {
      file.vehicle_order.assign(cells.begin() + 1, cells.end());
      while (!file.vehicle_order.empty() && file.vehicle_order.back().empty())
        file.vehicle_order.pop_back();  // "Vehicle_order,A,B," ends with a comma
    }
    else if (cells[0] == "Time")
      for (std::size_t i = 0; i < cells.size(); ++i)
        columns.index[cells[i]] = i;
  }
  if (!file.error.empty())
    return file;
  if (!columns.has("Time"))
  {
    file.error = path + ": no header line starting with Time (not an OpenACC file?)";
    return file;
  }
  for (const char* needed : {"Speed1", "Lat1", "Lon1"})
    if (!columns.has(needed) && !columns.has("Speed2"))
    {
      file.error = path + ": no column " + std::string(needed) + " nor any vehicle's (not an OpenACC file?)";
      return file;
    }
  if (!date_seen)
  {
    file.error = path + ": no Date line: the GNSS times need the day";
    return file;
  }
  std::size_t vehicles = file.vehicle_order.size();
  for (int k = 1; k <= 64; ++k)
    if (columns.has("Speed" + std::to_string(k)))
      vehicles = std::max<std::size_t>(vehicles, static_cast<std::size_t>(k));
  file.available_followers = availableFollowers(columns, vehicles);
  std::string error;
  file.follower_position = selectFollower(file, selection, error);
  if (file.follower_position == 0)
  {
    file.error = path + ": " + error;
    return file;
  }
  file.leader_position = file.follower_position - 1;
  for (const auto& [line_number, cells] : data)
  {
    OpenAccRow row;
    row.line = line_number;
    const std::string problem = parseRow(cells, columns, file.leader_position, row);
    if (problem.empty())
      file.rows.push_back(row);
    else
      file.rejected_rows.push_back("line " + std::to_string(line_number) + ": " + problem);
  }
  detectAngleUnit(file);
  return file;
}

}  // namespace acc
