#include "acc_identification/reproduction/canonical_run_csv.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace acc_identification
{
namespace
{
std::vector<std::string> splitFields(const std::string& line)
{
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ','))
  {
    while (!field.empty() && (field.back() == '\r' || field.back() == ' '))
    {
      field.pop_back();
    }
    fields.push_back(field);
  }
  return fields;
}

bool parseFinite(const std::string& text, double& value)
{
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && std::isfinite(value);
}

constexpr std::array<const char*, 4> kColumns{"time_s", "space_gap_m", "follower_speed_mps", "leader_speed_mps"};
}  // namespace

CanonicalRunCsv readCanonicalRunCsv(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw std::runtime_error(path + ": cannot open");
  }
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = splitFields(line);
  std::array<std::size_t, 4> column{};
  for (std::size_t c = 0; c < kColumns.size(); ++c)
  {
    std::size_t found = 0;
    while (found < header.size() && header[found] != kColumns[c])
    {
      ++found;
    }
    if (found == header.size())
    {
      throw std::runtime_error(path + ": header lacks column " + kColumns[c] +
                               " (expected time_s,space_gap_m,follower_speed_mps,leader_speed_mps)");
    }
    column[c] = found;
  }
  CanonicalRunCsv result;
  result.run.name = path;
  std::size_t line_number = 1;
  while (std::getline(in, line))
  {
    ++line_number;
    if (line.empty() || line == "\r")
    {
      continue;
    }
    const std::vector<std::string> fields = splitFields(line);
    std::array<double, 4> values{};
    std::string why;
    if (fields.size() != header.size())
    {
      why = "expected " + std::to_string(header.size()) + " fields, found " + std::to_string(fields.size());
    }
    for (std::size_t c = 0; why.empty() && c < kColumns.size(); ++c)
    {
      if (!parseFinite(fields[column[c]], values[c]))
      {
        why = std::string(kColumns[c]) + " '" + fields[column[c]] + "' is not a finite number";
      }
    }
    if (why.empty() && !result.run.time_s.empty() && !(values[0] > result.run.time_s.back()))
    {
      why = "time does not increase";
    }
    if (!why.empty())
    {
      ++result.rejected_rows;
      result.problems.push_back(path + ":" + std::to_string(line_number) + ": " + why);
      continue;
    }
    result.run.time_s.push_back(values[0]);
    result.run.space_gap_m.push_back(values[1]);
    result.run.follower_speed_mps.push_back(values[2]);
    result.run.leader_speed_mps.push_back(values[3]);
  }
  if (result.run.size() < 2)
  {
    throw std::runtime_error(path + ": fewer than two usable rows");
  }
  return result;
}

}  // namespace acc_identification
