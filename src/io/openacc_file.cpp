#include "acc_identification/io/openacc_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <utility>

#include "openacc_text.h"
#include "acc_identification/io/csv_fields.h"
#include "acc_identification/io/repeated_recording.h"

namespace acc
{
using namespace openacc;

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Metadata and the header are at the top; a file without a Time header this far down is not OpenACC.
constexpr std::size_t kMaxLinesBeforeHeader = 50;

/// A note that is also a metadata problem (OpenAccFile::metadata_problems).
void noteMetadataProblem(OpenAccFile& file, const std::string& text)
{
  file.notes.push_back(text);
  file.metadata_problems.push_back(text);
}

bool isLeapYear(long year)
{
  return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

bool isRealDay(long year, long month, long day)
{
  static const int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (year < 1900 || year > 2200 || month < 1 || month > 12 || day < 1)
  {
    return false;
  }
  return day <= kDays[month - 1] + (month == 2 && isLeapYear(year) ? 1 : 0);
}



/// Where one column's values go while the rows are read.
struct ColumnTarget
{
  std::size_t field = 0;
  std::string name;
  std::vector<double>* values = nullptr;     ///< numeric column
  std::vector<std::string>* texts = nullptr; ///< Driver column
};

/// One vehicle while it is read: its columns, whether it is kept is decided after the rows.
struct VehicleUnderConstruction
{
  OpenAccVehicle vehicle;
  bool any_column = false;
};


/// Which metadata lines were seen before the header.
struct MetadataSeen
{
  bool date = false, order = false, count = false, acc = false, setting = false;
  std::size_t other_lines = 0;  ///< non-blank lines before the header that are not metadata
  bool anyLine() const { return date || order || count || acc || setting || other_lines > 0; }
};

/// A number after a metadata key ("Number_of_vehicles,5" -> 5), or nullopt.
std::optional<long> integerField(const std::vector<std::string>& fields, std::size_t at)
{
  return fields.size() > at ? parseInteger(fields[at]) : std::nullopt;
}

/// Date,DD,MM,YYYY of a real day; false with file.error set otherwise.
bool readDateLine(const std::vector<std::string>& fields, const std::string& line, const std::string& where,
                  OpenAccFile& file)
{
  const auto day = integerField(fields, 1), month = integerField(fields, 2), year = integerField(fields, 3);
  if (!day || !month || !year || !isRealDay(*year, *month, *day))
  {
    file.error = where + "the Date line is not Date,DD,MM,YYYY of a real day: '" + shortened(trim(line)) + "'";
    return false;
  }
  file.metadata.day = static_cast<int>(*day);
  file.metadata.month = static_cast<int>(*month);
  file.metadata.year = static_cast<int>(*year);
  return true;
}

/// The names after the key, without the empty ones a trailing comma leaves ("Vehicle_order,A,B,").
std::vector<std::string> namesAfterKey(const std::vector<std::string>& fields)
{
  std::vector<std::string> names(fields.begin() + 1, fields.end());
  while (!names.empty() && names.back().empty())
  {
    names.pop_back();
  }
  return names;
}

/// A number line (Number_of_vehicles, ACC): its value, or -1 with a note when it is not a whole
/// number from 0 to a million (-1 is "unknown" to the readers, so a written -1 is said too).
int readNumberLine(const std::vector<std::string>& fields, const std::string& line, const std::string& what,
                   const std::string& where, OpenAccFile& file)
{
  const auto value = integerField(fields, 1);
  if (!value || *value < 0 || *value > 1000000)
  {
    noteMetadataProblem(file, where + what + (value ? " is not a count" : " is not a number") + ": '" + trim(line) +
                                  "'");
    return -1;
  }
  return static_cast<int>(*value);
}

/// One line before the header; false with file.error set when it makes the file unreadable.
bool readMetadataLine(const std::string& line, const std::vector<std::string>& fields, const std::string& where,
                      OpenAccFile& file, MetadataSeen& seen)
{
  const std::string key = upperCase(fields[0]);
  if (key == "DATE")
  {
    seen.date = true;
    return readDateLine(fields, line, where, file);
  }
  if (key == "VEHICLE_ORDER")
  {
    file.metadata.vehicle_order = namesAfterKey(fields);
    seen.order = !file.metadata.vehicle_order.empty();
  }
  else if (key == "NUMBER_OF_VEHICLES")
  {
    file.metadata.number_of_vehicles = readNumberLine(fields, line, "Number_of_vehicles", where, file);
    seen.count = true;
  }
  else if (key == "ACC")
  {
    file.metadata.acc = readNumberLine(fields, line, "the ACC line", where, file);
    if (file.metadata.acc > 2)  // the database's: 0 manual, 1 ACC throughout, 2 mixed
    {
      noteMetadataProblem(file, where + "the ACC line says " + std::to_string(file.metadata.acc) +
                                    ", none of 0 (manual), 1 (ACC) and 2 (mixed): read as absent: '" + trim(line) +
                                    "'");
      file.metadata.acc = -1;
    }
    seen.acc = true;
  }
  else if (key == "DISTANCE_SETTING")
  {
    file.metadata.distance_setting = fields.size() > 1 ? trim(fields[1]) : "";
    if (file.metadata.distance_setting.empty())
      noteMetadataProblem(file, where + "the Distance_setting line names no setting: its cars' setting is unknown "
                                        "('?')");
    seen.setting = true;
  }
  else
  {
    ++seen.other_lines;
    noteMetadataProblem(file, where + "line before the header not understood, ignored: '" + trim(line).substr(0, 80) + "'");
  }
  return true;
}

/// A line with a Time column, in any case.
bool isHeaderLine(const std::vector<std::string>& fields)
{
  return std::any_of(fields.begin(), fields.end(),
                     [](const std::string& name) { return canonicalColumnName(name) == "Time"; });
}

/// A first line that is already the header (the layout without metadata): a Time column and a
/// car's Speedk column, so that a canonical run CSV (time_s, ...) or any other CSV is not taken.
bool isHeaderWithoutMetadata(const std::vector<std::string>& fields)
{
  return isHeaderLine(fields) && std::any_of(fields.begin(), fields.end(), [](const std::string& name) {
           const auto column = classifyColumn(canonicalColumnName(name));
           return column && column->first == Quantity::kSpeed;
         });
}

/// The header's names, without the empty ones a trailing comma leaves, each in the database's
/// spelling (canonicalColumnName); the names written in another case are said in a note.
std::vector<std::string> headerNames(std::vector<std::string> fields, OpenAccFile& file)
{
  while (!fields.empty() && fields.back().empty())
  {
    fields.pop_back();
  }
  std::vector<std::string> respelled;
  for (std::string& name : fields)
  {
    const std::string canonical = canonicalColumnName(name);
    if (canonical != name)
      respelled.push_back(name + " as " + canonical);
    name = canonical;
  }
  if (!respelled.empty())
    file.notes.push_back(file.path + ": columns written in another case, read as the database names them: " +
                         join(respelled, ", "));
  return fields;
}

std::string noHeaderError(const OpenAccFile& file, std::size_t line_number)
{
  return file.path + ": no header line with a Time column" +
         (line_number >= kMaxLinesBeforeHeader ? " in the first " + std::to_string(kMaxLinesBeforeHeader) + " lines"
                                               : "") +
         " (not an OpenACC file?)";
}

/// A name Vehicle_order gives twice: two cars of one run cannot be one car (their data would be
/// fitted as one car's two runs), so the later one is named apart, NAME_k after its position k,
/// and a metadata problem says so.
void nameRepeatedCarsApart(OpenAccFile& file)
{
  std::vector<std::string>& order = file.metadata.vehicle_order;
  for (std::size_t k = 1; k < order.size(); ++k)
  {
    const auto first = std::find(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k), order[k]);
    if (first == order.begin() + static_cast<std::ptrdiff_t>(k))
      continue;
    const std::string apart = order[k] + "_" + std::to_string(k + 1);
    noteMetadataProblem(file, file.path + ": Vehicle_order names " + order[k] + " at positions " +
                                  std::to_string(first - order.begin() + 1) + " and " + std::to_string(k + 1) +
                                  ": the one at " + std::to_string(k + 1) + " is read as " + apart +
                                  ", a car of its own (check the line)");
    order[k] = apart;
  }
}

/// Without Date and Vehicle_order the file is not read; the other lines missing are a note.
bool checkMetadataLines(const MetadataSeen& seen, std::size_t header_line, OpenAccFile& file)
{
  if (!seen.date || !seen.order)
  {
    std::vector<std::string> missing;
    if (!seen.date)
    {
      missing.push_back("Date,DD,MM,YYYY");
    }
    if (!seen.order)
    {
      missing.push_back("Vehicle_order,NAME1,NAME2,...");
    }
    file.error = file.path + ": metadata missing before the header (line " + std::to_string(header_line) +
                 "): no " + join(missing, " and no ") + " line; an OpenACC file starts with Date, Vehicle_order, "
                 "Number_of_vehicles, ACC and Distance_setting lines";
    return false;
  }
  std::vector<std::string> absent;
  if (!seen.count)
  {
    absent.push_back("Number_of_vehicles");
  }
  if (!seen.acc)
  {
    absent.push_back("ACC");
  }
  if (!seen.setting)
  {
    absent.push_back("Distance_setting");
  }
  if (!absent.empty())
  {
    noteMetadataProblem(file, file.path + ": no " + join(absent, ", ") + " line (left unknown)");
  }
  nameRepeatedCarsApart(file);
  const int order_size = static_cast<int>(file.metadata.vehicle_order.size());
  if (file.metadata.number_of_vehicles >= 0 && file.metadata.number_of_vehicles != order_size)
  {
    noteMetadataProblem(file, file.path + ": Number_of_vehicles says " + std::to_string(file.metadata.number_of_vehicles) +
                         " but Vehicle_order names " + std::to_string(order_size) + " cars");
  }
  return true;
}


/// A file that starts with its header (the AstaZero layout of the database) has no metadata: the
/// cars are counted from the columns and named by position; the rest is unknown, and said so.
void noteAbsentMetadata(OpenAccFile& file)
{
  file.metadata.lines_present = false;
  const int cars = file.lastPosition();
  file.notes.push_back(file.path + ": no metadata lines (Date, Vehicle_order, Number_of_vehicles, ACC, "
                                   "Distance_setting): the file starts with its header, as the AstaZero layout does; " +
                       std::to_string(cars) + " car" + (cars == 1 ? "" : "s") +
                       " from the columns, named by position (vehicle 1, vehicle 2, ...); date, ACC and distance "
                       "setting unknown");
}

/// Reads the metadata lines and the header; returns false with file.error set when it cannot.
bool readMetadataAndHeader(std::istream& in, OpenAccFile& file, std::size_t& line_number)
{
  std::string line;
  MetadataSeen seen;
  while (std::getline(in, line))
  {
    ++line_number;
    if (line_number == 1)
      line = withoutByteOrderMark(line);
    if (isBlankCsvLine(line))
    {
      continue;
    }
    const std::vector<std::string> fields = splitCsvFields(line);
    if (isHeaderLine(fields))
    {
      file.header = headerNames(fields, file);
      break;
    }
    const std::string where = file.path + ":" + std::to_string(line_number) + ": ";
    if (!readMetadataLine(line, fields, where, file, seen))
    {
      return false;
    }
    if (line_number >= kMaxLinesBeforeHeader)
    {
      break;
    }
  }
  if (file.header.empty())
  {
    file.error = noHeaderError(file, line_number);
    return false;
  }
  if (!seen.anyLine())
  {
    noteAbsentMetadata(file);
    return true;
  }
  return checkMetadataLines(seen, line_number, file);
}

/// A car with columns beyond Vehicle_order gets a made-up name: said, unless the file has no
/// metadata at all (then every car is named by position, said once).
void noteCarsBeyondVehicleOrder(OpenAccFile& file)
{
  if (!file.metadata.lines_present)
  {
    return;
  }
  for (const OpenAccVehicle& v : file.vehicles)
  {
    if (v.position > static_cast<int>(file.metadata.vehicle_order.size()))
    {
      noteMetadataProblem(file, file.path + ": columns of car " + std::to_string(v.position) + " but Vehicle_order names " +
                           std::to_string(file.metadata.vehicle_order.size()) + " cars: called '" + v.name + "'");
    }
  }
}

/// The header's columns by name; false with file.error set when a name is given twice.
bool indexColumns(OpenAccFile& file, std::size_t header_line, std::map<std::string, std::size_t>& index)
{
  for (std::size_t i = 0; i < file.header.size(); ++i)
  {
    if (!file.header[i].empty() && !index.emplace(file.header[i], i).second)
    {
      file.error = file.path + ":" + std::to_string(header_line) + ": column " + file.header[i] +
                   " is named twice in the header";
      return false;
    }
  }
  return true;
}

/// The header's columns sorted by what they hold.
struct HeaderLayout
{
  std::optional<std::size_t> time_field;
  std::map<int, VehicleUnderConstruction> cars;
  std::map<int, std::pair<std::size_t, std::string>> gap_columns;  // k -> field, name of IVSk
  std::vector<std::string> unused;
};

/// Marks what a car has from one of its columns (E and N count only together, as Lat and Lon).
void addVehicleColumn(const OpenAccFile& file, Quantity quantity, int k, VehicleUnderConstruction& car)
{
  car.any_column = true;
  car.vehicle.position = k;
  car.vehicle.name = file.vehicleName(k);
  const std::string n = std::to_string(k);
  switch (quantity)
  {
    case Quantity::kSpeed: car.vehicle.has_speed = true; break;
    case Quantity::kEast:
    case Quantity::kNorth: car.vehicle.has_east_north = hasColumn(file, "E" + n) && hasColumn(file, "N" + n); break;
    case Quantity::kUp: car.vehicle.has_up = true; break;
    case Quantity::kAltitude: car.vehicle.has_altitude = true; break;
    case Quantity::kLatitude:
    case Quantity::kLongitude:
      car.vehicle.has_lat_lon = hasColumn(file, "Lat" + n) && hasColumn(file, "Lon" + n);
      break;
    case Quantity::kDriver: car.vehicle.has_driver = true; break;
    case Quantity::kGap: break;
  }
}

HeaderLayout classifyHeader(const OpenAccFile& file)
{
  HeaderLayout layout;
  for (std::size_t i = 0; i < file.header.size(); ++i)
  {
    const std::string& name = file.header[i];
    if (name == "Time")
    {
      layout.time_field = i;
      continue;
    }
    const auto column = name.empty() ? std::nullopt : classifyColumn(name);
    if (!column)
    {
      if (!name.empty())
      {
        layout.unused.push_back(name);
      }
      continue;
    }
    const auto [quantity, k] = *column;
    if (quantity == Quantity::kGap)
    {
      layout.gap_columns[k] = {i, name};
      continue;
    }
    addVehicleColumn(file, quantity, k, layout.cars[k]);
  }
  return layout;
}

/// IVSk belongs to car k (the gap behind it); without car k it is not used, and said so.
void attachGapColumns(OpenAccFile& file, HeaderLayout& layout)
{
  for (const auto& [k, gap] : layout.gap_columns)
  {
    auto car = layout.cars.find(k);
    if (car == layout.cars.end())
    {
      layout.unused.push_back(gap.second + " (car " + std::to_string(k) + ", " + file.vehicleName(k) +
                              ", has no columns)");
      continue;
    }
    car->second.vehicle.has_gap_to_follower = true;
  }
  if (!layout.unused.empty())
  {
    file.notes.push_back(file.path + ": columns not used: " + join(layout.unused, ", "));
  }
}

/// Where each column's values go. The vectors are filled row by row (all to the same length);
/// absent columns are filled with NaN at the end.
std::vector<ColumnTarget> columnTargets(OpenAccFile& file, HeaderLayout& layout,
                                        const std::map<std::string, std::size_t>& index)
{
  std::vector<ColumnTarget> targets;
  targets.push_back({*layout.time_field, "Time", &file.time_s, nullptr});
  for (auto& [k, car] : layout.cars)
  {
    OpenAccVehicle& v = car.vehicle;
    const std::string n = std::to_string(k);
    const std::vector<std::pair<std::string, std::vector<double>*>> numeric{
        {"Speed" + n, &v.speed_mps}, {"E" + n, &v.east_m},          {"N" + n, &v.north_m},
        {"U" + n, &v.up_m},          {"Alt" + n, &v.altitude_m},     {"Lat" + n, &v.latitude_deg},
        {"Lon" + n, &v.longitude_deg}, {"IVS" + n, &v.gap_to_follower_m}};
    for (const auto& [name, values] : numeric)
    {
      const auto at = index.find(name);
      if (at != index.end())
      {
        targets.push_back({at->second, name, values, nullptr});
      }
    }
    const auto driver = index.find("Driver" + n);
    if (driver != index.end())
    {
      targets.push_back({driver->second, "Driver" + n, nullptr, &v.driver});
    }
  }
  return targets;
}

/// A row with the wrong number of fields: every value NaN, the row counted and listed.
void addUnreadRow(OpenAccFile& file, const std::vector<ColumnTarget>& targets, std::size_t fields,
                  const std::string& where)
{
  const std::string why =
      "expected " + std::to_string(file.header.size()) + " fields, found " + std::to_string(fields);
  file.row_problems.push_back(why);
  file.problems.push_back(where + why + "; row not read (every value NaN)");
  ++file.bad_rows;
  for (const ColumnTarget& target : targets)
  {
    if (target.values)
    {
      target.values->push_back(kNaN);
    }
    else
    {
      target.texts->emplace_back();
    }
  }
}

/// A row's cells into their columns; every cell without a number is counted and listed.
void addRowCells(OpenAccFile& file, const std::vector<ColumnTarget>& targets, const std::vector<std::string>& fields,
                 std::size_t line_number, const std::string& where)
{
  const std::size_t row = file.line.size() - 1;
  file.row_problems.emplace_back();
  std::vector<std::string> bad_here;
  for (const ColumnTarget& target : targets)
  {
    const std::string& text = fields[target.field];
    bool bad = false;
    if (target.values)
    {
      double value = kNaN;
      bad = parseCell(text, value) != CellKind::kNumber;
      target.values->push_back(value);
    }
    else
    {
      target.texts->push_back(text);
      bad = text.empty();
    }
    if (bad)
    {
      file.bad_cells.push_back({row, line_number, target.name, text, ""});
      ++file.bad_cells_by_column[target.name];
      bad_here.push_back(file.bad_cells.back().describe());
    }
  }
  if (!bad_here.empty())
  {
    ++file.bad_rows;
    file.problems.push_back(where + std::to_string(bad_here.size()) + " cell" + (bad_here.size() > 1 ? "s" : "") +
                            " without a number (NaN): " + join(bad_here, ", "));
  }
}

/// Every data row after the header; none is dropped (a blank line is no row).
void readDataRows(std::istream& in, OpenAccFile& file, const std::vector<ColumnTarget>& targets,
                  std::size_t& line_number)
{
  std::string line;
  std::vector<std::string> previous_fields;
  while (std::getline(in, line))
  {
    ++line_number;
    if (isBlankCsvLine(line))
    {
      continue;  // a blank line (usually the last) carries no sample
    }
    std::vector<std::string> fields = splitCsvFields(line);
    // Empty fields past the header's (a trailing comma) carry nothing.
    while (fields.size() > file.header.size() && fields.back().empty())
    {
      fields.pop_back();
    }
    if (!file.line.empty() && fields == previous_fields)
    {
      // An export's duplicate: no sample of its own, and a second row at one time would stop
      // every stretch there. Listed and counted, not kept.
      file.duplicate_lines.push_back(line_number);
      file.problems.push_back(file.path + ":" + std::to_string(line_number) +
                              ": the same cells as the row before; duplicate row dropped");
      continue;
    }
    previous_fields = fields;
    file.line.push_back(line_number);
    const std::string where = file.path + ":" + std::to_string(line_number) + ": ";
    if (fields.size() != file.header.size())
    {
      addUnreadRow(file, targets, fields.size(), where);
    }
    else
    {
      addRowCells(file, targets, fields, line_number, where);
    }
  }
}

std::size_t countFinite(const std::vector<double>& values)
{
  return static_cast<std::size_t>(
      std::count_if(values.begin(), values.end(), [](double x) { return std::isfinite(x); }));
}

/// Absent columns become NaN in every row; the counts of speed and gap values are taken.
void completeColumns(OpenAccVehicle& v, std::size_t rows)
{
  for (std::vector<double>* values : {&v.speed_mps, &v.east_m, &v.north_m, &v.up_m, &v.altitude_m, &v.latitude_deg,
                                      &v.longitude_deg, &v.gap_to_follower_m})
  {
    values->resize(rows, kNaN);
  }
  v.speed_values = countFinite(v.speed_mps);
  v.gap_values = countFinite(v.gap_to_follower_m);
}

/// Whether the car has any value besides its gap (a gap alone does not make a car).
bool hasAnyValue(const OpenAccVehicle& v)
{
  bool any_value = v.speed_values > 0 ||
                   std::any_of(v.driver.begin(), v.driver.end(), [](const std::string& t) { return !t.empty(); });
  for (const std::vector<double>* values : {&v.east_m, &v.north_m, &v.up_m, &v.altitude_m, &v.latitude_deg,
                                            &v.longitude_deg})
  {
    any_value = any_value || countFinite(*values) > 0;
  }
  return any_value;
}

/// Keeps the cars with a value; the others, and the cars of Vehicle_order without columns, are noted.
void keepCarsWithData(OpenAccFile& file, std::map<int, VehicleUnderConstruction>& cars)
{
  std::vector<std::pair<int, std::string>> without_data;
  for (auto& [k, car] : cars)
  {
    completeColumns(car.vehicle, file.line.size());
    if (hasAnyValue(car.vehicle))
    {
      file.vehicles.push_back(std::move(car.vehicle));
    }
    else
    {
      without_data.emplace_back(k,
                                file.vehicleName(k) + " (" + std::to_string(k) + ", every cell of its columns empty)");
    }
  }
  for (int k = 1; k <= static_cast<int>(file.metadata.vehicle_order.size()); ++k)
  {
    if (cars.count(k) == 0)
    {
      without_data.emplace_back(k, file.vehicleName(k) + " (" + std::to_string(k) + ", no columns)");
    }
  }
  std::sort(without_data.begin(), without_data.end());
  noteCarsBeyondVehicleOrder(file);
  if (!without_data.empty())
  {
    std::vector<std::string> names;
    for (const auto& entry : without_data)
    {
      names.push_back(entry.second);
    }
    file.notes.push_back(file.path + ": no data for " + join(names, ", "));
  }
}

/// The ACC line against the followers' Driver columns, where they have them (the lead car is
/// driven by a person whatever the line says): ACC 0 (manual driving) while a Driver cell says
/// ACC, or ACC 1 while none does. The readers follow the Driver column row by row; said here.
void noteAccLineAgainstDriverColumns(OpenAccFile& file)
{
  std::vector<std::string> columns, with_acc;
  for (const OpenAccVehicle& v : file.vehicles)
  {
    if (v.position < 2 || !v.has_driver)
      continue;
    const std::string column = "Driver" + std::to_string(v.position);
    columns.push_back(column);
    if (std::any_of(v.driver.begin(), v.driver.end(), isAccDriverCell))
      with_acc.push_back(column);
  }
  if (file.metadata.acc == 0 && !with_acc.empty())
    noteMetadataProblem(file, file.path + ": the ACC line says 0 (manual driving) but " + join(with_acc, ", ") +
                                  " mark rows ACC; each follower's Driver column is followed row by row");
  if (file.metadata.acc == 1 && !columns.empty() && with_acc.empty())
    noteMetadataProblem(file, file.path + ": the ACC line says 1 (ACC on) but no cell of " + join(columns, ", ") +
                                  " says ACC; each follower's Driver column is followed row by row: no row is on ACC");
}

/// Whether two cars' speeds are one column written twice: equal, to the last bit, on every row where
/// both hold a number, and varying there (kRepeatedRecordingMinSamples rows or more, with
/// kRepeatedRecordingMinChanges changes or more: a standstill or a held value decides nothing). Equal on
/// part of the rows, or shifted by some rows (Newell's copy of the car ahead, a radar-derived
/// leader speed whose relative speed is zero for a while) is two series.
bool sameColumn(const std::vector<double>& a, const std::vector<double>& b)
{
  std::size_t common = 0, changes = 0;
  double previous = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t row = 0; row < std::min(a.size(), b.size()); ++row)
  {
    if (!std::isfinite(a[row]) || !std::isfinite(b[row]))
      continue;
    if (a[row] != b[row])
      return false;
    changes += common > 0 && a[row] != previous ? 1 : 0;
    previous = a[row];
    ++common;
  }
  return common >= kRepeatedRecordingMinSamples && changes >= kRepeatedRecordingMinChanges;
}

