#include "acc_identification/io/run_csv.h"
#include "acc_identification/io/csv_fields.h"
#include "acc_identification/io/gap_kinematics.h"
#include "acc_identification/io/problem_lines.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/plain_text.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
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
/// Column indices of the four canonical quantities in the file's header.
struct ColumnMap
{
  std::array<std::size_t, 4> index{};  ///< time, gap, follower speed, leader speed
  std::size_t field_count = 0;
  std::optional<std::size_t> valid;           ///< the optional valid column (nmea_to_csv writes it)
  std::optional<std::size_t> invalid_reason;  ///< and why a row is not
};

/// The canonical columns, in ColumnMap::index's order (time, gap, follower, leader).
const std::array<const char*, 4> kCanonicalColumns{"time_s", "space_gap_m", "follower_speed_mps", "leader_speed_mps"};

/// Whether a header cell names `name` in any case ("Time_s" is time_s: the unit is in the name,
/// and a spreadsheet may capitalise it; OpenACC's columns are read in any case too).
bool namesColumn(const std::string& cell, const std::string& name)
{
  return upperCase(cell) == upperCase(name);
}

std::optional<std::size_t> findColumn(const std::vector<std::string>& header, const std::string& name)
{
  for (std::size_t i = 0; i < header.size(); ++i)
  {
    if (namesColumn(header[i], name))
    {
      return i;
    }
  }
  return std::nullopt;
}

/// The header cells of the canonical columns spelt in another case, as a note ("" when none is).
std::string describeColumnSpellings(const std::string& path, const std::vector<std::string>& header,
                                    const ColumnMap& map)
{
  std::vector<std::string> read_as;
  for (std::size_t q = 0; q < kCanonicalColumns.size(); ++q)
    if (header[map.index[q]] != kCanonicalColumns[q])
      read_as.push_back("'" + header[map.index[q]] + "' as " + kCanonicalColumns[q]);
  return read_as.empty() ? "" : path + ": columns read in another case: " + join(read_as, ", ");
}

/// For the reader's error: what the file's first line holds, so a header that names the columns
/// almost right is seen ("" for an empty file).
std::string firstLineHint(const std::string& path)
{
  const std::vector<std::string> fields = firstLineFields(path);
  if (fields.empty())
    return "";
  return " (its first line reads '" + shortened(join(fields, ",")) + "')";
}

/// Why the file is not comma-separated text when its bytes say, else what its first line holds.
std::string layoutOrFirstLineHint(const std::string& path)
{
  const std::string layout = textLayoutHint(path);
  return layout.empty() ? firstLineHint(path) : layout;
}

/// The header names of the canonical format (time, gap, follower, leader); OpenACC files are
/// told by their Date line and read by readOpenAccFile.
std::optional<ColumnMap> mapColumns(const std::vector<std::string>& header)
{
  ColumnMap map;
  for (std::size_t q = 0; q < kCanonicalColumns.size(); ++q)
  {
    const auto found = findColumn(header, kCanonicalColumns[q]);
    if (!found)
    {
      return std::nullopt;
    }
    map.index[q] = *found;
  }
  map.field_count = header.size();
  map.valid = findColumn(header, "valid");
  map.invalid_reason = findColumn(header, "invalid_reason");
  return map;
}

/// The first name the header gives two columns (in any case): such a column would be read from its
/// first place alone, the other silently not.
std::optional<std::string> columnNamedTwice(const std::vector<std::string>& header)
{
  for (auto name = header.begin(); name != header.end(); ++name)
    if (!name->empty() &&
        std::find_if(header.begin(), name, [&](const std::string& before) { return namesColumn(before, *name); }) != name)
      return *name;
  return std::nullopt;
}

std::optional<double> parseNumber(const std::string& text)
{
  double value = 0.0;
  if (parseCell(text, value) != CellKind::kNumber)
  {
    return std::nullopt;
  }
  return value;
}


