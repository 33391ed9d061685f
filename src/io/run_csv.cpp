#include "acc_identification/io/run_csv.h"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

namespace acc
{
namespace
{
/// Column indices of the four canonical quantities in the file's header, and how to tell the
/// follower's driving mode (OpenACC only).
struct ColumnMap
{
  std::array<std::size_t, 4> index{};  ///< time, gap, follower speed, leader speed
  std::optional<std::size_t> driver_index;
  std::size_t field_count = 0;
};

std::vector<std::string> splitFields(const std::string& line)
{
  std::vector<std::string> fields;
  std::string field;
  std::istringstream stream(line);
  while (std::getline(stream, field, ','))
  {
    // Trim spaces and a Windows line end, which some exports carry.
    const auto first = field.find_first_not_of(" \t\r");
    const auto last = field.find_last_not_of(" \t\r");
    fields.push_back(first == std::string::npos ? "" : field.substr(first, last - first + 1));
  }
  if (!line.empty() && line.back() == ',')
  {
    fields.emplace_back();
  }
  return fields;
}

std::optional<std::size_t> findColumn(const std::vector<std::string>& header, const std::string& name)
{
  for (std::size_t i = 0; i < header.size(); ++i)
  {
    if (header[i] == name)
    {
      return i;
    }
  }
  return std::nullopt;
}

/// The header names of the canonical format, then of OpenACC (time, gap, follower, leader).
std::optional<ColumnMap> mapColumns(const std::vector<std::string>& header)
{
  static const std::array<std::array<const char*, 4>, 2> kNames{
      {{"time_s", "space_gap_m", "follower_speed_mps", "leader_speed_mps"},
       {"Time", "IVS1", "Speed2", "Speed1"}}};
  for (std::size_t format = 0; format < kNames.size(); ++format)
  {
    ColumnMap map;
    bool complete = true;
    for (std::size_t q = 0; q < 4 && complete; ++q)
    {
      const auto found = findColumn(header, kNames[format][q]);
      complete = found.has_value();
      map.index[q] = found.value_or(0);
    }
    if (complete)
    {
      map.field_count = header.size();
      if (format == 1)
      {
        map.driver_index = findColumn(header, "Driver2");
      }
      return map;
    }
  }
  return std::nullopt;
}

std::optional<double> parseNumber(const std::string& text)
{
  if (text.empty())
  {
    return std::nullopt;
  }
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE)
  {
    return std::nullopt;
  }
  return value;
}

std::string baseName(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const auto dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

/// Accumulates rows into runs, closing the current run at every split point, and accounts for
/// every row it rejects and every hole it splits at in contents.
class RunAssembler
{
public:
  RunAssembler(std::string path, const RunPlausibilityBounds& bounds, RunFileContents& contents)
    : path_(std::move(path)), name_(baseName(path_)), bounds_(bounds), contents_(contents)
  {
  }

  /// Appends a parsed row, or rejects it when its values are implausible or its time does not
  /// increase; starts a new run first when a hole in time separates it from the previous row.
  void add(std::size_t line_number, const std::array<double, 4>& values)
  {
    const std::string implausible = describeImplausibleValue(values[1], values[2], values[3], bounds_);
    if (!implausible.empty())
    {
      ++contents_.implausible_rows;
      reject(line_number, implausible);
      return;
    }
    if (!current_.time_s.empty())
    {
      const std::string not_increasing = describeTimeNotIncreasing(values[0]);
      if (!not_increasing.empty())
      {
        reject(line_number, not_increasing);
        return;
      }
      const std::string hole = describeTimeHole(current_.time_s.back(), values[0], bounds_);
      if (!hole.empty())
      {
        ++contents_.time_holes;
        report(line_number, hole + "; run split");
        split(line_number);
      }
    }
    current_.time_s.push_back(values[0]);
    current_.space_gap_m.push_back(values[1]);
    current_.follower_speed_mps.push_back(values[2]);
    current_.leader_speed_mps.push_back(values[3]);
  }

  /// Counts and lists a row that is not used, and splits the run there.
  void reject(std::size_t line_number, const std::string& why)
  {
    ++contents_.rejected_rows;
    report(line_number, why + "; row rejected, run split here");
    split(line_number);
  }

  void split(std::size_t line_number)
  {
    if (current_.size() >= 2)
    {
      ++pieces_;
      current_.name = pieces_ == 1 ? name_ : name_ + "#" + std::to_string(pieces_);
      contents_.runs.push_back(std::move(current_));
    }
    else if (current_.size() == 1)
    {
      std::ostringstream why;
      why << "a piece of one sample (t = " << current_.time_s[0]
          << " s) between split points is too short to simulate; not used";
      report(line_number, why.str());
    }
    current_ = CarFollowingRun{};
  }

private:
  std::string describeTimeNotIncreasing(double time_s) const
  {
    if (time_s > current_.time_s.back())
    {
      return "";
    }
    std::ostringstream why;
    why << "time " << time_s << " s does not increase (previous row " << current_.time_s.back() << " s)";
    return why.str();
  }

  void report(std::size_t line_number, const std::string& why)
  {
    contents_.problems.push_back(path_ + ":" + std::to_string(line_number) + ": " + why);
  }

  std::string path_;
  std::string name_;
  RunPlausibilityBounds bounds_;
  RunFileContents& contents_;
  CarFollowingRun current_;
  std::size_t pieces_ = 0;
};

/// Parses one data row into the four canonical values, or returns why not.
std::string parseRow(const std::vector<std::string>& fields, const ColumnMap& map,
                     std::array<double, 4>& values)
{
  static const std::array<const char*, 4> kQuantity{"time", "space gap", "follower speed",
                                                    "leader speed"};
  if (fields.size() != map.field_count)
  {
    return "expected " + std::to_string(map.field_count) + " fields, found " +
           std::to_string(fields.size());
  }
  for (std::size_t q = 0; q < 4; ++q)
  {
    const std::string& text = fields[map.index[q]];
    const auto value = parseNumber(text);
    if (!value || !std::isfinite(*value))
    {
      return std::string(kQuantity[q]) + " is not a finite number: '" + text + "'";
    }
    values[q] = *value;
  }
  return "";
}
}  // namespace

RunFileContents readRunFile(const std::string& path, const RunPlausibilityBounds& bounds)
{
  const std::string bounds_problem = describeBoundsProblem(bounds);
  if (!bounds_problem.empty())
  {
    throw std::invalid_argument("readRunFile: unusable plausibility bounds: " + bounds_problem);
  }
  std::ifstream file(path);
  if (!file)
  {
    throw RunReadError("cannot open run file '" + path + "'");
  }
  RunFileContents contents;
  std::string line;
  std::size_t line_number = 0;
  std::optional<ColumnMap> map;
  // The header is the first line that names the four columns; OpenACC puts metadata before it.
  while (!map && std::getline(file, line))
  {
    ++line_number;
    map = mapColumns(splitFields(line));
    if (line_number > 20 && !map)
    {
      break;
    }
  }
  if (!map)
  {
    throw RunReadError(path + ": no header with time_s,space_gap_m,follower_speed_mps,leader_speed_mps "
                              "(or OpenACC Time,IVS1,Speed2,Speed1) in the first 20 lines");
  }
  RunAssembler assembler(path, bounds, contents);
  while (std::getline(file, line))
  {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos)
    {
      continue;  // a blank line (usually the last) carries no sample
    }
    ++contents.data_rows;
    const auto fields = splitFields(line);
    std::array<double, 4> values{};
    const std::string malformed = parseRow(fields, *map, values);
    if (!malformed.empty())
    {
      assembler.reject(line_number, malformed);
    }
    else if (map->driver_index && fields[*map->driver_index] != "ACC")
    {
      ++contents.acc_off_rows;
      assembler.split(line_number);
    }
    else
    {
      assembler.add(line_number, values);
    }
  }
  assembler.split(line_number);
  return contents;
}

