#include "openacc_text.h"
#include "acc_identification/io/csv_fields.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>

namespace acc
{
namespace openacc
{
std::string trim(const std::string& text)
{
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
  {
    return "";
  }
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

std::optional<long> parseInteger(const std::string& text)
{
  if (text.empty())
  {
    return std::nullopt;
  }
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE)
  {
    return std::nullopt;
  }
  return value;
}


namespace
{
/// The per-vehicle and per-pair columns: their names' prefixes before the position.
const std::vector<std::pair<std::string, Quantity>>& columnPrefixes()
{
  static const std::vector<std::pair<std::string, Quantity>> kPrefixes{
      {"Speed", Quantity::kSpeed}, {"E", Quantity::kEast},      {"N", Quantity::kNorth},
      {"U", Quantity::kUp},        {"Alt", Quantity::kAltitude}, {"Lat", Quantity::kLatitude},
      {"Lon", Quantity::kLongitude}, {"Driver", Quantity::kDriver}, {"IVS", Quantity::kGap}};
  return kPrefixes;
}
}  // namespace

std::string canonicalColumnName(const std::string& name)
{
  if (upperCase(name) == "TIME")
    return "Time";
  const auto digits = name.find_first_of("0123456789");
  if (digits == std::string::npos || digits == 0)
    return name;
  const std::string prefix = upperCase(name.substr(0, digits));
  for (const auto& entry : columnPrefixes())
  {
    if (prefix == upperCase(entry.first))
      return entry.first + name.substr(digits);
  }
  return name;
}

std::optional<std::pair<Quantity, int>> classifyColumn(const std::string& name)
{
  const auto digits = name.find_first_of("0123456789");
  if (digits == std::string::npos || digits == 0 ||
      name.find_first_not_of("0123456789", digits) != std::string::npos || name[digits] == '0')
  {
    return std::nullopt;
  }
  const std::string prefix = name.substr(0, digits);
  const auto number = parseInteger(name.substr(digits));
  if (!number || *number < 1 || *number > 1000)
  {
    return std::nullopt;
  }
  for (const auto& [known, quantity] : columnPrefixes())
  {
    if (prefix == known)
    {
      return std::make_pair(quantity, static_cast<int>(*number));
    }
  }
  return std::nullopt;
}


bool hasColumn(const OpenAccFile& file, const std::string& name)
{
  return std::find(file.header.begin(), file.header.end(), name) != file.header.end();
}

/// Whether the header has any column of the car at this position (not counting IVS).
bool hasAnyColumnOf(const OpenAccFile& file, int position)
{
  for (const std::string& name : file.header)
  {
    const auto column = classifyColumn(name);
    if (column && column->first != Quantity::kGap && column->second == position)
    {
      return true;
    }
  }
  return false;
}

std::string noDataReason(const OpenAccFile& file, int position)
{
  return hasAnyColumnOf(file, position) ? "its columns are empty" : "its columns are absent";
}


}  // namespace openacc
}  // namespace acc
