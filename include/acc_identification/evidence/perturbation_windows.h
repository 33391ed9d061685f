#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "acc_identification/evidence/perturbation.h"

namespace acc
{
// Judging models where it matters: inside the leader's perturbations. Whole-run speed MSE barely
// sees a 3-second braking; these pieces score a prediction over each perturbation's window and
// compare two models paired over perturbations, for the campaign's platoon diagnosis and for
// diagnose's pair-level criterion alike.

/// The rows [first, end) of a perturbation's window: from criteria.pre_window_s before the onset
/// (or the run's start) to one past the dip window's last sample.
struct WindowRows
{
  std::size_t first = 0;
  std::size_t end = 0;
};
WindowRows perturbationWindowRows(const std::vector<double>& time_s, const Perturbation& perturbation,
                                  const PerturbationCriteria& criteria = {});

/// Per sample of a run: whether it lies in the window of one of its leader's perturbations
/// (findPerturbations on lead_speed_mps), the samples a braking decides.
std::vector<bool> insidePerturbationWindows(const std::vector<double>& time_s, const std::vector<double>& lead_speed_mps,
                                            const PerturbationCriteria& criteria = {});

/// The mean squared difference of predicted and measured speed over a perturbation's window,
/// [onset - criteria.pre_window_s, window_end), over the samples where both are finite [m^2/s^2];
/// NaN when there is none. time_s is the run's clock (increasing; NaN samples are skipped).
double perturbationWindowMse(const std::vector<double>& time_s, const std::vector<double>& predicted_mps,
                             const std::vector<double>& measured_mps, const Perturbation& perturbation,
                             const PerturbationCriteria& criteria = {});

/// Two models' summed losses over one cluster of scores that share an input: a perturbation
/// (every car of it in a platoon, or the one follower of a pair).
struct LossCluster
{
  double against = 0.0;    ///< the reference model's summed loss
  double candidate = 0.0;  ///< the candidate's
  std::size_t n = 0;       ///< scores summed
};

/// A candidate against a reference model, paired over clusters.
struct PairedLossComparison
{
  std::size_t clusters = 0;
  std::size_t entries = 0;  ///< scores over all clusters
  double against_loss = std::numeric_limits<double>::quiet_NaN();    ///< mean over the scores
  double candidate_loss = std::numeric_limits<double>::quiet_NaN();
  double relative_improvement = std::numeric_limits<double>::quiet_NaN();  ///< 1 - candidate / against
  /// Share of cluster-bootstrap replicates whose mean loss difference (against - candidate) is
  /// not positive, (1 + count) / (replicates + 1): the percentile test of "no improvement". 1 with
  /// fewer than two clusters or no replicates. Too small with few clusters: see small_sample_p_value.
  double p_value = 1.0;
  /// The same hypothesis by the wild cluster bootstrap-t (wildClusterBootstrapP, as many replicates
  /// and the same seed), which keeps its level with few clusters; reported beside p_value.
  double small_sample_p_value = 1.0;
};

/// Means, relative improvement and the cluster-bootstrap p-value (clusters resampled with
/// replacement `replicates` times by uniformBelow from std::mt19937_64(seed): bit for bit the same
/// with every standard library), and the wild cluster bootstrap-t's beside.
PairedLossComparison comparePairedLosses(const std::vector<LossCluster>& clusters, std::size_t replicates,
                                         std::uint64_t seed);

/// The naming rule both perturbation judges state (campaign's platoon diagnosis, diagnose's window
/// criterion): p at most alpha divided by the candidates compared (Bonferroni) and a mean loss at
/// least min_relative_improvement below the reference's.
inline bool namedByRule(const PairedLossComparison& comparison, double alpha, std::size_t candidates,
                        double min_relative_improvement)
{
  return comparison.p_value <= alpha / static_cast<double>(candidates) &&
         comparison.relative_improvement >= min_relative_improvement;
}

}  // namespace acc