/// Marks each car whose speeds are an earlier car's column written again (sameColumn: an export or
/// an edit that copied a column; two cars' measured speeds never agree to the last bit on every
/// row while they vary). Which of the two is the copy the file cannot tell; the later one is set
/// aside, and the note says so.
void markCopiedColumns(OpenAccFile& file)
{
  for (std::size_t k = 1; k < file.vehicles.size(); ++k)
  {
    OpenAccVehicle& car = file.vehicles[k];
    for (std::size_t j = 0; j < k && car.copied_column.empty(); ++j)
    {
      const OpenAccVehicle& original = file.vehicles[j];
      if (!original.copied_column.empty() || !sameColumn(car.speed_mps, original.speed_mps))
        continue;
      car.copied_column = "its speeds equal " + original.label() +
                          "'s on every row where both hold one, to the last digit, while they vary: one of the "
                          "two columns is a copy, not a car's own measurement; the later one is not read";
      // Set aside as a car without speeds, so that no reader (pairs, platoon check, SUMO chain)
      // takes it for a measurement.
      car.speed_mps.assign(car.speed_mps.size(), std::numeric_limits<double>::quiet_NaN());
      car.has_speed = false;
      car.speed_values = 0;
    }
  }
}

/// Why each car with data is not the follower of a pair.
void notePairlessFollowers(OpenAccFile& file)
{
  for (int k = 2; k <= file.lastPosition(); ++k)
  {
    if (file.vehicle(k) != nullptr)
    {
      const std::string why = describePairlessFollower(file, k);
      if (!why.empty())
      {
        file.notes.push_back(file.path + ": " + why);
      }
    }
  }
}

