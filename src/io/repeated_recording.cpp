#include "acc_identification/io/repeated_recording.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <utility>

#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
/// Only every kIndexStride-th stretch of an added series is indexed: a tenth of the memory, for
/// a repeat that must run kIndexStride - 1 samples longer to be found.
constexpr std::size_t kIndexStride = 10;
constexpr std::uint64_t kHashBase = 1099511628211ULL;  // FNV's prime: odd, so multiplying is a bijection mod 2^64

/// A value's bits, with -0 taken as +0 (equal as numbers).
std::uint64_t bitsOf(double value)
{
  const double normalised = value + 0.0;
  std::uint64_t bits = 0;
  std::memcpy(&bits, &normalised, sizeof bits);
  return bits;
}

/// Whether a stretch with these counts can decide a repeat: finite, and varying.
bool decides(std::size_t not_finite, std::size_t changes)
{
  return not_finite == 0 && changes >= kRepeatedRecordingMinChanges;
}

/// Every stretch of kRepeatedRecordingMinSamples values of a series that can decide a repeat
/// (finite and varying), with its polynomial hash: visit(first_row, hash) in order, until visit
/// returns true.
template <typename Visit>
void forEachVaryingStretch(const std::vector<double>& series, Visit&& visit)
{
  constexpr std::size_t m = kRepeatedRecordingMinSamples;
  if (series.size() < m)
    return;
  std::uint64_t top_power = 1;  // kHashBase^(m - 1)
  for (std::size_t k = 1; k < m; ++k)
    top_power *= kHashBase;
  std::uint64_t hash = 0;
  std::size_t not_finite = 0, changes = 0;  // within the stretch ending at k
  for (std::size_t k = 0; k < series.size(); ++k)
  {
    if (k >= m)  // the sample leaving the stretch, and its step to the next
    {
      const std::size_t out = k - m;
      hash -= bitsOf(series[out]) * top_power;
      not_finite -= std::isfinite(series[out]) ? 0 : 1;
      changes -= series[out + 1] != series[out] ? 1 : 0;
    }
    hash = hash * kHashBase + bitsOf(series[k]);
    not_finite += std::isfinite(series[k]) ? 0 : 1;
    if (k > 0)
      changes += series[k] != series[k - 1] ? 1 : 0;
    if (k + 1 >= m && decides(not_finite, changes) && visit(k + 1 - m, hash))
      return;
  }
}

/// The first varying stretch of a series whose rows, shifted, lie within [0, rows), or none (a
/// series too short, at standstill, not finite, or not varying where the two overlap).
std::optional<std::size_t> firstVaryingStretchWithin(const std::vector<double>& series, long long shift,
                                                     std::size_t rows)
{
  std::optional<std::size_t> first;
  forEachVaryingStretch(series, [&](std::size_t row, std::uint64_t) {
    const long long shifted = static_cast<long long>(row) + shift;
    if (shifted < 0 || static_cast<std::size_t>(shifted) + kRepeatedRecordingMinSamples > rows)
      return false;
    first = row;
    return true;
  });
  return first;
}

/// Whether series[row, row + m) can decide a repeat, as forEachVaryingStretch asks
/// (m = kRepeatedRecordingMinSamples).
bool varyingAt(const std::vector<double>& series, std::size_t row)
{
  if (row + kRepeatedRecordingMinSamples > series.size())
    return false;
  std::size_t not_finite = 0, changes = 0;
  for (std::size_t k = row; k < row + kRepeatedRecordingMinSamples; ++k)
  {
    not_finite += std::isfinite(series[k]) ? 0 : 1;
    changes += k > row && series[k] != series[k - 1] ? 1 : 0;
  }
  return decides(not_finite, changes);
}

/// Whether a[i, i + m) equals b[j, j + m) value for value (m = kRepeatedRecordingMinSamples; out
/// of range: no).
bool sameStretch(const std::vector<double>& a, long long i, const std::vector<double>& b, std::size_t j)
{
  constexpr std::size_t m = kRepeatedRecordingMinSamples;
  if (i < 0 || static_cast<std::size_t>(i) + m > a.size() || j + m > b.size())
    return false;
  for (std::size_t k = 0; k < m; ++k)
  {
    if (!(a[static_cast<std::size_t>(i) + k] == b[j + k]))
      return false;
  }
  return true;
}
}  // namespace

void RepeatedRecordingIndex::add(Recording recording, std::size_t id)
{
  const std::size_t number = recordings_.size();
  for (std::size_t s = 0; s < recording.size(); ++s)
  {
    forEachVaryingStretch(recording[s], [&](std::size_t row, std::uint64_t hash) {
      if (row % kIndexStride == 0)
        stretches_[hash].push_back({number, s, row});
      return false;
    });
  }
  recordings_.push_back(std::move(recording));
  ids_.push_back(id);
}

