#include "acc_identification/diagnosis/effect_selection.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "acc_identification/model/block_bootstrap.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
namespace
{
/// Paired differences a - b, run by run.
SquaredErrorsByRun difference(const SquaredErrorsByRun& a, const SquaredErrorsByRun& b)
{
  SquaredErrorsByRun d(a.size());
  for (std::size_t r = 0; r < a.size(); ++r)
  {
    if (a[r].size() != b[r].size())
    {
      throw std::invalid_argument("held-out errors of two models differ in length");
    }
    d[r].resize(a[r].size());
    for (std::size_t t = 0; t < a[r].size(); ++t)
    {
      d[r][t] = a[r][t] - b[r][t];
    }
  }
  return d;
}


/// Moving-block bootstrap of the means of several paired series at once (the same resampled
/// blocks for all). Returns [resample][series]. Blocks wrap around each run's end (circular), so
/// every sample is equally likely to be drawn.
std::vector<std::vector<double>> bootstrapMeans(const std::vector<SquaredErrorsByRun>& series, std::size_t block,
                                                const SelectionOptions& options)
{
  std::vector<std::size_t> run_lengths;
  for (const std::vector<double>& run : series.front())
  {
    run_lengths.push_back(run.size());
  }
  const MovingBlockBootstrap plan(run_lengths, block, options.resamples, options.seed, BlockPlacement::circular);
  std::vector<std::vector<double>> means(options.resamples, std::vector<double>(series.size(), 0.0));
  for (std::size_t k = 0; k < series.size(); ++k)
  {
    std::vector<double> concatenated;
    for (const std::vector<double>& run : series[k])
    {
      concatenated.insert(concatenated.end(), run.begin(), run.end());
    }
    const std::vector<double> replicates = plan.replicateMeans(concatenated);
    for (std::size_t b = 0; b < replicates.size(); ++b)
    {
      means[b][k] = replicates[b];
    }
  }
  return means;
}


std::vector<double> column(const std::vector<std::vector<double>>& matrix, std::size_t k)
{
  std::vector<double> values;
  for (const auto& row : matrix)
  {
    values.push_back(row[k]);
  }
  return values;
}

ImprovementEstimate estimate(const SquaredErrorsByRun& diff, const std::vector<double>& boot, double level,
                             double base_mse)
{
  ImprovementEstimate e;
  e.mean = meanOf(diff);
  e.relative = base_mse > 0.0 ? e.mean / base_mse : 0.0;
  e.lower_bound = interpolatedQuantile(boot, level);
  e.upper_bound = interpolatedQuantile(boot, 1.0 - level);
  return e;
}
}  // namespace

double familyWiseLevel(const std::vector<std::vector<double>>& resamples, double alpha)
{
  const std::size_t B = resamples.size(), K = resamples.empty() ? 0 : resamples.front().size();
  if (B == 0 || K <= 1)
    return alpha;
  std::vector<double> smallest_rank(B, 1.0);
  for (std::size_t k = 0; k < K; ++k)
  {
    std::vector<double> sorted = column(resamples, k);
    if (!std::all_of(sorted.begin(), sorted.end(), [](double v) { return std::isfinite(v); }))
      continue;  // never named (its bound is not above 0), so it takes no share of alpha
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t b = 0; b < B; ++b)
    {
      // The share of this candidate's resamples at or below this one.
      const auto at_or_below = std::upper_bound(sorted.begin(), sorted.end(), resamples[b][k]) - sorted.begin();
      smallest_rank[b] = std::min(smallest_rank[b], static_cast<double>(at_or_below) / static_cast<double>(B));
    }
  }
  std::sort(smallest_rank.begin(), smallest_rank.end());
  // At most floor(alpha B) minima lie below the floor(alpha B)-th smallest (counting from 0).
  const auto allowed = static_cast<std::size_t>(std::floor(alpha * static_cast<double>(B)));
  const double level = smallest_rank[std::min(allowed, B - 1)];
  return std::clamp(level, alpha / static_cast<double>(K), alpha);
}

