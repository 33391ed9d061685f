#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// A gap that saw-tooths: a position held between its updates (or extrapolated at a wrong rate),
/// then reset. Seen in OpenACC ZalaZone runs (run 26's IVS1 for its first 7 s: +0.82 m every 0.1 s
/// where the speeds say 0.004 m, and back by 2-2.5 m every third or fourth sample: the BMW i3's
/// position, whose columns stand still between updates 0.3-0.4 s apart at 8.2 m/s; run 16,
/// the two gaps around one car in opposite phase). Its net change over seconds agrees with
/// the speeds, so the windows of gap_kinematics.h do not see it, and every value is plausible.
/// Per sample, step_mismatch = (s_k - s_k-1) - the trapezoid integral of (leader - follower) speed
/// over the step. A saw-tooth makes most steps the same nonzero mismatch (the extrapolation's rate
/// error times the sample period) and the resets bring the mean back to 0. Noise on the gap
/// spreads the steps instead: white noise of 1 m moves a window's median by 0.4 m now and then,
/// but puts a tenth of its steps near it, not half.
struct GapSawtoothOptions
{
  double window_s = 2.0;  ///< consecutive windows of this length within each run
  /// A window saw-tooths when the median step mismatch exceeds this (metres per sample; on the
  /// bundled runs' clean windows it stays below 0.2 m, run 26's and run 16's saw-tooths give
  /// 0.78-0.83 m),
  double min_median_step_mismatch_m = 0.4;
  /// at least this share of its steps lie within near_median of the median (relative to it),
  double min_share_near_median = 0.5;
  double near_median = 0.25;
  /// and the mean step mismatch is less than this share of the median (the resets bring the net
  /// change back: a rate error that does not come back is a jump or a unit error, gap_kinematics.h).
  double max_mean_to_median = 0.5;
  /// A span reaches beyond its windows through the consecutive steps next to it whose mismatch
  /// exceeds this (metres): a window boundary cuts the saw-tooth's first and last teeth.
  double min_step_mismatch_to_extend_m = 0.2;
};

/// A stretch of consecutive saw-tooth windows in one run.
struct GapSawtoothSpan
{
  std::string run;
  std::size_t run_index = 0;  ///< in the runs checked
  /// The samples [first_sample, end_sample) of that run whose gap is off: from the end of the first
  /// mismatched step to the end of the last (the windows', extended as the options say).
  std::size_t first_sample = 0, end_sample = 0;
  double start_s = 0.0, end_s = 0.0;  ///< times of the first and the last of those samples
  /// Steps inside it against the drift (mismatch of the other sign than the median, larger than
  /// min_step_mismatch_to_extend_m): the resets, after each of which the gap is a fresh fix.
  std::size_t resets = 0;
  double median_step_mismatch_m = 0.0;  ///< the largest of its windows', signed
  /// "follower" or "leader" when that window's extra rate is the cars' own speed (within 25 %):
  /// that car's position stood still between its updates (the gap grows when the follower's does,
  /// shrinks when the leader's does); "" for another rate (an extrapolation, a range).
  std::string held_position;
};

struct GapSawtooth
{
  std::size_t windows = 0;           ///< windows judged
  std::size_t sawtooth_windows = 0;  ///< of them, saw-tooths
  std::vector<GapSawtoothSpan> spans;
};

/// The check above over every run (windows never cross runs; a run's last window shorter than
/// window_s is not judged).
GapSawtooth checkGapSawtooth(const std::vector<CarFollowingRun>& runs, const GapSawtoothOptions& options = {});

/// One span in words, for a warning: where, by how much per sample, whose position held, and what
/// the gap there is not.
std::string describeSawtoothSpan(const GapSawtoothSpan& span);

/// Rebuilds the gap over a span of the run it was found in. The sample before the span and the
/// sample after each reset are fresh fixes and keep their gap; every other sample of the span
/// takes the gap of the last fresh fix plus what the speeds say since (gapChangeBySpeedsM: the
/// Doppler speeds are not affected, and over the 0.3-0.4 s between fixes they carry the gap to
/// centimetres). The speeds, the time and every sample outside the span are left as they are.
/// Throws std::out_of_range when the span is not within the run or starts at its first sample.
void rebuildSawtoothGap(const GapSawtoothSpan& span, CarFollowingRun* run,
                        const GapSawtoothOptions& options = {});

/// "the gap of its 66 samples rebuilt from the fixes after its 16 resets and the speeds between"
std::string describeGapRebuilt(const GapSawtoothSpan& span);
}  // namespace acc