/// The counts behind the listed problems, in one note.
void noteBadCellsAndRows(OpenAccFile& file)
{
  const std::size_t rows = file.line.size();
  if (!file.bad_cells.empty())
  {
    std::vector<std::string> by_column;
    for (const auto& [column, count] : file.bad_cells_by_column)
    {
      by_column.push_back(column + " " + std::to_string(count));
    }
    file.notes.push_back(file.path + ": " + std::to_string(file.bad_cells.size()) +
                         " cells without a usable number in " + std::to_string(file.bad_rows) + " of " +
                         std::to_string(rows) + " rows (" + join(by_column, ", ") +
                         "); their values are NaN: a pair with one in its own columns rejects that row, listed "
                         "where the pair is read, and other cars' cells do not matter to it");
  }
  else if (file.bad_rows > 0)
  {
    file.notes.push_back(file.path + ": " + std::to_string(file.bad_rows) + " of " + std::to_string(rows) +
                         " rows not read, each listed");
  }
  if (!file.duplicate_lines.empty())
  {
    file.notes.push_back(describeDuplicateRows(file));
  }
}
}  // namespace

bool isAccDriverCell(const std::string& cell) { return upperCase(cell) == "ACC"; }

bool accLineSaysOnThroughout(const OpenAccMetadata& metadata) { return metadata.acc != 0 && metadata.acc != 2; }