double meanOf(const SquaredErrorsByRun& series)
{
  double sum = 0.0;
  std::size_t count = 0;
  for (const auto& run : series)
  {
    for (double value : run)
    {
      sum += value;
    }
    count += run.size();
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

SelectionResult selectEffect(const SquaredErrorsByRun& base, const std::vector<SquaredErrorsByRun>& candidates,
                             const std::vector<EffectKind>& kinds, double sample_period_s,
                             const SelectionOptions& options, const std::vector<bool>& resolvable,
                             double reference_mse)
{
  SelectionResult result;
  result.candidates = kinds;
  const std::size_t K = candidates.size();
  if (K == 0)
  {
    return result;
  }
  const std::size_t block = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::lround(options.block_length_s / std::max(sample_period_s, 1e-9))));
  result.block_length_samples = static_cast<double>(block);
  const double base_mse = reference_mse > 0.0 ? reference_mse : meanOf(base);
  std::vector<SquaredErrorsByRun> diffs;
  for (const SquaredErrorsByRun& c : candidates)
  {
    diffs.push_back(difference(base, c));
  }
  const auto boot = bootstrapMeans(diffs, block, options);
  const double level = familyWiseLevel(boot, options.alpha);
  result.level = level;
  result.family_wise_alpha = options.alpha;
  for (std::size_t k = 0; k < K; ++k)
  {
    result.versus_base.push_back(estimate(diffs[k], column(boot, k), level, base_mse));
    const ImprovementEstimate& e = result.versus_base.back();
    const bool resolved = resolvable.empty() || resolvable[k];
    result.significant.push_back(resolved && e.lower_bound > 0.0 && e.relative >= options.min_relative_improvement);
    result.ranking.push_back(k);
  }
  std::stable_sort(result.ranking.begin(), result.ranking.end(), [&](std::size_t a, std::size_t b) {
    return result.versus_base[a].mean > result.versus_base[b].mean;
  });
  // The best is the significant effect with the largest improvement.
  const auto first_significant = std::find_if(result.ranking.begin(), result.ranking.end(),
                                              [&](std::size_t k) { return result.significant[k]; });
  if (first_significant == result.ranking.end())
  {
    return result;  // nothing is significant: none is reported
  }
  const std::size_t best = *first_significant;
  result.dominant = kinds[best];
  result.plausible.push_back(kinds[best]);
  result.distinguishable = true;
  // Paired comparisons of the best against every other significant effect (the same bootstrap
  // blocks: the difference of two columns is the bootstrap of the difference of the series).
  for (std::size_t rank = 0; rank < K; ++rank)
  {
    const std::size_t j = result.ranking[rank];
    if (j == best || !result.significant[j])
    {
      continue;
    }
    std::vector<double> boot_difference;
    for (const auto& row : boot)
    {
      boot_difference.push_back(row[best] - row[j]);
    }
    const ImprovementEstimate versus =
        estimate(difference(candidates[j], candidates[best]), boot_difference, options.alpha, base_mse);
    if (!result.has_runner_up)
    {
      result.has_runner_up = true;
      result.best_versus_runner_up = versus;
    }
    if (!(versus.lower_bound > 0.0))
    {
      result.plausible.push_back(kinds[j]);
      result.distinguishable = false;
    }
  }
  return result;
}

std::string describeSelectionRule(const SelectionOptions& options, std::size_t candidates)
{
  char text[2048];
  std::snprintf(text, sizeof text,
                "Held-out paired squared speed errors d_k(t) = e_base(t)^2 - e_k(t)^2; moving-block bootstrap "
                "(%g s blocks, %zu resamples, within runs, the same blocks for every effect). An effect is "
                "significant when the one-sided lower bound of its mean improvement is above 0 at the level that "
                "holds the family-wise error rate over the %zu effects at alpha %g under the bootstrap's joint "
                "distribution (Westfall-Young minP on the resamples' ranks; between %.4g%% and %g%%: the effects' "
                "improvements move together), the improvement is at least %g%% of the base model's held-out MSE, and "
                "its magnitude is resolvable (a lag, delay or clock offset of at least one sample period). "
                "The dominant effect is the significant one with the largest improvement (none if none is); "
                "another significant effect is indistinguishable from it when the one-sided %g%% lower bound of "
                "their paired difference is not above 0.",
                options.block_length_s, options.resamples, candidates, options.alpha,
                100.0 * options.alpha / static_cast<double>(candidates), 100.0 * options.alpha,
                100.0 * options.min_relative_improvement, 100.0 * (1.0 - options.alpha));
  return text;
}

}  // namespace acc