/// Accumulates rows into runs, closing the current run at every split point, and accounts for
/// every row it rejects and every hole it splits at in contents.
class RunAssembler
{
public:
  /// Runs are named name, name#2, ...; every problem is "path:line: " + about + why.
  RunAssembler(std::string path, std::string name, std::string about, const RunPlausibilityBounds& bounds,
               RunFileContents& contents)
    : path_(std::move(path)), name_(std::move(name)), about_(std::move(about)), bounds_(bounds), contents_(contents)
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
      contents_.too_fast_rows += values[2] > bounds_.max_speed_mps || values[3] > bounds_.max_speed_mps ? 1 : 0;
      contents_.negative_rows += values[1] < bounds_.min_space_gap_m || values[2] < bounds_.min_speed_mps ||
                                         values[3] < bounds_.min_speed_mps
                                     ? 1
                                     : 0;
      reject(line_number, implausible);
      return;
    }
    if (!current_.time_s.empty())
    {
      if (repeatsLastSample(values))
      {
        ++contents_.rejected_rows;
        ++contents_.duplicate_rows;
        report(line_number, "the same time and values as the row before; duplicate row rejected, run not split");
        return;
      }
      const std::string not_increasing = describeTimeNotIncreasing(values[0]);
      if (!not_increasing.empty())
      {
        ++contents_.time_back_rows;
        reject(line_number, not_increasing);
        return;
      }
      ++contents_.time_steps;
      contents_.shortest_step_s = std::min(contents_.shortest_step_s, values[0] - current_.time_s.back());
      const std::string hole = describeTimeHole(current_.time_s.back(), values[0], bounds_);
      if (!hole.empty())
      {
        ++contents_.time_holes;
        split();
        report(line_number, hole + "; run split");
      }
    }
    current_.time_s.push_back(values[0]);
    current_.space_gap_m.push_back(values[1]);
    current_.follower_speed_mps.push_back(values[2]);
    current_.leader_speed_mps.push_back(values[3]);
    current_lines_.push_back(line_number);
  }

  /// Counts and lists a row that is not used, and splits the run there. The run closes first, so
  /// that what its closing lists (a rebuilt stretch, a lone sample) comes before this row and the
  /// problems stay in line order, where consecutive rejected rows condense into one range.
  void reject(std::size_t line_number, const std::string& why)
  {
    ++contents_.rejected_rows;
    split();
    report(line_number, why + "; row rejected, run split here");
  }

  /// Closes the current run (a run when it holds two samples or more), its gap rebuilt where it
  /// saw-tooths (each stretch counted and listed).
  void split()
  {
    if (current_.size() >= 2)
    {
      ++pieces_;
      current_.name = pieces_ == 1 ? name_ : name_ + "#" + std::to_string(pieces_);
      for (const GapSawtoothSpan& span : checkGapSawtooth({current_}).spans)
        rebuildGap(span);
      contents_.runs.push_back(std::move(current_));
    }
    else if (current_.size() == 1)
    {
      ++contents_.single_sample_rows;
      std::ostringstream why;
      why << "a piece of one sample (t = " << current_.time_s[0]
          << " s) between split points is too short to simulate; not used";
      report(current_lines_.front(), why.str());
    }
    current_ = CarFollowingRun{};
    current_lines_.clear();
  }

private:
  void rebuildGap(const GapSawtoothSpan& span)
  {
    rebuildSawtoothGap(span, &current_);
    contents_.sawtooth_rows += span.end_sample - span.first_sample;
    contents_.sawtooth_spans.push_back(span);
    const std::size_t first_line = current_lines_[span.first_sample];
    report(first_line, describeSawtoothSpan(span) + "; lines " + std::to_string(first_line) + "-" +
                           std::to_string(current_lines_[span.end_sample - 1]) + ": " + describeGapRebuilt(span));
  }

  bool repeatsLastSample(const std::array<double, 4>& values) const
  {
    return values[0] == current_.time_s.back() && values[1] == current_.space_gap_m.back() &&
           values[2] == current_.follower_speed_mps.back() && values[3] == current_.leader_speed_mps.back();
  }

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
    contents_.problems.push_back(path_ + ":" + std::to_string(line_number) + ": " + about_ + why);
  }

  std::string path_;
  std::string name_;
  std::string about_;
  RunPlausibilityBounds bounds_;
  RunFileContents& contents_;
  CarFollowingRun current_;
  std::vector<std::size_t> current_lines_;  ///< the file line of each of current_'s samples
  std::size_t pieces_ = 0;
};

