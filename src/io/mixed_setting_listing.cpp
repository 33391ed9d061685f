#include "acc_identification/io/mixed_setting_listing.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "acc_identification/io/csv_fields.h"
#include "acc_identification/io/distance_setting.h"
#include "acc_identification/model/plain_text.h"
#include "openacc_text.h"

namespace acc
{
namespace
{
/// The header's fields when the line is one: `filename`, then a column naming a setting.
bool isListingHeader(const std::vector<std::string>& fields)
{
  return fields.size() >= 2 && upperCase(fields[0]) == "FILENAME" &&
         upperCase(fields[1]).find("SETTING") != std::string::npos;
}

/// "Long timegap setting" -> "L": the setting a header's first word names, "" for none known.
std::string settingNamedBy(const std::string& column)
{
  return distanceSettingLetter(column.substr(0, column.find_first_of(" _")));
}

/// "BMW_I3/MERCEDES_GLE450" -> both names; empty parts dropped.
std::vector<std::string> carsOf(const std::string& cell)
{
  std::vector<std::string> cars;
  std::size_t start = 0;
  while (start <= cell.size())
  {
    const std::size_t slash = std::min(cell.find('/', start), cell.size());
    const std::string name = openacc::trim(cell.substr(start, slash - start));
    if (!name.empty())
      cars.push_back(name);
    start = slash + 1;
  }
  return cars;
}
}  // namespace

bool looksLikeMixedSettingListing(const std::string& path) { return isListingHeader(firstLineFields(path)); }

MixedSettingListing readMixedSettingListing(const std::string& path)
{
  MixedSettingListing listing;
  listing.path = path;
  std::ifstream in(path);
  if (!in)
  {
    listing.problems.push_back("cannot open the file");
    return listing;
  }
  std::string line;
  bool header_seen = false;
  for (std::size_t number = 1; std::getline(in, line); ++number)
  {
    if (number == 1)
      line = withoutByteOrderMark(line);
    if (isBlankCsvLine(line))
      continue;
    const std::vector<std::string> fields = splitCsvFields(line);
    if (!header_seen)
    {
      header_seen = true;
      if (!isListingHeader(fields))
      {
        listing.problems.push_back("line " + std::to_string(number) + ": not a header 'filename,<setting> setting'");
        return listing;
      }
      listing.listed_setting = settingNamedBy(fields[1]);
      if (listing.listed_setting.empty())
        listing.problems.push_back("line " + std::to_string(number) + ": '" + fields[1] +
                                   "' names no setting known (Long, Medium or Short)");
      continue;
    }
    const std::string run = std::filesystem::path(fields[0]).stem().string();
    const std::vector<std::string> cars = fields.size() >= 2 ? carsOf(fields[1]) : std::vector<std::string>{};
    if (run.empty() || cars.empty())
      listing.problems.push_back("line " + std::to_string(number) + ": " +
                                 (run.empty() ? "no file named" : "no car named for " + run) + ", left out");
    else if (!listing.cars_by_run.emplace(run, cars).second)
      listing.problems.push_back("line " + std::to_string(number) + ": " + run +
                                 " listed a second time, left out (the first line kept)");
  }
  return listing;
}

}  // namespace acc
