#pragma once

#include <cstddef>
#include <iosfwd>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "acc_identification/model/car_following_run.h"
#include "acc_identification/io/gap_sawtooth.h"
#include "acc_identification/io/openacc_file.h"
#include "acc_identification/io/run_plausibility.h"

namespace acc
{
/// A file that cannot be read as runs at all (missing, no recognisable header, no data).
class RunReadError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Everything read from one run file, with an account of every row that was not used.
struct RunFileContents
{
  std::vector<CarFollowingRun> runs;
  std::size_t data_rows = 0;          ///< rows after the header
  std::size_t rejected_rows = 0;      ///< rows not used (each one listed in problems)
  std::size_t implausible_rows = 0;   ///< of rejected_rows: values outside the plausibility bounds
  /// Of rejected_rows: rows a canonical CSV's optional valid column marks 0 (the pairing's
  /// verdict, as nmea_to_csv writes it): split points, as an invalid RelativeState in a bag.
  std::size_t marked_invalid_rows = 0;
  /// Of rejected_rows: exact repeats of the row before (the same time and values), which carry no
  /// sample of their own and so do not split the run.
  std::size_t duplicate_rows = 0;
  /// Of rejected_rows: a time not after the row before's. Many of a file's rows so: its rows are
  /// not in time order (describeTimeOrder), and the holes between the rest say nothing of its rate.
  std::size_t time_back_rows = 0;
  std::size_t time_holes = 0;         ///< steps longer than max_time_step_s (split points, no row lost)
  /// Steps between consecutive rows that were looked at for a hole (time_holes of them were one):
  /// when most are, the data are recorded more coarsely than a run may step (describeCoarseSteps).
  std::size_t time_steps = 0;
  /// The shortest of those steps [s] (infinity without one): when even it is longer than any
  /// car-following log steps (kImplausibleShortestStepS), time is not in seconds.
  double shortest_step_s = std::numeric_limits<double>::infinity();
  std::size_t acc_off_rows = 0;       ///< OpenACC rows where the follower was not on ACC (split points)
  /// Rows alone between split points (a piece of one sample cannot be simulated): not used, each
  /// listed in problems. So data_rows = rejected_rows + acc_off_rows + single_sample_rows + the
  /// runs' samples: every row is used or counted.
  std::size_t single_sample_rows = 0;
  /// Of implausible_rows: a speed above the upper bound (RunPlausibilityBounds::max_speed_mps).
  /// Most of a file's rows so: its speeds are in km/h (describeSpeedUnit).
  std::size_t too_fast_rows = 0;
  /// Of implausible_rows: a speed or gap below its lower bound. Most of a file's rows so: a sign
  /// error (describeSign).
  std::size_t negative_rows = 0;
  /// Rows whose gap saw-tooths (a position held between its updates, gap_sawtooth.h) and was
  /// rebuilt from the fixes and the speeds (rebuildSawtoothGap); used, not in rejected_rows; each
  /// stretch listed in problems and in sawtooth_spans (each names its run, and its samples index
  /// into that run; run_index is 0).
  std::size_t sawtooth_rows = 0;
  std::vector<GapSawtoothSpan> sawtooth_spans;
  std::vector<std::string> problems;  ///< "path:line: why", one per rejected row, hole or short piece
  /// "path: ...", for OpenACC files: the pair(s) read and how they were chosen (also by default:
  /// never silently), the cars without data or without a pair and why, how ACC on was told, the
  /// file's bad cells outside the pair. Empty for a canonical CSV.
  std::vector<std::string> notes;
  /// OpenACC: the pair(s) the runs are of, in order; empty for a canonical CSV.
  std::vector<OpenAccPair> pairs;
  /// OpenACC: for each run, the index in pairs of its pair.
  std::vector<std::size_t> run_pairs;
};

/// Reads a canonical run CSV (header time_s,space_gap_m,follower_speed_mps,leader_speed_mps, in
/// any column order; an optional valid column, 0 or 1 (0.0, 1.0, false, true alike), with invalid_reason beside it, as
/// nmea_to_csv writes them: a row marked 0 is a split point, rejected with its reason) or an OpenACC file of any layout (two vehicles or a platoon; read by
/// readOpenAccFile, openacc_file.h) as the runs of one leader-follower pair: by default the first
/// pair the file holds, said in notes. A bad row (wrong field count, not a number, not finite, a
/// value outside the plausibility bounds, time not increasing) is rejected, listed with its line
/// number, and splits the run, so that no simulation ever integrates across it; an exact repeat of
/// the row before (an export's duplicate) is rejected and listed too, without a split. For OpenACC only
/// the pair's own cells count (Time, IVS(k-1), Speed(k), Speed(k-1)): a NaN in another car's
/// column does not touch it. A time step longer than bounds.max_time_step_s splits the run too,
/// keeping both rows, and is listed. OpenACC rows where the follower's Driverk is not ACC split
/// the run; without a Driverk column, the ACC metadata line tells (1 or absent: ACC on
/// throughout; 0 or 2: no row is known to be on ACC). Pieces with fewer than two samples are
/// listed in problems. Runs are named after the file ("part3"; OpenACC: the file and the
/// follower, "dynamic_part12 BMW_I3"), with "#2", "#3"... for later pieces.
/// Throws RunReadError when the file cannot be opened, has no recognisable header or metadata, or
/// the OpenACC pair chosen is not in the file (the message lists the pairs that are), and
/// std::invalid_argument when the bounds are unusable (describeBoundsProblem); never for a row.
RunFileContents readRunFile(const std::string& path, const RunPlausibilityBounds& bounds = RunPlausibilityBounds{});

/// readRunFile() with the OpenACC pair(s) to read: the first (the default above), one follower by
/// name or position (OpenAccPairSelector::byFollower("BMW_I3"), ("3")), or all pairs (every pair's
/// runs in one list, counts summed over the pairs, each problem naming its pair). A canonical CSV
/// holds one pair: choosing a follower there throws RunReadError.
RunFileContents readRunFile(const std::string& path, const RunPlausibilityBounds& bounds,
                            const OpenAccPairSelector& selector);

/// Samples handed over as columns rather than read from a file (the Python API's DataFrames),
/// judged row by row by the readers' own rules: a value that is not finite or not plausible, or a
/// time that does not increase, rejects its row and splits the run; a hole longer than
/// bounds.max_time_step_s splits it; an exact repeat is dropped; a saw-toothing gap is rebuilt.
/// Every problem reads "label:row: why", row taken from rows (one per sample); the runs are named
/// name, name#2, ... The columns of `columns` must have equal lengths, and rows as many entries.
RunFileContents assembleRunColumns(const std::string& label, const std::string& name, const CarFollowingRun& columns,
                                   const std::vector<std::size_t>& rows, const RunPlausibilityBounds& bounds);

/// One OpenACC pair's runs, with their own counts and problems.
struct PairRunContents
{
  OpenAccPair pair;  ///< empty names and positions 0 for a canonical CSV
  RunFileContents contents;
};

/// Every pair of a file, each read as readRunFile reads one.
struct AllPairRuns
{
  std::vector<std::string> notes;  ///< the file's notes and the pairs read
  std::vector<PairRunContents> pairs;
};

/// The runs of every pair of an OpenACC file, pair by pair (a canonical CSV: its one pair). Throws
/// as readRunFile, and RunReadError when the file holds no pair.
AllPairRuns readAllPairRuns(const std::string& path, const RunPlausibilityBounds& bounds = RunPlausibilityBounds{});

/// "path: 3 of 2530 rows rejected (1 outside the plausibility bounds, 0 duplicates), 2 holes in
/// time split a run" (and ", 1 rows alone between split points not used", ", the gap of 66 rows
/// rebuilt where it saw-tooths" when there are), or "" when no row is rejected, left alone or
/// rebuilt and no hole splits.
std::string describeRowCounts(const std::string& path, const RunFileContents& contents);

/// No car-following log steps this coarsely: a file whose every step is at least this long [s]
/// holds its time in another unit (milliseconds: 100 per 10 Hz step), not a coarse receiver.
constexpr double kImplausibleShortestStepS = 5.0;

/// "" unless most of the steps are holes (a 1 Hz receiver against a max gap of 0.5 s: every row
/// alone, nothing to simulate); then what that means and what to set, for the row counts and for
/// the error that no run is usable. Where even the shortest step is kImplausibleShortestStepS or
/// more, it says the time is not in seconds instead (a larger max gap would only fit nonsense).
std::string describeCoarseSteps(const RunFileContents& contents);

/// "; N of its M rows go back in time ...: sort them by time" when more than a tenth of the rows
/// do (a file whose rows are shuffled), else "". describeCoarseSteps(contents) then says nothing:
/// the holes between the rest are the shuffle's, not the recording's rate.
std::string describeTimeOrder(const RunFileContents& contents);
/// The same from the counts (a bag's holes against its steps between messages, its shortest step).
std::string describeCoarseSteps(std::size_t time_holes, std::size_t time_steps,
                                double shortest_step_s = std::numeric_limits<double>::infinity());

/// "" unless most rows have a speed above the upper bound; then that the speeds are likely in km/h
/// and to convert them, for the row counts and the error that no run is usable (the rows' own
/// lines say only that each value is out of bounds).
std::string describeSpeedUnit(const RunFileContents& contents);

/// "; N of its M rows have a speed or gap below its bound: a sign error? ..." when most rows do
/// (speeds or a gap negated throughout), else "".
std::string describeSign(const RunFileContents& contents);

/// readRunFile() for tools: returns the runs, and writes every note and problem (and the counts of
/// rejected rows and holes) to stderr, so nothing is dropped silently. Throws as readRunFile, and
/// RunReadError when no run is usable.
std::vector<CarFollowingRun> readRuns(const std::string& path,
                                      const RunPlausibilityBounds& bounds = RunPlausibilityBounds{});

/// readRuns() with the OpenACC pair(s) to read (see readRunFile).
std::vector<CarFollowingRun> readRuns(const std::string& path, const RunPlausibilityBounds& bounds,
                                      const OpenAccPairSelector& selector);

/// What readRuns() does with what readRunFile() read: writes every note ("note: ") and problem
/// ("warning: ") and the counts to log, and where the gap jumps against the speeds
/// (checkGapKinematics) a warning; takes the runs; throws RunReadError when none is usable, and
/// when the gap and the speeds disagree by a unit error (GapKinematics::unit_error).
std::vector<CarFollowingRun> reportAndTakeRuns(const std::string& path, RunFileContents& contents, std::ostream& log);

/// Writes one run as a canonical CSV (full double precision). Throws RunReadError on I/O failure.
void writeRunCsv(const std::string& path, const CarFollowingRun& run);

}  // namespace acc