/// The valid column's flag: "0" or "1" for a number equal to either, otherwise its text in lower
/// case ("" without the column or with a wrong field count).
std::string validFlag(const std::vector<std::string>& fields, const ColumnMap& map)
{
  if (!map.valid || fields.size() != map.field_count)
  {
    return "";
  }
  std::string flag = fields[*map.valid];
  double number = 0.0;
  if (parseCell(flag, number) == CellKind::kNumber && (number == 0.0 || number == 1.0))
  {
    return number == 1.0 ? "1" : "0";  // "1.0", as pandas writes a flag column that has a gap
  }
  std::transform(flag.begin(), flag.end(), flag.begin(), [](unsigned char c) { return std::tolower(c); });
  return flag;
}

/// Why a row whose valid column says 0 (or false) is not used: the reason the file gives; nullopt
/// for every other row (valid, no valid column, or a flag parseRow calls malformed).
std::optional<std::string> markedInvalid(const std::vector<std::string>& fields, const ColumnMap& map)
{
  const std::string flag = validFlag(fields, map);
  if (flag != "0" && flag != "false")
  {
    return std::nullopt;
  }
  const std::string reason = map.invalid_reason ? fields[*map.invalid_reason] : "";
  return "marked invalid" + (reason.empty() ? std::string() : ": " + reason);
}

const std::array<const char*, 4> kQuantity{"time", "space gap", "follower speed", "leader speed"};

/// Why a row's values are not all finite numbers ("" when they are), naming the first as parseRow does.
std::string describeNotFinite(const std::array<double, 4>& values)
{
  for (std::size_t q = 0; q < 4; ++q)
  {
    if (!std::isfinite(values[q]))
    {
      std::ostringstream why;
      why << kQuantity[q] << " is not a finite number: '" << values[q] << "'";
      return why.str();
    }
  }
  return "";
}

/// Parses one data row into the four canonical values, or returns why not.
std::string parseRow(const std::vector<std::string>& fields, const ColumnMap& map,
                     std::array<double, 4>& values)
{
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
  const std::string flag = validFlag(fields, map);
  if (map.valid && flag != "1" && flag != "true")
  {
    return "valid is neither 0 nor 1 (nor false or true): '" + fields[*map.valid] + "'";
  }
  return "";
}
}  // namespace

namespace
{
void checkBounds(const RunPlausibilityBounds& bounds)
{
  const std::string bounds_problem = describeBoundsProblem(bounds);
  if (!bounds_problem.empty())
  {
    throw std::invalid_argument("readRunFile: unusable plausibility bounds: " + bounds_problem);
  }
}

RunFileContents readCanonicalFile(const std::string& path, const RunPlausibilityBounds& bounds)
{
  std::ifstream file(path);
  if (!file)
  {
    throw RunReadError("cannot open run file '" + path + "'");
  }
  RunFileContents contents;
  std::string line;
  std::size_t line_number = 0;
  std::optional<ColumnMap> map;
  std::vector<std::string> header;
  // The header is the first line that names the four columns.
  while (!map && std::getline(file, line))
  {
    ++line_number;
    header = splitCsvFields(line_number == 1 ? withoutByteOrderMark(line) : line);
    map = mapColumns(header);
    if (line_number > 20 && !map)
    {
      break;
    }
  }
  if (!map)
  {
    throw RunReadError(path + ": no header with time_s,space_gap_m,follower_speed_mps,leader_speed_mps in the "
                              "first 20 lines, and no OpenACC Date line or Time,Speed1,... header first" +
                       layoutOrFirstLineHint(path));
  }
  if (const std::string spellings = describeColumnSpellings(path, header, *map); !spellings.empty())
    contents.notes.push_back(spellings);
  if (const std::optional<std::string> twice = columnNamedTwice(header))
  {
    throw RunReadError(path + ":" + std::to_string(line_number) + ": the header names column '" + *twice +
                       "' twice: which one holds the data is not said");
  }
  RunAssembler assembler(path, std::filesystem::path(path).stem().string(), "", bounds, contents);
  while (std::getline(file, line))
  {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos)
    {
      continue;  // a blank line (usually the last) carries no sample
    }
    ++contents.data_rows;
    std::array<double, 4> values{};
    const std::vector<std::string> fields = splitCsvFields(line);
    // A row the file marks invalid is a split point whatever its values (they may be NaN).
    const std::optional<std::string> invalid = markedInvalid(fields, *map);
    const std::string malformed = invalid ? *invalid : parseRow(fields, *map, values);
    contents.marked_invalid_rows += invalid ? 1 : 0;
    if (!malformed.empty())
    {
      assembler.reject(line_number, malformed);
    }
    else
    {
      assembler.add(line_number, values);
    }
  }
  assembler.split();
  return contents;
}