bool RepeatedRecordingIndex::repeatsAtShift(const Recording& later, std::size_t earlier, long long shift,
                                            std::size_t matched_row, bool every_series) const
{
  std::size_t rows = 0;  // the earlier recording's (a car without speeds has an empty series)
  for (const std::vector<double>& series : recordings_[earlier])
    rows = std::max(rows, series.size());
  for (const std::vector<double>& series : later)
  {
    // Compared where the match was found, else where it varies within the overlap.
    const std::optional<std::size_t> row =
        varyingAt(series, matched_row) ? matched_row : firstVaryingStretchWithin(series, shift, rows);
    if (!row && every_series)
      return false;
    if (!row)
      continue;  // nothing in it, where the two overlap, can tell one drive from another
    bool repeated = false;
    for (const std::vector<double>& candidate : recordings_[earlier])
      repeated = repeated || sameStretch(candidate, static_cast<long long>(*row) + shift, series, *row);
    if (!repeated)
      return false;
  }
  return true;
}

std::optional<RepeatedRecording> RepeatedRecordingIndex::find(const Recording& recording, bool every_series) const
{
  std::optional<RepeatedRecording> found;
  std::set<std::pair<std::size_t, long long>> refuted;  // (earlier recording, shift) already checked
  for (std::size_t s = 0; s < recording.size() && !found; ++s)
  {
    forEachVaryingStretch(recording[s], [&](std::size_t row, std::uint64_t hash) {
      const auto candidates = stretches_.find(hash);
      if (candidates == stretches_.end())
        return false;
      for (const Entry& entry : candidates->second)
      {
        const long long shift = static_cast<long long>(entry.row) - static_cast<long long>(row);
        if (!sameStretch(recordings_[entry.recording][entry.series], static_cast<long long>(entry.row),
                         recording[s], row) ||
            !refuted.insert({entry.recording, shift}).second)
          continue;
        if (repeatsAtShift(recording, entry.recording, shift, row, every_series))
        {
          found = RepeatedRecording{ids_[entry.recording], s, entry.series, entry.row, row};
          return true;
        }
      }
      return false;
    });
  }
  return found;
}

std::optional<RepeatedRun> findRepeatedRun(const std::vector<CarFollowingRun>& runs,
                                           const std::vector<std::size_t>& input_of)
{
  RepeatedRecordingIndex earlier_inputs;
  std::map<std::size_t, RepeatedRecordingIndex> own_input;  // by input: its runs so far
  std::size_t indexed = 0;  // runs [0, indexed) are in earlier_inputs: those of the inputs before this run's
  for (std::size_t k = 0; k < runs.size(); ++k)
  {
    for (; indexed < k && input_of[indexed] < input_of[k]; ++indexed)
      earlier_inputs.add({runs[indexed].follower_speed_mps, runs[indexed].leader_speed_mps}, indexed);
    const Recording speeds{runs[k].follower_speed_mps, runs[k].leader_speed_mps};
    if (const std::optional<RepeatedRecording> repeat = earlier_inputs.find(speeds))
      return RepeatedRun{k, repeat->id, *repeat};
    RepeatedRecordingIndex& same_input = own_input[input_of[k]];
    const std::optional<RepeatedRecording> repeat = same_input.find(speeds, true);
    if (repeat && runs[k].time_s[repeat->later_row] == runs[repeat->id].time_s[repeat->earlier_row])
      return RepeatedRun{k, repeat->id, *repeat};
    same_input.add(speeds, k);
  }
  return std::nullopt;
}

std::string describeRepeatedRun(const std::vector<CarFollowingRun>& runs, const std::vector<std::size_t>& input_of,
                                const std::vector<std::string>& path_of_run)
{
  const std::optional<RepeatedRun> repeat = findRepeatedRun(runs, input_of);
  if (!repeat)
    return "";
  const CarFollowingRun& later = runs[repeat->later];
  const CarFollowingRun& earlier = runs[repeat->earlier];
  return path_of_run[repeat->later] + ": its run " + later.name + " (from " +
         describeSampleTime(later.time_s[repeat->where.later_row]) + ") repeats " + path_of_run[repeat->earlier] +
         "'s run " + earlier.name + " (from " + describeSampleTime(earlier.time_s[repeat->where.earlier_row]) +
         ") sample for sample: the follower's and the leader's speeds over " +
         std::to_string(kRepeatedRecordingMinSamples) +
         " samples or more, to the last digit, are the same recording (" +
         (input_of[repeat->later] == input_of[repeat->earlier] ? "one drive given twice in this input"
                                                                : "a copy, an excerpt or an export of the same drive") +
         ")";
}

std::string describeSampleTime(double time_s) { return printfText("t = %.1f s", time_s); }

}  // namespace acc
