#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/evidence/wild_cluster_bootstrap.h"

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
  /// The wild cluster bootstrap-t's p of "no improvement" (wildClusterTest), this comparison alone;
  /// 1 with fewer than two clusters or no replicates.
  double p_value = 1.0;
};

/// Means and relative improvement, p_value left at 1: for a member of a family, whose p (alone and
/// within the family) comes from wildClusterMaxT over differencesOf.
PairedLossComparison pairedLossMeans(const std::vector<LossCluster>& clusters);

/// pairedLossMeans and the wild cluster bootstrap-t's p of this comparison alone (`replicates`
/// replicates from `seed`).
PairedLossComparison comparePairedLosses(const std::vector<LossCluster>& clusters, std::size_t replicates,
                                         std::uint64_t seed);

/// The clusters' summed differences (against - candidate) and sizes. Cluster g is numbered
/// numbers[g] of a family's numbering, or g when numbers is empty.
ClusteredDifferences differencesOf(const std::vector<LossCluster>& clusters,
                                   const std::vector<std::size_t>& numbers = {});

/// The naming rule both perturbation judges state (campaign's platoon diagnosis, diagnose's window
/// criterion): the candidate's family-wise p (wildClusterMaxT over the candidates compared) at most
/// alpha and a mean loss at least min_relative_improvement below the reference's.
inline bool namedByRule(const PairedLossComparison& comparison, double family_p_value, double alpha,
                        double min_relative_improvement)
{
  return family_p_value <= alpha && comparison.relative_improvement >= min_relative_improvement;
}

}  // namespace acc