/// How the follower's rows are known to be on ACC: its Driverk column, else the file's ACC line.
enum class AccSource
{
  kDriverColumn,
  kOnThroughout,  ///< ACC line 1 or absent
  kNeverKnown     ///< ACC line 0 (manual) or 2 (mixed) without a Driverk column
};

AccSource accSource(const OpenAccFile& file, const OpenAccVehicle& follower)
{
  if (follower.has_driver)
  {
    return AccSource::kDriverColumn;
  }
  return accLineSaysOnThroughout(file.metadata) ? AccSource::kOnThroughout : AccSource::kNeverKnown;
}

std::string describeAccSource(const OpenAccFile& file, const OpenAccPair& pair, AccSource source)
{
  const std::string follower = pair.follower_name + " (" + std::to_string(pair.follower_position) + ")";
  const std::string driver = "Driver" + std::to_string(pair.follower_position);
  switch (source)
  {
    case AccSource::kDriverColumn:
      return file.path + ": " + follower + ": ACC on where " + driver + " is ACC (any case); other rows split the run" +
             (file.metadata.acc == 0 ? " (the ACC line says 0, manual driving throughout: the " + driver +
                                           " column, row by row, is followed)"
                                     : "");
    case AccSource::kOnThroughout:
      return file.path + ": " + follower + ": no " + driver + " column; ACC on throughout, as the ACC line says (" +
             (file.metadata.acc == 1 ? std::string("1") : std::string("absent: assumed")) + ")";
    case AccSource::kNeverKnown:
      break;
  }
  return file.path + ": " + follower + ": no " + driver + " column and the ACC line is " +
         std::to_string(file.metadata.acc) + (file.metadata.acc == 0 ? " (manual driving)" : " (ACC and manual mixed)") +
         ": no row is known to be on ACC, none used";
}

/// Why row i of the file cannot give a sample of the pair: the row unread, or a bad cell of the
/// pair's own columns (other cars' cells do not matter). "" when the four values are numbers.
std::string pairRowProblem(const OpenAccFile& file, const OpenAccPair& pair, std::size_t i)
{
  return file.rowProblem(i, {"Time", "IVS" + std::to_string(pair.leader_position),
                             "Speed" + std::to_string(pair.follower_position),
                             "Speed" + std::to_string(pair.leader_position)});
}

/// The stretches of rows where the follower's ACC was off, as a note that names their lines and
/// times (the first few): rows not used are said, not dropped silently.
class AccOffStretches
{
public:
  void add(std::size_t line, double time_s, bool acc_off)
  {
    if (!acc_off)
    {
      open_ = false;
      return;
    }
    if (!open_)
      stretches_.push_back({line, line, time_s, time_s});
    stretches_.back().last_line = line;
    stretches_.back().last_time_s = time_s;
    open_ = true;
  }
  std::string note(std::size_t rows, const std::string& path, const std::string& about) const
  {
    constexpr std::size_t kNamed = 5;
    std::string text = path + ": " + about + std::to_string(rows) +
                       " rows with the follower's ACC off (driven by hand) not used, each stretch splitting a run: ";
    for (std::size_t i = 0; i < stretches_.size() && i < kNamed; ++i)
    {
      const Stretch& s = stretches_[i];
      text += (i > 0 ? ", " : "") + printfText("lines %zu-%zu (t = %.1f to %.1f s)", s.first_line, s.last_line,
                                              s.first_time_s, s.last_time_s);
    }
    if (stretches_.size() > kNamed)
      text += " and " + std::to_string(stretches_.size() - kNamed) + " more stretches";
    return text;
  }

private:
  struct Stretch
  {
    std::size_t first_line, last_line;
    double first_time_s, last_time_s;
  };
  std::vector<Stretch> stretches_;
  bool open_ = false;
};

