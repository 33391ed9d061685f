#pragma once

#include <cstddef>
#include <deque>
#include <limits>
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
  /// Over the same recent windows: the gap's change per metre of the relative speed's integral
  /// (least squares through 0; 1 for a leader ahead, -1 for receivers the other way round) and
  /// the integrals' RMS [m], how much the slope has to go on. NaN when none.
  double recentGapPerDopplerSlope() const;
  double recentDopplerIntegralRms() const;
  std::size_t recentWindows() const { return recent_.size(); }
  /// The latest recent full window's two sides: the gap's change and the relative speed's integral
  /// [m] (NaN when no recent window; right after add() returned a residual, that window's).
  double lastGapChangeM() const { return recent_.empty() ? kNoWindow : recent_.back().gap_change_m; }
  double lastDopplerIntegralM() const { return recent_.empty() ? kNoWindow : recent_.back().doppler_integral_m; }
  void reset();

private:
  struct Sample
  {
    double time_s;
    double gap_m;
    double relative_speed_mps;
    double integral_m;  // of the relative speed since the first sample
  };
  /// One full window ending at time_s: its two sides, whose difference is its residual.
  struct Residual
  {
    double time_s;
    double gap_change_m;
    double doppler_integral_m;
    double residual_m() const { return gap_change_m - doppler_integral_m; }
  };

  double window_s_;
  double max_spacing_s_;
  std::deque<Sample> history_;
  std::deque<Residual> recent_;
  double recent_sum_squares_ = 0.0;
  double recent_sum_cross_ = 0.0;           ///< gap change times Doppler integral
  double recent_sum_integral_squares_ = 0.0;
  static constexpr double kNoWindow = std::numeric_limits<double>::quiet_NaN();
};

/// The consistency of a whole series, same windows as GapDopplerConsistency.
struct ConsistencySummary
{
  double rms_m;          ///< RMS of all residuals; NaN when no full window
  std::size_t windows;   ///< residuals computed
  /// The gap's change per metre of the relative speed's integral over the windows (least squares
  /// through 0): 1 for a gap behind the leader as the Doppler speeds say, -1 when the two cars are
  /// the other way round (the gap is unsigned, the relative speed is not). NaN when no window.
  double gap_per_doppler_slope = std::numeric_limits<double>::quiet_NaN();
  /// RMS of the windows' relative-speed integrals [m]: how much the slope has to go on.
  double doppler_integral_rms_m = std::numeric_limits<double>::quiet_NaN();
};
/// The one rule, batch (nmea_to_csv) and live (relative_state_node's diagnostics), for receivers
/// given the other way round: the gap is a distance, the same either way, while the relative
/// speed changes its sign, so the gap's change follows the relative speed's integral with a slope
/// near -1 instead of 1. Decided only where the relative speed moved the gap by a metre or more
/// (RMS) over ten windows or more, at a slope below -0.5.
bool receiversLookSwapped(double gap_per_doppler_slope, double doppler_integral_rms_m, std::size_t windows);

ConsistencySummary gapDopplerConsistency(const std::vector<double>& time_s, const std::vector<double>& gap_m,
                                         const std::vector<double>& relative_speed_mps, double window_s = 10.0,
                                         double max_spacing_s = 0.5);

}  // namespace acc
