#pragma once

#include <cstddef>
#include <deque>
#include <vector>

namespace acc
{
/// The physical check of a gap signal: over a window, the change of the gap must equal the
/// integral of the relative (Doppler) speed, leader minus follower. The residual
///   r(t) = [gap(t) - gap(t - W)] - integral over [t - W, t] of relative_speed (trapezoids)
/// is computed for each sample once a full window of contiguous data precedes it. Doppler
/// speeds are independent of the positions, so a gap with a position error that wanders
/// (multipath, a misplaced antenna offset on a curve) shows here; a constant offset does not.
class GapDopplerConsistency
{
public:
  /// @param window_s        W, the check window
  /// @param max_spacing_s   samples further apart break the data: the window restarts
  explicit GapDopplerConsistency(double window_s = 10.0, double max_spacing_s = 0.5);

  /// Adds a sample; returns r(t) for the window ending here, NaN until a full window exists.
  double add(double time_s, double gap_m, double relative_speed_mps);
  /// RMS of the residuals of the windows that ended in the last W seconds; NaN when none.
  double recentRms() const;
  void reset();

private:
  struct Sample
  {
    double time_s;
    double gap_m;
    double relative_speed_mps;
    double integral_m;  // of the relative speed since the first sample
  };
  struct Residual
  {
    double time_s;
    double residual_m;
  };

  double window_s_;
  double max_spacing_s_;
  std::deque<Sample> history_;
  std::deque<Residual> recent_;
  double recent_sum_squares_ = 0.0;
};

/// The consistency of a whole series, same windows as GapDopplerConsistency.
struct ConsistencySummary
{
  double rms_m;          ///< RMS of all residuals; NaN when no full window
  std::size_t windows;   ///< residuals computed
};
ConsistencySummary gapDopplerConsistency(const std::vector<double>& time_s, const std::vector<double>& gap_m,
                                         const std::vector<double>& relative_speed_mps, double window_s = 10.0,
                                         double max_spacing_s = 0.5);

}  // namespace acc