/// One pair's runs: the four values of each row, through the same checks as a canonical CSV.
RunFileContents readPairRuns(const OpenAccFile& file, const OpenAccPair& pair, const RunPlausibilityBounds& bounds,
                             bool name_pair_in_problems)
{
  RunFileContents contents;
  contents.pairs.push_back(pair);
  const OpenAccVehicle& leader = *file.vehicle(pair.leader_position);
  const OpenAccVehicle& follower = *file.vehicle(pair.follower_position);
  const AccSource source = accSource(file, follower);
  contents.notes.push_back(describeAccSource(file, pair, source));
  const std::string about = name_pair_in_problems ? pair.follower_name + " behind " + pair.leader_name + ": " : "";
  RunAssembler assembler(file.path, file.name + " " + pair.follower_name, about, bounds, contents);
  AccOffStretches acc_off;
  for (std::size_t i = 0; i < file.rows(); ++i)
  {
    ++contents.data_rows;
    const std::string problem = pairRowProblem(file, pair, i);
    const bool acc_on = isOnAccAt(file, follower, i);
    acc_off.add(file.line[i], file.time_s[i], problem.empty() && !acc_on);
    if (!problem.empty())
    {
      assembler.reject(file.line[i], problem);
    }
    else if (!acc_on)
    {
      ++contents.acc_off_rows;
      assembler.split();
    }
    else
    {
      assembler.add(file.line[i], {file.time_s[i], leader.gap_to_follower_m[i], follower.speed_mps[i],
                                   leader.speed_mps[i]});
    }
  }
  assembler.split();
  // The file's exact repeats (dropped as it was read, listed in its notes) are this pair's rows
  // too: counted as a canonical CSV counts them, so the JSON's counts add up to the file's rows.
  contents.data_rows += file.duplicate_lines.size();
  contents.rejected_rows += file.duplicate_lines.size();
  contents.duplicate_rows += file.duplicate_lines.size();
  if (contents.acc_off_rows > 0)
    contents.notes.push_back(acc_off.note(contents.acc_off_rows, file.path, about));
  contents.run_pairs.assign(contents.runs.size(), 0);
  return contents;
}

OpenAccFile readOpenAccOrThrow(const std::string& path)
{
  OpenAccFile file = readOpenAccFile(path);
  if (!file.error.empty())
  {
    throw RunReadError(file.error);
  }
  return file;
}

std::vector<OpenAccPair> choosePairsOrThrow(const OpenAccFile& file, const OpenAccPairSelector& selector,
                                            std::vector<std::string>& notes)
{
  const OpenAccPairChoice choice = selectOpenAccPairs(file, selector);
  if (!choice.error.empty())
  {
    throw RunReadError(choice.error);
  }
  notes = file.notes;
  notes.push_back(choice.note);
  return choice.pairs;
}

