#include "acc_identification/diagnosis/perturbation_window_criterion.h"

#include <cmath>

#include "acc_identification/model/number_text.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
namespace
{
/// The window MSE of one held-out simulation in one perturbation.
double windowLoss(const CarFollowingRun& run, const SimulatedFollower& sim, const Perturbation& perturbation,
                  const PerturbationCriteria& criteria)
{
  if (sim.diverged && sim.diverged_at_index < perturbation.window_end)
    return kDivergenceBound * kDivergenceBound;
  return perturbationWindowMse(run.time_s, sim.speed_mps, run.follower_speed_mps, perturbation, criteria);
}

/// Every model's window losses: losses[m][i] for model m (0: base) in scored perturbation i.
std::vector<std::vector<double>> windowLosses(const std::vector<CarFollowingRun>& held_out,
                                              const std::vector<const std::vector<SimulatedFollower>*>& models,
                                              const PerturbationCriteria& criteria)
{
  std::vector<std::vector<double>> losses(models.size());
  for (std::size_t r = 0; r < held_out.size(); ++r)
  {
    const CarFollowingRun& run = held_out[r];
    for (const Perturbation& perturbation : findPerturbations(run.time_s, run.leader_speed_mps, criteria))
    {
      std::vector<double> row;
      bool scored = true;
      for (const std::vector<SimulatedFollower>* sims : models)
      {
        row.push_back(r < sims->size() ? windowLoss(run, (*sims)[r], perturbation, criteria)
                                       : std::numeric_limits<double>::quiet_NaN());
        scored = scored && std::isfinite(row.back());
      }
      for (std::size_t m = 0; scored && m < models.size(); ++m)
        losses[m].push_back(row[m]);
    }
  }
  return losses;
}

/// The root of the mean window MSE; NaN without a window (rootMeanOf would say 0).
double rootMean(const std::vector<double>& window_mse)
{
  return window_mse.empty() ? std::numeric_limits<double>::quiet_NaN() : rootMeanOf(window_mse);
}
}  // namespace

PerturbationWindowCriterion judgeOnPerturbationWindows(const std::vector<CarFollowingRun>& held_out,
                                                       const std::vector<SimulatedFollower>& base,
                                                       const std::vector<HeldOutPredictions>& effects,
                                                       const PerturbationWindowOptions& options)
{
  PerturbationWindowCriterion out;
  out.rule = perturbationWindowRule(options, effects.size());
  std::vector<const std::vector<SimulatedFollower>*> models{&base};
  for (const HeldOutPredictions& effect : effects)
    models.push_back(effect.second);
  const std::vector<std::vector<double>> losses = windowLosses(held_out, models, options.perturbation);
  out.perturbations = losses[0].size();
  out.base_window_rmse_speed_mps = rootMean(losses[0]);
  if (out.perturbations < 2)
    out.reason = "the leaders perturb " + std::to_string(out.perturbations) +
                 " time(s) in the held-out parts: at least 2 perturbations are needed to compare models on them";
  // Every effect against the base model on the same perturbations: one family, its level held by
  // the joint max-t of the wild cluster bootstrap.
  std::vector<ClusteredDifferences> family;
  for (std::size_t e = 0; e < effects.size(); ++e)
  {
    PerturbationWindowScore score;
    score.effect = effects[e].first;
    score.window_rmse_speed_mps = rootMean(losses[e + 1]);
    std::vector<LossCluster> clusters;
    for (std::size_t i = 0; i < out.perturbations; ++i)
      clusters.push_back({losses[0][i], losses[e + 1][i], 1});
    score.versus_base = pairedLossMeans(clusters);
    family.push_back(differencesOf(clusters));
    out.effects.push_back(score);
  }
  const std::vector<WildClusterTest> tests = wildClusterMaxT(family, out.perturbations, options.replicates, options.seed);
  double best_loss = std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < out.effects.size(); ++e)
  {
    PerturbationWindowScore& score = out.effects[e];
    score.versus_base.p_value = tests[e].p_value;
    score.family_p_value = tests[e].family_p_value;
    score.significant = out.perturbations >= 2 && namedByRule(score.versus_base, score.family_p_value, options.alpha,
                                                               options.min_relative_improvement);
    if (score.significant && score.versus_base.candidate_loss < best_loss)
    {
      best_loss = score.versus_base.candidate_loss;
      out.named = score.effect;
    }
  }
  return out;
}

std::string perturbationWindowRule(const PerturbationWindowOptions& options, std::size_t candidates)
{
  return "on the held-out parts, each leader perturbation's window (" + significant(options.perturbation.pre_window_s) +
         " s before its onset to " + significant(options.perturbation.extension_s) +
         " s after its recovery) is scored by each model's speed MSE; an effect is named when its mean window MSE is at "
         "least " + significant(100.0 * options.min_relative_improvement) +
         " % below the base model's and the wild cluster bootstrap-t over perturbations (Webb weights, every "
         "pattern visited with up to seven perturbations, else " +
         std::to_string(options.replicates) + " drawn; the max-t over the " +
         std::to_string(candidates) + " effects) gives a family-wise p <= " + significant(options.alpha) +
         "; the lowest window MSE among the named wins";
}

}  // namespace acc