bool isOnAccAt(const OpenAccFile& file, const OpenAccVehicle& car, std::size_t row)
{
  return car.has_driver ? isAccDriverCell(car.driver[row]) : accLineSaysOnThroughout(file.metadata);
}

std::string describeDuplicateRows(const OpenAccFile& file)
{
  constexpr std::size_t kLinesNamed = 10;
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < file.duplicate_lines.size() && i < kLinesNamed; ++i)
    lines.push_back(std::to_string(file.duplicate_lines[i]));
  const std::size_t n = file.duplicate_lines.size();
  return file.path + ": " + std::to_string(n) + " row" + (n == 1 ? "" : "s") +
         " with the same cells as the row before, dropped as duplicates (line" + (n == 1 ? " " : "s ") +
         join(lines, ", ") + (n > kLinesNamed ? ", ..." : "") + ")";
}

const char* angleUnitName(OpenAccAngleUnit unit)
{
  return unit == OpenAccAngleUnit::kDegrees ? "degrees" : "radians";
}

std::string OpenAccVehicle::label() const
{
  return name + " (" + std::to_string(position) + ")";
}

std::string OpenAccBadCell::describe() const
{
  if (!why.empty())
  {
    return column + " " + text + ": " + why;
  }
  if (text.empty())
  {
    return column + " empty";
  }
  double value = 0.0;
  if (parseCell(text, value) == CellKind::kNotFinite)
  {
    return column + " " + text;
  }
  return column + " not a number: '" + text + "'";
}