/// Appends one pair's contents to the file's: runs, counts, problems and notes.
void append(RunFileContents& all, RunFileContents&& one)
{
  const std::size_t pair_index = all.pairs.size();
  all.pairs.push_back(one.pairs.front());
  for (CarFollowingRun& run : one.runs)
  {
    all.runs.push_back(std::move(run));
    all.run_pairs.push_back(pair_index);
  }
  all.data_rows += one.data_rows;
  all.rejected_rows += one.rejected_rows;
  all.implausible_rows += one.implausible_rows;
  all.marked_invalid_rows += one.marked_invalid_rows;
  all.duplicate_rows += one.duplicate_rows;
  all.time_back_rows += one.time_back_rows;
  all.time_holes += one.time_holes;
  all.time_steps += one.time_steps;
  all.shortest_step_s = std::min(all.shortest_step_s, one.shortest_step_s);
  all.acc_off_rows += one.acc_off_rows;
  all.single_sample_rows += one.single_sample_rows;
  all.too_fast_rows += one.too_fast_rows;
  all.negative_rows += one.negative_rows;
  all.sawtooth_rows += one.sawtooth_rows;
  all.sawtooth_spans.insert(all.sawtooth_spans.end(), one.sawtooth_spans.begin(), one.sawtooth_spans.end());
  all.problems.insert(all.problems.end(), one.problems.begin(), one.problems.end());
  all.notes.insert(all.notes.end(), one.notes.begin(), one.notes.end());
}

RunFileContents readOpenAccRuns(const std::string& path, const RunPlausibilityBounds& bounds,
                                const OpenAccPairSelector& selector)
{
  const OpenAccFile file = readOpenAccOrThrow(path);
  RunFileContents contents;
  const std::vector<OpenAccPair> pairs = choosePairsOrThrow(file, selector, contents.notes);
  for (const OpenAccPair& pair : pairs)
  {
    append(contents, readPairRuns(file, pair, bounds, pairs.size() > 1));
  }
  return contents;
}
}  // namespace

RunFileContents assembleRunColumns(const std::string& label, const std::string& name, const CarFollowingRun& columns,
                                   const std::vector<std::size_t>& rows, const RunPlausibilityBounds& bounds)
{
  checkBounds(bounds);
  const std::size_t count = columns.time_s.size();
  if (columns.space_gap_m.size() != count || columns.follower_speed_mps.size() != count ||
      columns.leader_speed_mps.size() != count || rows.size() != count)
  {
    throw std::invalid_argument(label + ": the columns of a run have different lengths");
  }
  RunFileContents contents;
  RunAssembler assembler(label, name, "", bounds, contents);
  for (std::size_t i = 0; i < count; ++i)
  {
    ++contents.data_rows;
    const std::array<double, 4> values{columns.time_s[i], columns.space_gap_m[i], columns.follower_speed_mps[i],
                                       columns.leader_speed_mps[i]};
    const std::string not_finite = describeNotFinite(values);
    if (!not_finite.empty())
      assembler.reject(rows[i], not_finite);
    else
      assembler.add(rows[i], values);
  }
  assembler.split();
  return contents;
}

RunFileContents readRunFile(const std::string& path, const RunPlausibilityBounds& bounds)
{
  return readRunFile(path, bounds, OpenAccPairSelector::first());
}

RunFileContents readRunFile(const std::string& path, const RunPlausibilityBounds& bounds,
                            const OpenAccPairSelector& selector)
{
  checkBounds(bounds);
  if (looksLikeOpenAccFile(path))
  {
    return readOpenAccRuns(path, bounds, selector);
  }
  if (selector.kind == OpenAccPairSelector::Kind::kFollower)
  {
    throw RunReadError(path + ": " + selector.describe() +
                       " chosen, but this is a canonical run CSV (no OpenACC Date line or Time,Speed1,... header first): it holds one pair");
  }
  return readCanonicalFile(path, bounds);
}

AllPairRuns readAllPairRuns(const std::string& path, const RunPlausibilityBounds& bounds)
{
  checkBounds(bounds);
  AllPairRuns all;
  if (!looksLikeOpenAccFile(path))
  {
    all.pairs.push_back({OpenAccPair{}, readCanonicalFile(path, bounds)});
    return all;
  }
  const OpenAccFile file = readOpenAccOrThrow(path);
  for (const OpenAccPair& pair : choosePairsOrThrow(file, OpenAccPairSelector::all(), all.notes))
  {
    RunFileContents contents = readPairRuns(file, pair, bounds, false);
    all.pairs.push_back({pair, std::move(contents)});
  }
  return all;
}

