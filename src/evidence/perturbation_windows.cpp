#include "acc_identification/evidence/perturbation_windows.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace acc
{
WindowRows perturbationWindowRows(const std::vector<double>& time_s, const Perturbation& perturbation,
                                  const PerturbationCriteria& criteria)
{
  std::size_t r = perturbation.onset;
  while (r > 0 && std::isfinite(time_s[r - 1]) && time_s[r - 1] >= time_s[perturbation.onset] - criteria.pre_window_s)
    --r;
  return {r, perturbation.window_end};
}

std::vector<bool> insidePerturbationWindows(const std::vector<double>& time_s, const std::vector<double>& lead_speed_mps,
                                            const PerturbationCriteria& criteria)
{
  std::vector<bool> inside(time_s.size(), false);
  for (const Perturbation& perturbation : findPerturbations(time_s, lead_speed_mps, criteria))
  {
    const WindowRows rows = perturbationWindowRows(time_s, perturbation, criteria);
    for (std::size_t r = rows.first; r < rows.end && r < inside.size(); ++r)
      inside[r] = true;
  }
  return inside;
}

double perturbationWindowMse(const std::vector<double>& time_s, const std::vector<double>& predicted_mps,
                             const std::vector<double>& measured_mps, const Perturbation& perturbation,
                             const PerturbationCriteria& criteria)
{
  double sum = 0.0;
  std::size_t n = 0;
  const WindowRows rows = perturbationWindowRows(time_s, perturbation, criteria);
  for (std::size_t r = rows.first; r < rows.end && r < predicted_mps.size() && r < measured_mps.size(); ++r)
  {
    if (std::isfinite(predicted_mps[r]) && std::isfinite(measured_mps[r]))
    {
      sum += (predicted_mps[r] - measured_mps[r]) * (predicted_mps[r] - measured_mps[r]);
      ++n;
    }
  }
  return n > 0 ? sum / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

PairedLossComparison pairedLossMeans(const std::vector<LossCluster>& clusters)
{
  PairedLossComparison out;
  out.clusters = clusters.size();
  double sum_against = 0.0, sum_candidate = 0.0;
  for (const LossCluster& c : clusters)
  {
    sum_against += c.against;
    sum_candidate += c.candidate;
    out.entries += c.n;
  }
  if (out.entries == 0)
    return out;
  out.against_loss = sum_against / static_cast<double>(out.entries);
  out.candidate_loss = sum_candidate / static_cast<double>(out.entries);
  out.relative_improvement =
      out.against_loss > 0.0 ? 1.0 - out.candidate_loss / out.against_loss : std::numeric_limits<double>::quiet_NaN();
  return out;
}

PairedLossComparison comparePairedLosses(const std::vector<LossCluster>& clusters, std::size_t replicates,
                                         std::uint64_t seed)
{
  PairedLossComparison out = pairedLossMeans(clusters);
  if (out.entries == 0)
    return out;
  const ClusteredDifferences differences = differencesOf(clusters);
  out.p_value = wildClusterTest(differences.sums, differences.sizes, replicates, seed).p_value;
  return out;
}

ClusteredDifferences differencesOf(const std::vector<LossCluster>& clusters, const std::vector<std::size_t>& numbers)
{
  if (!numbers.empty() && numbers.size() != clusters.size())
    throw std::invalid_argument("differencesOf: " + std::to_string(numbers.size()) + " cluster numbers for " +
                                std::to_string(clusters.size()) + " clusters");
  ClusteredDifferences out;
  for (std::size_t g = 0; g < clusters.size(); ++g)
  {
    out.clusters.push_back(numbers.empty() ? g : numbers[g]);
    out.sums.push_back(clusters[g].against - clusters[g].candidate);
    out.sizes.push_back(clusters[g].n);
  }
  return out;
}

}  // namespace acc
