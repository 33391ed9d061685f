#pragma once

#include <string>

namespace acc
{
/// What a car-following sample may physically be. A value outside these bounds is a unit, parse or
/// sensor error, never a measurement: one follower speed of 1e9 m/s would otherwise dominate every
/// RMSE of the fit without a word. Shared by every reader of runs (CSV and bags), so that the same
/// values give the same runs and the same messages whatever the file format.
struct RunPlausibilityBounds
{
  /// A Doppler speed is a magnitude, so it is never negative in principle; filtering and
  /// interpolation can still put a standstill slightly below zero, hence -1 and not 0.
  /// Applies to the follower and the leader speed alike.
  double min_speed_mps = -1.0;
  /// 100 m/s = 360 km/h: no car under ACC comes near it; above it the value is an error.
  double max_speed_mps = 100.0;
  /// The gap is bumper to bumper; positioning error can make it slightly negative when the cars are
  /// close, but an overlap beyond 2 m would be a collision, not car following.
  double min_space_gap_m = -2.0;
  /// Beyond 1000 m the follower does not follow anything (ACC radars see a few hundred metres).
  double max_space_gap_m = 1000.0;
  /// The largest time step inside one run. The model is simulated with Euler steps at the data's
  /// own step (typically 0.1 s), so a hole in the data would become one long step across seconds
  /// that were never measured; 0.5 s leaves room for four dropped epochs at 10 Hz and splits the
  /// run at anything longer. The same limit as the identifier node's ~max_gap_s and the tools'
  /// --max-gap, so a CSV, a bag and a live window of the same samples give the same runs.
  double max_time_step_s = 0.5;
};

/// Why the bounds themselves cannot be used (a minimum not below its maximum, a time step not
/// positive, NaN), or "" when they can. Infinite bounds are allowed: they switch a check off.
std::string describeBoundsProblem(const RunPlausibilityBounds& bounds);

/// Why a sample's values are physically impossible, or "" when they are plausible. Names the first
/// value outside its bounds, in column order (gap, follower speed, leader speed), with its unit:
/// "follower_speed_mps 1e+09 outside [-1, 100] m/s". A non-finite value is outside every bound.
std::string describeImplausibleValue(double space_gap_m, double follower_speed_mps, double leader_speed_mps,
                                     const RunPlausibilityBounds& bounds);

/// Why the step from the previous sample of a run to this one is a hole at which the run must be
/// split (neither sample is wrong, but no simulation may step across it), or "" when it is not:
/// "hole of 10 s before this row (max 1 s)". Only judges the length of the step; a time that does
/// not increase is the reader's to reject.
std::string describeTimeHole(double previous_time_s, double time_s, const RunPlausibilityBounds& bounds);

}  // namespace acc