const OpenAccVehicle* OpenAccFile::vehicle(int position) const
{
  for (const OpenAccVehicle& candidate : vehicles)
  {
    if (candidate.position == position)
    {
      return &candidate;
    }
  }
  return nullptr;
}

int OpenAccFile::lastPosition() const
{
  int highest = static_cast<int>(metadata.vehicle_order.size());
  for (const std::string& name : header)
  {
    const auto column = classifyColumn(name);
    if (column)
    {
      highest = std::max(highest, column->second + (column->first == Quantity::kGap ? 1 : 0));
    }
  }
  return highest;
}

std::string OpenAccFile::vehicleName(int position) const
{
  const std::size_t index = static_cast<std::size_t>(position - 1);
  if (position >= 1 && index < metadata.vehicle_order.size() && !metadata.vehicle_order[index].empty())
  {
    return metadata.vehicle_order[index];
  }
  return "vehicle " + std::to_string(position);
}

std::string OpenAccFile::cellProblem(std::size_t row, const std::string& column) const
{
  auto at = std::lower_bound(bad_cells.begin(), bad_cells.end(), row,
                             [](const OpenAccBadCell& cell, std::size_t r) { return cell.row < r; });
  for (; at != bad_cells.end() && at->row == row; ++at)
  {
    if (at->column == column)
    {
      return at->describe();
    }
  }
  return "";
}