namespace
{
/// What most of a file's rejected rows likely come from, each "; ..." that applies: rows out of time
/// order, a coarse step or a time not in seconds, speeds in km/h, a sign error.
std::string describeLikelyCauses(const RunFileContents& contents)
{
  return describeTimeOrder(contents) + describeCoarseSteps(contents) + describeSpeedUnit(contents) +
         describeSign(contents);
}
}  // namespace

std::string describeRowCounts(const std::string& path, const RunFileContents& contents)
{
  if (contents.rejected_rows == 0 && contents.time_holes == 0 && contents.sawtooth_rows == 0 &&
      contents.single_sample_rows == 0)
  {
    return "";
  }
  std::ostringstream counts;
  counts << path << ": " << contents.rejected_rows << " of " << contents.data_rows << " rows rejected ("
         << contents.implausible_rows << " outside the plausibility bounds, " << contents.duplicate_rows
         << " duplicates), " << contents.time_holes << " holes in time split a run";
  if (contents.single_sample_rows > 0)
    counts << ", " << contents.single_sample_rows << " rows alone between split points not used";
  if (contents.sawtooth_rows > 0)
    counts << ", the gap of " << contents.sawtooth_rows << " rows rebuilt where it saw-tooths";
  counts << describeLikelyCauses(contents);
  return counts.str();
}

namespace
{
/// "; ROWS of its DATA_ROWS rows WHAT" when more than `share` of the rows are so (the likely cause
/// of a file's rejected rows), else "".
std::string describeRowsSo(std::size_t rows, std::size_t data_rows, double share, const std::string& what)
{
  if (static_cast<double>(rows) <= share * static_cast<double>(data_rows))
    return "";
  return "; " + std::to_string(rows) + " of its " + std::to_string(data_rows) + " rows " + what;
}
}  // namespace

std::string describeSign(const RunFileContents& contents)
{
  return describeRowsSo(contents.negative_rows, contents.data_rows, 0.5,
                        "have a speed or a gap below its bound: a sign error? (speeds are magnitudes, and the gap, "
                        "from the leader's rear bumper to the follower's front, is positive)");
}

std::string describeSpeedUnit(const RunFileContents& contents)
{
  return describeRowsSo(contents.too_fast_rows, contents.data_rows, 0.5,
                        "have a speed above the plausible bound (faster than any car under ACC): the speeds are likely "
                        "in km/h; convert them to m/s (divide by 3.6: the canonical follower_speed_mps, "
                        "leader_speed_mps)");
}

std::string describeTimeOrder(const RunFileContents& contents)
{
  return describeRowsSo(contents.time_back_rows, contents.data_rows, 0.1,
                        "go back in time from the row before: the rows are not in time order; sort them by time");
}

std::string describeCoarseSteps(const RunFileContents& contents)
{
  if (!describeTimeOrder(contents).empty())
    return "";  // the holes between shuffled rows are the shuffle's
  return describeCoarseSteps(contents.time_holes, contents.time_steps, contents.shortest_step_s);
}

std::string describeCoarseSteps(std::size_t time_holes, std::size_t time_steps, double shortest_step_s)
{
  if (time_steps == 0 || 2 * time_holes <= time_steps)
    return "";
  if (shortest_step_s >= kImplausibleShortestStepS && std::isfinite(shortest_step_s))
    return "; " + std::to_string(time_holes) + " of its " + std::to_string(time_steps) +
           " steps are such holes, and even the shortest step is " + significant(shortest_step_s, 6) +
           ": no car-following log steps that coarsely, so the time is not in seconds (milliseconds step by "
           "100 at 10 Hz); convert it to seconds (the canonical time_s, OpenACC's Time) rather than raising "
           "the largest step a run may hold";
  return "; " + std::to_string(time_holes) + " of its " + std::to_string(time_steps) +
         " steps are such holes: the data are recorded more coarsely than the largest step a run may hold "
         "(a receiver at 1 Hz against the default 0.5 s); set it above their step (the tools' --max-gap, "
         "Python's max_gap_s, the identifier's ~max_gap_s)";
}

