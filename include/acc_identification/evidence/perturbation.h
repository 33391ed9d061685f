#pragma once

#include <cstddef>
#include <limits>
#include <vector>

namespace acc
{
/// How a perturbation of the platoon's first car is found and a dip measured.
struct PerturbationCriteria
{
  /// A perturbation: the first car's speed more than this below its median over the run.
  double drop_below_median_mps = 1.0;
  /// Its onset: the last sample before the drop with the speed within this of the median.
  double onset_below_median_mps = 0.25;
  /// Drops closer than this are one perturbation (speed noise around the threshold).
  double merge_within_s = 5.0;
  /// Shorter drops are noise, not perturbations.
  double min_duration_s = 1.0;
  /// A car's pre-perturbation speed: its mean over this long before the onset.
  double pre_window_s = 5.0;
  /// The window a dip's minimum is searched in: from the onset to the first car's recovery plus this.
  double extension_s = 30.0;
  /// The distance lost integrates across holes in a car's speed up to this long; a longer hole
  /// (or a window whose first or last sample is missing) leaves it unknown.
  double max_bridged_hole_s = 1.0;
  /// A car's braking and recovery rates are least-squares slopes of its speed over this span: long
  /// enough that white speed noise (GNSS Doppler: a few cm/s) adds little to a peak taken over
  /// many spans, short against a braking of a few seconds.
  double acceleration_span_s = 2.0;
};

/// One perturbation, as sample indices into the run's time vector.
struct Perturbation
{
  std::size_t onset = 0;       ///< last sample near the median before the drop
  std::size_t end = 0;         ///< first sample after the drop back above median - threshold
  std::size_t window_end = 0;  ///< one past the last sample of the dip window (end + extension)
  double onset_s = 0.0;
  double end_s = 0.0;
  double window_end_s = 0.0;
  double lead_median_mps = 0.0;
};

/// The perturbations of the first car's speed (NaN samples are skipped). time_s increasing.
std::vector<Perturbation> findPerturbations(const std::vector<double>& time_s, const std::vector<double>& lead_speed_mps,
                                            const PerturbationCriteria& criteria = {});

/// A car's dip in this perturbation: its mean speed over the pre-window minus its minimum within
/// [onset, window_end). NaN when either has no finite sample.
double dipDepthMps(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                   const Perturbation& perturbation, const PerturbationCriteria& criteria = {});

/// The distance a car loses in this perturbation against keeping its pre-perturbation speed: the
/// integral over [onset, window_end) of (mean speed over the pre-window - speed) where positive
/// (trapezoids; holes up to criteria.max_bridged_hole_s bridged). It is what the gap behind the
/// car gives up, so a follower's dip follows it as much as the car's own dip: two cars that dip
/// equally deep pass on different dips if one recovers more slowly. NaN when the pre-window has
/// no finite sample or the window is not covered.
double distanceLostM(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                     const Perturbation& perturbation, const PerturbationCriteria& criteria = {});

/// The shape of a car's dip beyond its depth. Rates [m/s^2, both positive]: the steepest falling
/// and rising least-squares slope of its speed over criteria.acceleration_span_s, braking on spans
/// from a span before the onset to the dip's minimum, recovery on spans from the minimum to the
/// window's end; a follower's rates over its leader's say how much of a braking's shape it passes
/// on. Width [s]: how long its speed stays below half its dip (below the mean of its
/// pre-perturbation speed and its minimum; crossings interpolated linearly), the dip's full width
/// at half depth: two dips of one depth lose different distances when one is wider.
/// Each NaN where the window's first or last sample is missing (the dip may lie outside the data),
/// where a hole longer than criteria.max_bridged_hole_s hides what it measures, and the width
/// also where the speed is not back above half its dip by the window's end.
struct DipShape
{
  double braking_mps2 = std::numeric_limits<double>::quiet_NaN();
  double recovery_mps2 = std::numeric_limits<double>::quiet_NaN();
  double width_s = std::numeric_limits<double>::quiet_NaN();
};
DipShape dipShape(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                  const Perturbation& perturbation, const PerturbationCriteria& criteria = {});

/// The median of the finite values (NaN when none).
double finiteMedian(std::vector<double> values);

}  // namespace acc