std::string OpenAccFile::rowProblem(std::size_t row, const std::vector<std::string>& columns) const
{
  if (!row_problems[row].empty())
  {
    return row_problems[row];
  }
  std::string problems;
  for (const std::string& column : columns)
  {
    const std::string problem = cellProblem(row, column);
    if (!problem.empty())
    {
      problems += (problems.empty() ? "" : ", ") + problem;
    }
  }
  return problems;
}

bool looksLikeOpenAccFile(const std::string& path)
{
  const std::vector<std::string> fields = firstLineFields(path);
  return !fields.empty() && (upperCase(fields[0]) == "DATE" || isHeaderWithoutMetadata(fields));
}

OpenAccFile readOpenAccFile(const std::string& path)
{
  OpenAccFile file;
  file.path = path;
  file.name = std::filesystem::path(path).stem().string();
  std::ifstream in(path);
  if (!in)
  {
    file.error = "cannot open OpenACC file '" + path + "'";
    return file;
  }
  std::size_t line_number = 0;
  std::map<std::string, std::size_t> index;  // columns by name, any order; each named once
  if (!readMetadataAndHeader(in, file, line_number) || !indexColumns(file, line_number, index))
  {
    file.error += textLayoutHint(path);  // a CR-only or UTF-16 export fails here: said what it is
    return file;
  }
  HeaderLayout layout = classifyHeader(file);
  if (!layout.time_field)
  {
    file.error = file.path + ": no Time column";
    return file;
  }
  attachGapColumns(file, layout);
  const std::size_t header_line = line_number;
  readDataRows(in, file, columnTargets(file, layout, index), line_number);
  if (file.rows() == 0)
  {
    file.error = file.path + ": no data rows after the header (line " + std::to_string(header_line) + ")";
    return file;
  }
  keepCarsWithData(file, layout.cars);
  noteAccLineAgainstDriverColumns(file);
  markCopiedColumns(file);
  notePairlessFollowers(file);
  detectAngleUnit(file);
  setAsideImpossibleAngles(file);
  noteBadCellsAndRows(file);
  // The unit matters to every position read from the file: said with the other notes.
  file.notes.push_back(file.path + ": " + file.angle_unit_reason);
  return file;
}

}  // namespace acc