namespace
{
/// One line with the counts behind the problems, or "" when nothing was rejected or split.
std::string describeCounts(const std::string& path, const RunFileContents& contents)
{
  if (contents.rejected_rows == 0 && contents.time_holes == 0)
  {
    return "";
  }
  std::ostringstream counts;
  counts << path << ": " << contents.rejected_rows << " of " << contents.data_rows << " rows rejected ("
         << contents.implausible_rows << " outside the plausibility bounds), " << contents.time_holes
         << " holes in time split a run";
  return counts.str();
}
}  // namespace

std::vector<CarFollowingRun> readRuns(const std::string& path, const RunPlausibilityBounds& bounds)
{
  RunFileContents contents = readRunFile(path, bounds);
  for (const std::string& problem : contents.problems)
  {
    std::cerr << "warning: " << problem << "\n";
  }
  const std::string counts = describeCounts(path, contents);
  if (!counts.empty())
  {
    std::cerr << "warning: " << counts << "\n";
  }
  if (contents.runs.empty())
  {
    throw RunReadError(path + ": no usable run (" + std::to_string(contents.data_rows) + " data rows, " +
                       std::to_string(contents.rejected_rows) + " rejected of which " +
                       std::to_string(contents.implausible_rows) + " implausible, " +
                       std::to_string(contents.time_holes) + " holes in time, " +
                       std::to_string(contents.acc_off_rows) + " with ACC off)");
  }
  return std::move(contents.runs);
}

void writeRunCsv(const std::string& path, const CarFollowingRun& run)
{
  std::ofstream file(path);
  if (!file)
  {
    throw RunReadError("cannot write run file '" + path + "'");
  }
  file << "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n"
       << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (std::size_t i = 0; i < run.size(); ++i)
  {
    file << run.time_s[i] << ',' << run.space_gap_m[i] << ',' << run.follower_speed_mps[i] << ','
         << run.leader_speed_mps[i] << '\n';
  }
  if (!file)
  {
    throw RunReadError("error while writing run file '" + path + "'");
  }
}

}  // namespace acc