std::vector<CarFollowingRun> readRuns(const std::string& path, const RunPlausibilityBounds& bounds)
{
  return readRuns(path, bounds, OpenAccPairSelector::first());
}

std::vector<CarFollowingRun> readRuns(const std::string& path, const RunPlausibilityBounds& bounds,
                                      const OpenAccPairSelector& selector)
{
  RunFileContents contents = readRunFile(path, bounds, selector);
  return reportAndTakeRuns(path, contents, std::cerr);
}

/// The problem lines listed of a file recorded more coarsely than a run may step, with most of its
/// speeds too fast or below a bound, or its rows out of time order (the rest counted, the cause said).
constexpr std::size_t kCoarseProblemLinesShown = 10;

namespace
{
/// With several OpenACC pairs read (--all-pairs), each pair's gap against its own speeds: one pair in
/// other units (a gap in feet) is diluted in the file's pooled check and would enter the fit.
void refusePairInOtherUnits(const std::string& path, const RunFileContents& contents)
{
  if (contents.pairs.size() < 2)
    return;
  for (std::size_t pair = 0; pair < contents.pairs.size(); ++pair)
  {
    std::vector<CarFollowingRun> runs;
    for (std::size_t i = 0; i < contents.runs.size() && i < contents.run_pairs.size(); ++i)
      if (contents.run_pairs[i] == pair)
        runs.push_back(contents.runs[i]);
    const GapKinematics kinematics = checkGapKinematics(runs);
    if (!kinematics.unit_error.empty())
      throw RunReadError(path + ": " + contents.pairs[pair].label() + ": " + kinematics.unit_error +
                         kUnitErrorRefusal);
  }
}
}  // namespace

std::vector<CarFollowingRun> reportAndTakeRuns(const std::string& path, RunFileContents& contents, std::ostream& log)
{
  for (const std::string& note : contents.notes)
  {
    log << "note: " << note << "\n";
  }
  const std::vector<std::string> problems = condenseProblemLines(contents.problems);
  // Recorded more coarsely than a run may step (a 1 Hz log at the default 0.5 s), every row is a
  // hole and a one-sample piece; with speeds in km/h, most rows are too fast: the first lines show
  // it, the count and the fix follow below, where 843 (and 1,140) lines once buried them.
  // The same for rows negated throughout (a sign error) or shuffled: the cause is said below.
  const bool coarse = !describeCoarseSteps(contents).empty();
  const bool too_fast = !describeSpeedUnit(contents).empty();
  const bool negative = !describeSign(contents).empty();
  const std::size_t shown = describeLikelyCauses(contents).empty()
                                ? problems.size()
                                : std::min(problems.size(), kCoarseProblemLinesShown);
  for (std::size_t i = 0; i < shown; ++i)
    log << "warning: " << problems[i] << "\n";
  if (shown < problems.size())
    log << "warning: " << path << ": " << problems.size() - shown << " more such lines not listed ("
        << (coarse      ? "each row a hole and a piece too short"
            : too_fast  ? "most rows too fast"
            : negative  ? "most rows below a bound"
                        : "rows out of time order")
        << "; counted below)\n";
  const std::string counts = describeRowCounts(path, contents);
  if (!counts.empty())
  {
    log << "warning: " << counts << "\n";
  }
  const GapKinematics kinematics = checkGapKinematics(contents.runs);
  if (!kinematics.unit_error.empty())
    throw RunReadError(path + ": " + kinematics.unit_error + kUnitErrorRefusal);
  refusePairInOtherUnits(path, contents);
  for (const std::string& disagreement : kinematics.warnings)
  {
    log << "warning: " << path << ": " << disagreement << "\n";
  }
  if (contents.runs.empty())
  {
    throw RunReadError(path + ": no usable run (" + std::to_string(contents.data_rows) + " data rows, " +
                       std::to_string(contents.rejected_rows) + " rejected of which " +
                       std::to_string(contents.implausible_rows) + " implausible, " +
                       std::to_string(contents.time_holes) + " holes in time, " +
                       std::to_string(contents.acc_off_rows) + " with ACC off)" + describeLikelyCauses(contents));
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
