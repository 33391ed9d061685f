#include <acc_identification/conversion/openacc_trajectories.h>

#include <acc_identification/gnss/utc_date.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

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

/// Fills row from cells; returns the first problem, or "" when the row is good.
std::string parseRow(const std::vector<std::string>& cells, const Columns& columns, OpenAccRow& row)
{
  auto get = [&](const std::string& name, double& value) -> std::string {
    auto at = columns.index.find(name);
    if (at == columns.index.end())
    {
      value = std::nan("");
      return "";
    }
    if (at->second >= cells.size() || !parseNumber(cells[at->second], value))
      return "column " + name + " is not a number";
    return "";
  };
  std::string problem = get("Time", row.time_of_day_s);
  for (int v = 0; v < 2 && problem.empty(); ++v)
  {
    const std::string n = std::to_string(v + 1);
    for (const auto& [name, target] :
         {std::pair<std::string, double*>{"Speed" + n, &row.speed_mps[v]}, {"Lat" + n, &row.latitude_rad[v]},
          {"Lon" + n, &row.longitude_rad[v]}, {"Alt" + n, &row.altitude_m[v]}, {"E" + n, &row.east_m[v]},
          {"N" + n, &row.north_m[v]}})
      if (problem.empty())
        problem = get(name, *target);
  }
  if (problem.empty())
    problem = get("IVS1", row.ivs_m);
  if (problem.empty() && (std::abs(row.latitude_rad[0]) > M_PI / 2 || std::abs(row.latitude_rad[1]) > M_PI / 2))
    problem = "latitude beyond +-pi/2 rad (OpenACC positions are radians)";
  return problem;
}
}  // namespace

double OpenAccTrajectories::dayStartUnixS() const
{
  return static_cast<double>(daysFromCivil(year, static_cast<unsigned>(month), static_cast<unsigned>(day))) *
         kSecondsPerDay;
}

OpenAccTrajectories readOpenAccTrajectories(const std::string& path)
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
  while (std::getline(in, line))
  {
    ++number;
    auto cells = splitCsv(line);
    if (cells.empty() || (cells.size() == 1 && cells[0].empty()))
      continue;
    if (columns.index.empty())
    {
      if (cells[0] == "Date")
      {
        date_seen = parseDate(cells, file);
        if (!date_seen)
          file.error = path + ":" + std::to_string(number) + ": Date line is not Date,DD,MM,YYYY of a real day";
      }
      else if (cells[0] == "Vehicle_order")
        file.vehicle_order.assign(cells.begin() + 1, cells.end());
      else if (cells[0] == "Time")
        for (std::size_t i = 0; i < cells.size(); ++i)
          columns.index[cells[i]] = i;
      continue;
    }
    OpenAccRow row;
    row.line = number;
    std::string problem = parseRow(cells, columns, row);
    if (problem.empty())
      file.rows.push_back(row);
    else
      file.rejected_rows.push_back("line " + std::to_string(number) + ": " + problem);
  }
  for (const char* needed : {"Time", "Speed1", "Lat1", "Lon1", "Speed2", "Lat2", "Lon2"})
    if (file.error.empty() && !columns.has(needed))
      file.error = path + ": no column " + std::string(needed) + " (not an OpenACC two-vehicle file?)";
  if (file.error.empty() && !date_seen)
    file.error = path + ": no Date line: the GNSS times need the day";
  return file;
}

}  // namespace acc
