#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// When a run's measured gap and its two speeds disagree about the motion. The gap comes from
/// positions or a radar and the speeds from Doppler, independently, so over a window the change
/// of the gap equals the integral of the speed difference (leader - follower) to a metre or two:
/// on the bundled OpenACC runs, 0.1-1.8 m RMS over 10 s windows, 5.1 m at most, and a ratio of
/// the two of 0.76-1.23 wherever the cars' relative motion is at least 2 m. A unit error scales
/// one against the other (speeds in km/h: the gap changes at 0.28 of the rate the speeds say; a
/// gap in feet: 3.3 times), and a gap that jumps (a lost target, a car cutting in, a sign error)
/// leaves a window metres off. Both pass every per-sample plausibility bound.
struct GapKinematicsOptions
{
  double window_s = 10.0;  ///< consecutive windows of this length within each run
  /// A window whose gap change and integrated speed difference differ by more than this is a jump.
  double max_window_mismatch_m = 10.0;
  /// The ratio is judged only when the integrated speed difference varies this much over the
  /// windows (standard deviation): in steady following both changes are noise.
  double min_relative_motion_m = 3.0;
  double min_scale = 0.5, max_scale = 2.0;  ///< the ratio allowed
};

struct GapKinematics
{
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::size_t windows = 0;
  /// Least-squares ratio of the gap change to the integrated speed difference over the windows
  /// (1 when both are in metres and m/s); NaN without windows.
  double scale = kNaN;
  double relative_motion_m = kNaN;  ///< standard deviation of the integrated speed difference over the windows
  double rms_mismatch_m = kNaN;     ///< RMS of (gap change - integrated speed difference)
  std::size_t jump_windows = 0;     ///< windows off by more than max_window_mismatch_m
  /// The window most off: its run, start and end, the gap change and what the speeds say.
  std::string worst_run;
  double worst_start_s = kNaN, worst_end_s = kNaN, worst_gap_change_m = kNaN, worst_speed_change_m = kNaN;
  /// Whether the relative motion was enough to judge the ratio (min_relative_motion_m).
  bool ratio_judged = false;
  /// The ratio judged (enough relative motion) and outside [min_scale, max_scale], in words: a
  /// unit error, which every reader refuses (a model fitted to a gap and speeds in different
  /// units gives wrong numbers, not an estimate); "" otherwise. Also the first of `warnings`.
  std::string unit_error;
  /// Each disagreement in words, for a warning; empty when the gap and the speeds agree (or too
  /// little relative motion decides the ratio: said in none). What these windows average away,
  /// a gap that saw-tooths sample by sample, the run reader finds and rebuilds (gap_sawtooth.h).
  std::vector<std::string> warnings;
};

/// What a reader that refuses data for their unit_error says after it.
inline constexpr const char* kUnitErrorRefusal =
    ": not used: a model fitted to a gap and speeds that disagree gives wrong numbers, not an estimate (the gap "
    "in metres and the speeds in m/s, of the same two cars)";

/// The check above over every run (windows never cross runs).
GapKinematics checkGapKinematics(const std::vector<CarFollowingRun>& runs, const GapKinematicsOptions& options = {});
}  // namespace acc
