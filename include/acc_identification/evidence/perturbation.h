#pragma once

#include <cstddef>
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

/// The median of the finite values (NaN when none).
double finiteMedian(std::vector<double> values);

}  // namespace acc
