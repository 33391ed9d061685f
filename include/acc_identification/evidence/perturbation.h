#pragma once

#include <climits>
#include <cstddef>
#include <limits>
#include <string>
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
  /// The data end before the dip window does (within extension_s of the first car's recovery).
  bool window_cut = false;
  /// Why the data do not hold the whole perturbation ("" when they do): the first car's speed was
  /// already below its median where the data begin (no onset near it), it is still below when they
  /// end, or they end before the window does with the first car judged behind it not yet recovering
  /// (judgeCutWindows). A dip there may be cut off: every car's dip, distance lost and shape are
  /// NaN, measured or predicted alike.
  std::string incomplete;
  /// With a cut window: the order (platoon position) of the first car judged whose dip the data's
  /// end may cut off; its dip and those of the cars after it are not measured, measured or predicted
  /// (cut_note says why). INT_MAX when every car's is whole.
  int first_cut_order = INT_MAX;
  std::string cut_note;
  /// Whether the data's end may cut off the dip of the car of this order (measured or predicted).
  bool cutOffAt(int order) const { return order >= first_cut_order; }
};

/// The perturbations of the first car's speed (NaN samples are skipped), those the data do not hold
/// whole among them marked (Perturbation::incomplete; a cut window judged on the first car's own
/// speed). time_s increasing.
std::vector<Perturbation> findPerturbations(const std::vector<double>& time_s, const std::vector<double>& lead_speed_mps,
                                            const PerturbationCriteria& criteria = {});

/// A measured car's speed, named for a note, with its order behind the first car (its position).
struct MeasuredSpeed
{
  std::string name;
  const std::vector<double>* speed_mps = nullptr;
  int order = 2;
};

/// How much a car's speed must have risen again after its minimum before the data end, as a share of
/// its dip, for that minimum to be its dip's and not a point on the way down.
constexpr double kCutDipRecoveredShare = 0.25;

/// A window cut by the data's end holds a car's dip whole when the car's speed rose again, by
/// kCutDipRecoveredShare of its dip, after its minimum and before the data end: the cars further
/// back dip later than the first. Sets first_cut_order and cut_note at the first car (in the order
/// given, by its order) that had not; when it is the first given, the perturbation is incomplete.
/// Its predictions are then not scored against a dip that may go on, nor it against them.
void judgeCutWindows(std::vector<Perturbation>& perturbations, const std::vector<double>& time_s,
                     const std::vector<MeasuredSpeed>& cars, const PerturbationCriteria& criteria = {});

/// Whether a car's speed covers the perturbation's window: the perturbation is complete, the
/// window's first and last samples are there, and no hole in it is longer than
/// criteria.max_bridged_hole_s (a hole may hide the minimum, the distance lost or the braking).
bool windowCovered(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                   const Perturbation& perturbation, const PerturbationCriteria& criteria = {});

/// A car's dip in this perturbation: its mean speed over the pre-window minus its minimum within
/// [onset, window_end). NaN when the pre-window has no finite sample or the window is not covered
/// (windowCovered): a dip cut off by the data's end or hidden by a hole is not measured.
double dipDepthMps(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                   const Perturbation& perturbation, const PerturbationCriteria& criteria = {});

/// The distance a car loses in this perturbation against keeping its pre-perturbation speed: the
/// integral over [onset, window_end) of (mean speed over the pre-window - speed) where positive
/// (trapezoids; holes up to criteria.max_bridged_hole_s bridged). It is what the gap behind the
/// car gives up, so a follower's dip follows it as much as the car's own dip: two cars that dip
/// equally deep pass on different dips if one recovers more slowly. NaN when the pre-window has
/// no finite sample or the window is not covered (windowCovered).
double distanceLostM(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                     const Perturbation& perturbation, const PerturbationCriteria& criteria = {});

/// The shape of a car's dip beyond its depth. Rates [m/s^2, both positive]: the steepest falling
/// and rising least-squares slope of its speed over criteria.acceleration_span_s, braking on spans
/// from a span before the onset to the dip's minimum, recovery on spans from the minimum to the
/// window's end; a follower's rates over its leader's say how much of a braking's shape it passes
/// on. Width [s]: how long its speed stays below half its dip (below the mean of its
/// pre-perturbation speed and its minimum; crossings interpolated linearly), the dip's full width
/// at half depth: two dips of one depth lose different distances when one is wider.
/// Each NaN where the window is not covered (windowCovered: the dip may lie outside the data or in
/// a hole), and the width also where the speed is not back above half its dip by the window's end.
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
