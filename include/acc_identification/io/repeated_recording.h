#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// Two inputs that hold the same recording: a file copied under another name, an excerpt cut
/// from a run given beside the run, one drive exported twice. Given together they are not two
/// drives: a leave-one-run-out fit (campaign) or a held-out score (diagnose --held-out) would
/// judge a model on data it was fitted on, and a calibration would count the drive twice.
///
/// The test is the physics of a measurement: a measured speed is noisy in its last digits, so two
/// different drives never hold the same long stretch of values sample for sample. A stretch
/// repeats when kRepeatedRecordingMinSamples consecutive values of one series appear in the same
/// order in another, to the last bit, and the stretch varies (at least
/// kRepeatedRecordingMinChanges of its consecutive samples differ): a car at standstill, or a
/// value a recorder held through a dropout, is the same in every drive and decides nothing.
/// A recording is several series sampled together (a file's cars, a run's follower and leader),
/// and it repeats an earlier one only when every series of it that varies repeats one of the
/// earlier's at the same shift of rows: simulated drives without noise share their leader's
/// profile, and differ in their followers. Exact equality also means that a drive converted
/// through another format (printed with fewer digits) is not recognised: only copies of the same
/// numbers are. Every tenth stretch of a recording is indexed, so a repeat of
/// kRepeatedRecordingMinSamples + 9 samples is found whatever its alignment, a shorter one may be.
constexpr std::size_t kRepeatedRecordingMinSamples = 100;  ///< 10 s at 10 Hz
constexpr std::size_t kRepeatedRecordingMinChanges = 20;

/// Series sampled together, by row: a file's cars' speeds, a run's follower and leader speeds.
using Recording = std::vector<std::vector<double>>;

/// Where a recording repeats one indexed before.
struct RepeatedRecording
{
  std::size_t id = 0;             ///< the id the earlier recording was added with
  std::size_t series = 0;         ///< the first of the later recording's series that repeats
  std::size_t earlier_series = 0;  ///< the earlier recording's series it repeats
  std::size_t earlier_row = 0;     ///< where the repeated stretch starts in the earlier recording
  std::size_t later_row = 0;       ///< and in the later one
};

/// Recordings indexed by the stretches their series hold, so that each new one is looked up
/// against all of them in time about linear in its length (a rolling hash of its stretches, each
/// match then compared value for value).
class RepeatedRecordingIndex
{
public:
  /// Adds a recording under an id (a file's or a run's number).
  void add(Recording recording, std::size_t id);

  /// Where `recording` repeats one added before (every varying series of it, at one shift of
  /// rows), or none. With `every_series`, each of its series must vary where compared and repeat:
  /// a series that does not vary then refutes the repeat instead of deciding nothing.
  std::optional<RepeatedRecording> find(const Recording& recording, bool every_series = false) const;

private:
  struct Entry
  {
    std::size_t recording = 0;  ///< into recordings_
    std::size_t series = 0;
    std::size_t row = 0;
  };
  /// Whether every series of `later` that varies repeats one of recording `earlier`'s at rows
  /// shifted by `shift`: at matched_row where it varies there, else where it first varies.
  bool repeatsAtShift(const Recording& later, std::size_t earlier, long long shift, std::size_t matched_row,
                      bool every_series) const;

  std::vector<Recording> recordings_;
  std::vector<std::size_t> ids_;
  /// Every kIndexStride-th varying stretch of each series, by its hash: a repeat of
  /// kRepeatedRecordingMinSamples + kIndexStride - 1 samples or more holds one of them whole.
  std::unordered_map<std::uint64_t, std::vector<Entry>> stretches_;
};

/// A run that repeats an earlier one: indices into the runs looked at, and where.
struct RepeatedRun
{
  std::size_t later = 0;
  std::size_t earlier = 0;
  RepeatedRecording where;  ///< its id is `earlier`; series 0 the follower's speeds, 1 the leader's
};

/// The first run whose follower and leader speeds repeat an earlier run's, or none; `input_of[k]`
/// numbers the input run k came from. Across inputs every varying series of the later run must
/// repeat. Runs of one input are compared too, but only where both the follower's and the
/// leader's speeds vary and repeat at the same time stamps: one drive appended after itself, its
/// clock restarted. A file's neighbouring pairs share a car (the follower of one leads the next),
/// so that car's speeds alone repeat whenever the other car's hardly change; and a noise-free
/// simulated platoon (Newell's time-shifted copies) or periodic drive repeats at other times. A
/// drive appended with its time running on, or re-based, is not recognised.
std::optional<RepeatedRun> findRepeatedRun(const std::vector<CarFollowingRun>& runs,
                                           const std::vector<std::size_t>& input_of);

/// findRepeatedRun said: "LATER_PATH: its run NAME (from t = ...) repeats EARLIER_PATH's run NAME
/// (from t = ...) sample for sample: ...", `path_of_run[k]` the file run k came from and
/// `input_of[k]` the input (one drive given twice within one input is said so); "" when no run
/// repeats an earlier one.
std::string describeRepeatedRun(const std::vector<CarFollowingRun>& runs, const std::vector<std::size_t>& input_of,
                                const std::vector<std::string>& path_of_run);

/// "t = 950.2 s": the time of a sample, for the messages that name a repeat.
std::string describeSampleTime(double time_s);

}  // namespace acc
