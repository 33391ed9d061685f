#pragma once

// The pieces the OpenACC reader's files share (openacc_file.cpp, openacc_angle_unit.cpp,
// openacc_pairs.cpp): the text of fields and cells, the kind of a column by its name, and what
// the header says about a car. Internal to the reader: not part of the package's API.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/io/openacc_file.h"
#include "acc_identification/model/plain_text.h"

namespace acc
{
namespace openacc
{
/// Without the spaces, tabs and line ends around it.
std::string trim(const std::string& text);
/// A whole decimal number, the whole text; nullopt otherwise.
std::optional<long> parseInteger(const std::string& text);

/// The quantity of a per-vehicle or per-pair column ("Speed3" -> Speed, 3).
enum class Quantity
{
  kSpeed,
  kEast,
  kNorth,
  kUp,
  kAltitude,
  kLatitude,
  kLongitude,
  kDriver,
  kGap
};
/// The quantity and car number of a column name ("IVS2" -> gap, 2), or nullopt for any other name.
std::optional<std::pair<Quantity, int>> classifyColumn(const std::string& name);
/// The database's spelling of a column written in another case ("time" -> "Time", "ivs2" ->
/// "IVS2", "speed1" -> "Speed1"); any other name unchanged.
std::string canonicalColumnName(const std::string& name);

bool hasColumn(const OpenAccFile& file, const std::string& name);
/// Whether the header has any column of the car at this position (not counting IVS).
bool hasAnyColumnOf(const OpenAccFile& file, int position);
/// "its columns are empty" or "its columns are absent", for a car without data.
std::string noDataReason(const OpenAccFile& file, int position);

/// Decides the unit of the Lat/Lon cells and says why (file.angle_unit, angle_unit_reason);
/// converts them to degrees (openacc_angle_unit.cpp).
void detectAngleUnit(OpenAccFile& file);
/// After detectAngleUnit: each Lat beyond +-90 degrees or Lon beyond +-180 set aside as a bad
/// cell (NaN, listed in problems, counted), not taken as a position.
void setAsideImpossibleAngles(OpenAccFile& file);

}  // namespace openacc
}  // namespace acc
