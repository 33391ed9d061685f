#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// The statistical rule that decides which effect the held-out data support.
///
/// For each candidate k and each held-out sample t, d_k(t) = e_base(t)^2 - e_k(t)^2 (squared
/// speed errors of the base and the augmented model). The improvement is the mean of d_k. Its
/// sampling distribution is estimated by a moving-block bootstrap (blocks of block_length_s,
/// drawn within each run so that every run keeps its length; the same blocks for every
/// candidate, so the comparisons are paired), which keeps the seconds-long correlation of model
/// errors that an i.i.d. bootstrap would destroy.
///  - k is significant when the one-sided lower confidence bound of its improvement is above 0 at
///    the level that holds the family-wise error rate over the K candidates at alpha
///    (familyWiseLevel below, between Bonferroni's alpha / K and alpha), and the improvement is at
///    least min_relative_improvement of the base model's held-out MSE (a gain too small to matter
///    is not reported as a missing effect);
///  - an effect whose fitted magnitude the data cannot resolve (resolvable[k] false; e.g. a lag,
///    delay or clock offset shorter than one sample period) is never significant;
///  - the best effect is the significant one with the largest improvement; none if none is;
///  - another significant effect j cannot be told apart from the best b when the lower bound
///    (level alpha) of the mean of e_j^2 - e_b^2 is not above 0. The plausible set is b and all such j.
struct SelectionOptions
{
  double block_length_s = 10.0;
  std::size_t resamples = 2000;
  double alpha = 0.05;
  double min_relative_improvement = 0.02;
  std::uint32_t seed = 12345;
};

/// The per-candidate level of one-sided percentile lower bounds that holds the family-wise error
/// rate at alpha under the bootstrap's joint distribution (Westfall and Young's minP, on the
/// resamples' ranks): each resample's smallest rank over the candidates, each rank taken within
/// its own candidate's resamples, and the largest level that at most alpha of those minima fall
/// below. resamples: [resample][candidate]. The candidates' fits share the base model and the same
/// held-out errors, so their improvements move together (a delay, a lag and a clock offset
/// nearly one for one): the level then lies well above Bonferroni's alpha / K, which holds for
/// independent candidates, and reaches alpha for identical ones. Never below alpha / K.
double familyWiseLevel(const std::vector<std::vector<double>>& resamples, double alpha);

/// Held-out squared speed errors of one model, one vector per run (same lengths for every model).
using SquaredErrorsByRun = std::vector<std::vector<double>>;

/// The mean over every sample of every run (0 when there is none).
double meanOf(const SquaredErrorsByRun& series);

/// Mean of a paired difference and its bootstrap lower bounds.
struct ImprovementEstimate
{
  double mean = 0.0;             ///< mean over all held-out samples [m^2/s^2]
  double relative = 0.0;         ///< mean / base MSE
  double lower_bound = 0.0;      ///< one-sided lower bound at the level used by the rule
  double upper_bound = 0.0;      ///< the matching upper bound (two-sided interval, for reports)
};

struct SelectionResult
{
  std::vector<EffectKind> candidates;          ///< as given
  std::vector<ImprovementEstimate> versus_base;  ///< per candidate, at the family-wise level
  /// The one-sided level of each candidate's bound against the base: familyWiseLevel of the
  /// candidates' resampled improvements (alpha with one candidate).
  double level = 0.0;
  double family_wise_alpha = 0.0;  ///< the options' alpha, which `level` holds over the candidates
  std::vector<bool> significant;
  std::vector<std::size_t> ranking;            ///< candidate indices, largest improvement first
  EffectKind dominant = EffectKind::none;
  std::vector<EffectKind> plausible;           ///< empty when dominant is none
  /// Best minus runner-up (the next significant effect): mean and lower bound at level alpha.
  ImprovementEstimate best_versus_runner_up;
  bool has_runner_up = false;
  bool distinguishable = false;                ///< the best is significantly better than every other
  double block_length_samples = 0.0;
};

/// Applies the rule. base and each candidates' errors must have the same run structure.
/// sample_period_s converts the block length to samples. resolvable: one flag per candidate
/// (empty: all resolvable). reference_mse: the MSE that `relative` and the practical threshold
/// refer to; 0 (default) means base's own. Forward selection passes the current model as base
/// and leaves this 0: each step must remove a share of what the current model still gets wrong
/// (measured against the base model's MSE, an effect that explains most of the gap, such as a
/// set speed, left every second effect below the threshold, however large against the rest).
SelectionResult selectEffect(const SquaredErrorsByRun& base, const std::vector<SquaredErrorsByRun>& candidates,
                             const std::vector<EffectKind>& kinds, double sample_period_s,
                             const SelectionOptions& options, const std::vector<bool>& resolvable = {},
                             double reference_mse = 0.0);

/// The rule in one paragraph, for reports.
std::string describeSelectionRule(const SelectionOptions& options, std::size_t candidates);

}  // namespace acc
