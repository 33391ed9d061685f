#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace acc
{
/// The one reader of OpenACC files (JRC OpenACC database, Makridis et al., Transportation Research
/// Part C 125 (2021) 103047; (c) European Union, CC BY 4.0), whatever the campaign's layout:
/// two-vehicle runs (Casale: Time, Speed1, Lat1, Lon1, E1, N1, Speed2, Lat2, Lon2, Alt2, E2, N2, U2,
/// IVS1, Driver2) and platoons (ZalaZone: Time, per vehicle k Speedk, Ek, Nk, Lonk, Latk, Altk, then
/// IVS1..IVS(n-1)). A file starts with metadata lines (Date,DD,MM,YYYY; Vehicle_order,NAME1,...;
/// Number_of_vehicles,N; ACC,0|1|2; Distance_setting,S|M|L|min|max|SL), then the header line;
/// or, as the AstaZero layout (Time, Speed1, E1, N1, Speed2, E2, N2, IVS1, A1, A2), with the header
/// itself: then the cars are counted from the columns and named by position ("vehicle 2"), the
/// date, ACC and setting are unknown, and a note says so. Columns are found by name in any order;
/// the number k of a column is the car's position in Vehicle_order (1 = the platoon's leader);
/// columns of no known kind (AstaZero's accelerations Ak) are listed in a note as not used. The run reader (run_csv.h) and the NMEA converter
/// (conversion/openacc_to_nmea.h) are views on this one.

/// The file's metadata lines.
struct OpenAccMetadata
{
  int year = 0, month = 0, day = 0;         ///< the Date line (a real day, checked)
  std::vector<std::string> vehicle_order;   ///< every car of the test, leader first (trailing comma dropped)
  int number_of_vehicles = -1;              ///< the Number_of_vehicles line; -1 when absent or not a number
  int acc = -1;                             ///< the ACC line: 0 manual, 1 ACC throughout, 2 mixed; -1 when absent
  std::string distance_setting;             ///< the Distance_setting line (S, M, L, min, max, SL...); "" when absent
  /// False when the file starts with its header (no metadata line at all: the AstaZero layout);
  /// then the file's first note says so.
  bool lines_present = true;
};

/// The unit the file's Lat/Lon cells were found to be in (see OpenAccFile::angle_unit_reason).
enum class OpenAccAngleUnit
{
  kRadians,
  kDegrees
};

/// "radians" or "degrees".
const char* angleUnitName(OpenAccAngleUnit unit);

/// One car whose columns are in the file, one value per data row. NaN wherever the cell is empty,
/// NaN or not a number (each such cell is in OpenAccFile::bad_cells), and in every row when the
/// column is absent (its has_ flag is false).
struct OpenAccVehicle
{
  int position = 0;  ///< 1-based position in Vehicle_order, the k of its columns
  std::string name;  ///< its Vehicle_order name, or "vehicle k" when Vehicle_order is shorter
  std::vector<double> speed_mps;      ///< Speedk (Doppler)
  std::vector<double> east_m;         ///< Ek, local ENU plane of the file
  std::vector<double> north_m;        ///< Nk
  std::vector<double> up_m;           ///< Uk (Casale's follower)
  std::vector<double> altitude_m;     ///< Altk
  std::vector<double> latitude_deg;   ///< Latk in DEGREES, whatever unit the file holds (see angle_unit)
  std::vector<double> longitude_deg;  ///< Lonk in degrees
  std::vector<std::string> driver;    ///< Driverk cells as written ("ACC", "Human"); empty without the column
  std::vector<double> gap_to_follower_m;  ///< IVSk: bumper-to-bumper gap to the car at position k+1
  bool has_speed = false, has_east_north = false, has_up = false, has_altitude = false, has_lat_lon = false,
       has_driver = false, has_gap_to_follower = false;
  std::size_t speed_values = 0;  ///< finite Speedk cells
  std::size_t gap_values = 0;    ///< finite IVSk cells
  /// Non-empty when its speeds are an earlier car's column written again (equal to the last bit on
  /// every row where both hold one, while they vary): a copied column, not a measurement of a car
  /// of its own. It is then neither follower nor leader of a pair, and holds no speeds (NaN,
  /// has_speed false, speed_values 0), so that no reader takes it for a measurement. Says whose:
  /// "its speeds equal MAZDA_3 (10)'s on every row ...".
  std::string copied_column;

  /// "BMW_I3 (3)".
  std::string label() const;
};

/// One cell that holds no number: empty, NaN (or inf), or text that is not a number. Its value is NaN.
struct OpenAccBadCell
{
  std::size_t row = 0;   ///< index into the data rows
  std::size_t line = 0;  ///< 1-based line in the file
  std::string column;    ///< "IVS1"
  std::string text;      ///< as written ("" when empty)
  /// Why a number is unusable ("not a latitude in radians, the file's unit"); "" for a cell
  /// without a number.
  std::string why;
  /// "IVS1 empty", "Speed5 NaN", "Alt2 not a number: 'n/a'", "Lat1 7: not a latitude in ...".
  std::string describe() const;
};

/// Everything read from one OpenACC file. Nothing is dropped silently: every data row is kept (a
/// malformed row with all its values NaN) but an exact repeat of the row before, and every bad
/// cell, row and repeat is counted and listed.
struct OpenAccFile
{
  std::string path;
  std::string name;  ///< the file's name without folder and extension: "dynamic_part12"
  OpenAccMetadata metadata;
  std::vector<std::string> header;
  std::vector<std::size_t> line;  ///< 1-based file line of each data row
  std::vector<double> time_s;     ///< the Time column (seconds; Casale: since UTC midnight); NaN where bad
  std::vector<OpenAccVehicle> vehicles;  ///< the cars with data in the file, by position
  /// The unit the Lat/Lon cells are in (the database's notes say radians; ZalaZone files hold
  /// degrees), detected per file, and why: values beyond +-pi/2 (Lat) or +-pi (Lon) cannot be
  /// radians; otherwise the unit in which consecutive fixes move as far as the E/N columns say.
  OpenAccAngleUnit angle_unit = OpenAccAngleUnit::kRadians;
  std::string angle_unit_reason;
  std::vector<std::string> row_problems;  ///< per row: why the whole row is unread ("" when it is read)
  std::vector<OpenAccBadCell> bad_cells;  ///< in row order
  std::map<std::string, std::size_t> bad_cells_by_column;
  std::size_t bad_rows = 0;  ///< rows with a bad cell or unread as a whole
  /// Lines that repeat the data row before cell for cell (an export's duplicate): dropped, not
  /// rows, each listed in problems and counted in a note.
  std::vector<std::size_t> duplicate_lines;
  /// "path:line: why", one per row with a bad cell (naming every one) or unread as a whole.
  std::vector<std::string> problems;
  /// "path: ...": what the file holds and what was made of it (the unit and why, the cars without
  /// data, the followers without a pair and why, metadata that disagree, columns not used).
  std::vector<std::string> notes;
  /// Those of the notes that say the file's description of itself is missing, not understood or
  /// contradicted by its columns (a metadata line absent or not a number, a line before the header
  /// not understood, Number_of_vehicles or Vehicle_order against the columns, the ACC line against
  /// the followers' Driver columns): what a reader of many files (the campaign) passes on.
  std::vector<std::string> metadata_problems;
  /// Non-empty when the file cannot be read at all (missing, no Date or Vehicle_order line, no
  /// header with a Time column, a column named twice); the fields above then hold what was read.
  std::string error;

  std::size_t rows() const { return time_s.size(); }
  /// The car at this position, or nullptr when it has no data in the file.
  const OpenAccVehicle* vehicle(int position) const;
  /// The last position the file names: by Vehicle_order, or by a column (IVSk names car k+1),
  /// whether or not that car has data.
  int lastPosition() const;
  /// The car's Vehicle_order name ("vehicle k" beyond it), whether or not it has data.
  std::string vehicleName(int position) const;
  /// Why the cell of this column in this row is bad ("IVS1 empty"), or "" when it holds a number
  /// (or the row is unread as a whole: see row_problems).
  std::string cellProblem(std::size_t row, const std::string& column) const;
  /// Why this row cannot give the values of these columns: the row's own problem when it is unread
  /// as a whole, else every bad cell among them ("IVS1 empty, Speed2 NaN"); "" when all are
  /// numbers. Cells of other columns do not matter (a reader asks for the pair it reads).
  std::string rowProblem(std::size_t row, const std::vector<std::string>& columns) const;
};

/// A Driverk cell that says ACC, in any case ("ACC", "acc"); the database writes ACC or Human.
bool isAccDriverCell(const std::string& cell);

/// What the file's ACC line says of a car without a Driver column: on ACC throughout (1, or the
/// line absent), or no row known to be on ACC (0 manual, 2 mixed).
bool accLineSaysOnThroughout(const OpenAccMetadata& metadata);

/// Whether the car is known to be on ACC at this row: its Driver cell says ACC; without a Driver
/// column, the file's ACC line is 1 or absent. The one rule the run readers and the platoon check
/// follow.
bool isOnAccAt(const OpenAccFile& file, const OpenAccVehicle& car, std::size_t row);

/// "path: 3 rows with the same cells as the row before, dropped as duplicates (lines 12, 40, 41)".
std::string describeDuplicateRows(const OpenAccFile& file);

/// Reads an OpenACC file; never throws for the file's content (see OpenAccFile::error).
OpenAccFile readOpenAccFile(const std::string& path);

/// Whether the file looks like an OpenACC file: its first line is a Date line, or a header with a
/// Time and a Speedk column (the layout without metadata). A canonical run CSV starts with its
/// header of time_s, ... and is not one.
bool looksLikeOpenAccFile(const std::string& path);

/// A leader-follower pair: the follower and the car DIRECTLY ahead of it in Vehicle_order.
struct OpenAccPair
{
  int leader_position = 0, follower_position = 0;
  std::string leader_name, follower_name;
  /// "BMW_I3 behind SMART_TARGET, positions 3/2".
  std::string label() const;
};

/// The pairs the file holds: the follower at position k and the car at k-1 both with Speed data,
/// and their gap IVS(k-1) with data. The leader is always the car directly ahead: when it has no
/// data, the follower has no pair (never the car further ahead; describePairlessFollower says so).
std::vector<OpenAccPair> availablePairs(const OpenAccFile& file);

/// Why the car at this position is not the follower of an available pair ("" when it is).
std::string describePairlessFollower(const OpenAccFile& file, int follower_position);

/// The available pairs as a list for messages: "MERCEDES_GLE450 behind SMART_TARGET, positions 2/1; ..."
/// or "none".
std::string describeAvailablePairs(const OpenAccFile& file);

/// Which pair(s) of a file to read.
struct OpenAccPairSelector
{
  enum class Kind
  {
    kFirst,     ///< the first available pair (said in a note, never silently)
    kFollower,  ///< the pair of one follower, by name (case-insensitive) or position ("3")
    kAll        ///< every available pair
  };
  Kind kind = Kind::kFirst;
  std::string follower;  ///< for kFollower

  static OpenAccPairSelector first() { return {}; }
  static OpenAccPairSelector all() { return {Kind::kAll, ""}; }
  static OpenAccPairSelector byFollower(const std::string& name_or_position) { return {Kind::kFollower, name_or_position}; }
  /// "" -> first, "all" (any case) -> all, anything else -> that follower.
  static OpenAccPairSelector parse(const std::string& text);
  /// "the first available pair", "all pairs", "follower 'BMW_I3'".
  std::string describe() const;
};

/// The pairs a selector picks in a file.
struct OpenAccPairChoice
{
  std::vector<OpenAccPair> pairs;  ///< empty when error is set
  /// Why the choice is not available, with the list of the pairs that are:
  /// "path: no pair with follower 'TESLA_MODELX' (position 5): ...; pairs in this file: ...".
  std::string error;
  /// "path: pair read: ... (the first available pair; no follower chosen; others: ...)".
  std::string note;
};

OpenAccPairChoice selectOpenAccPairs(const OpenAccFile& file, const OpenAccPairSelector& selector);

}  // namespace acc
