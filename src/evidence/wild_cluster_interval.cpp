#include "acc_identification/evidence/wild_cluster_interval.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/evidence/wild_cluster_bootstrap.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Bisection stops when an end is known to 1e-4 of the ratio (of 1e-4 for ratios under 1).
constexpr double kRatioTolerance = 1e-4;
/// Steps out from the estimate towards an infinite bound: 2^40 times the estimate is as far as a
/// ratio of dips or rates can mean anything.
constexpr int kMaxDoublings = 40;

void checkConfidence(double confidence)
{
  if (!(confidence > 0.0 && confidence < 1.0))
    throw std::invalid_argument("wild cluster interval: the confidence must lie in (0, 1)");
}

/// Whether the one-sided test "the mean per entry is not positive" rejects at `tail`.
bool rejectsPositive(const std::vector<double>& sums, const std::vector<std::size_t>& sizes, double tail,
                     std::size_t replicates, std::uint64_t seed)
{
  return wildClusterTest(sums, sizes, replicates, seed).p_value <= tail;
}

/// The clusters' finite values, the clusters without one left out.
std::vector<std::vector<double>> finiteClusters(const std::vector<std::vector<double>>& clusters)
{
  std::vector<std::vector<double>> out;
  for (const std::vector<double>& cluster : clusters)
  {
    std::vector<double> finite;
    std::copy_if(cluster.begin(), cluster.end(), std::back_inserter(finite), [](double v) { return std::isfinite(v); });
    if (!finite.empty())
      out.push_back(std::move(finite));
  }
  return out;
}

/// Whether median m is rejected as too small (`below`: significantly fewer than half the values lie
/// at or below it) or as too large (significantly fewer than half lie at or above it).
bool medianRejected(const std::vector<std::vector<double>>& clusters, const std::vector<std::size_t>& sizes, double m,
                    bool below, double tail, std::size_t replicates, std::uint64_t seed)
{
  std::vector<double> half_minus_count;
  for (const std::vector<double>& cluster : clusters)
  {
    const auto counted = std::count_if(cluster.begin(), cluster.end(),
                                       [m, below](double v) { return below ? v <= m : v >= m; });
    half_minus_count.push_back(0.5 * static_cast<double>(cluster.size()) - static_cast<double>(counted));
  }
  return rejectsPositive(half_minus_count, sizes, tail, replicates, seed);
}

/// Whether ratio r is rejected as too small (the numerators significantly above r denominators)
/// or, for `!too_small`, as too large.
bool ratioRejected(const std::vector<RatioCluster>& clusters, const std::vector<std::size_t>& sizes, double r,
                   bool too_small, double tail, std::size_t replicates, std::uint64_t seed)
{
  std::vector<double> excess;
  for (const RatioCluster& c : clusters)
    excess.push_back(too_small ? c.numerator - r * c.denominator : r * c.denominator - c.numerator);
  return rejectsPositive(excess, sizes, tail, replicates, seed);
}

/// The end of the accepted ratios between `accepted` and the rejected `outside` (bisection to
/// `tolerance`).
template <typename Rejected>
double bisectEnd(double accepted, double outside, double tolerance, Rejected rejected)
{
  double inside = accepted;
  while (std::abs(outside - inside) > tolerance)
  {
    const double middle = 0.5 * (inside + outside);
    (rejected(middle) ? outside : inside) = middle;
  }
  return inside;
}

/// The end of the accepted ratios from the estimate towards `bound`: `bound` itself when it is
/// not rejected. Towards an infinite bound, the test far out is the test of the denominators
/// alone (r d - n over |r| tends to d, and the t statistic does not see the scale), so
/// `far_rejected` says whether any finite end exists; the search then doubles its step until a
/// ratio is rejected and bisects back (kMaxDoublings, beyond which the end is taken as infinite).
template <typename Rejected>
double ratioEnd(double estimate, double bound, bool far_rejected, double tolerance, Rejected rejected)
{
  if (std::isfinite(bound))
    return rejected(bound) ? bisectEnd(estimate, bound, tolerance, rejected) : bound;
  if (!far_rejected)
    return bound;
  const double direction = bound > 0.0 ? 1.0 : -1.0;
  double accepted = estimate;
  double step = std::max(1.0, std::abs(estimate));
  for (int doubling = 0; doubling < kMaxDoublings; ++doubling, step *= 2.0)
  {
    const double trial = estimate + direction * step;
    if (rejected(trial))
      return bisectEnd(accepted, trial, tolerance, rejected);
    accepted = trial;
  }
  return bound;
}

/// The clusters with a positive denominator and at least one observation, their sizes, and
/// whether every one shows the same ratio.
struct HeldClusters
{
  std::vector<RatioCluster> clusters;
  std::vector<std::size_t> sizes;
  double numerator = 0.0, denominator = 0.0;
  bool same_ratio = true;
};

HeldClusters heldClusters(const std::vector<RatioCluster>& clusters)
{
  HeldClusters held;
  for (const RatioCluster& c : clusters)
  {
    if (!(c.denominator > 0.0) || c.n == 0)
      continue;
    if (!held.clusters.empty())
      held.same_ratio = held.same_ratio && c.numerator * held.clusters.front().denominator ==
                                               held.clusters.front().numerator * c.denominator;
    held.clusters.push_back(c);
    held.sizes.push_back(c.n);
    held.numerator += c.numerator;
    held.denominator += c.denominator;
  }
  return held;
}

/// The ratios within [lowest, highest] that the equal-tailed test does not reject.
std::pair<double, double> invertRatioTest(const std::vector<RatioCluster>& clusters, double lowest, double highest,
                                          double confidence, std::size_t replicates, std::uint64_t seed)
{
  checkConfidence(confidence);
  const HeldClusters held = heldClusters(clusters);
  // Clusters that all show the same ratio (every trial a success, say) have no spread to weigh:
  // every other ratio would be rejected as certainly false, which a handful of clusters cannot say.
  if (held.clusters.size() < 2 || held.same_ratio)
    return {kNaN, kNaN};
  const double tail = 0.5 * (1.0 - confidence), ratio = held.numerator / held.denominator;
  const double tolerance = kRatioTolerance * std::max(1.0, std::abs(ratio));
  std::vector<double> denominators;
  for (const RatioCluster& c : held.clusters)
    denominators.push_back(c.denominator);
  const bool far_rejected = rejectsPositive(denominators, held.sizes, tail, replicates, seed);
  // Below the ratio only "too small" can reject, above it only "too large".
  const auto too_small = [&](double r) { return ratioRejected(held.clusters, held.sizes, r, true, tail, replicates, seed); };
  const auto too_large = [&](double r) { return ratioRejected(held.clusters, held.sizes, r, false, tail, replicates, seed); };
  return {ratioEnd(ratio, lowest, far_rejected, tolerance, too_small),
          ratioEnd(ratio, highest, far_rejected, tolerance, too_large)};
}
}  // namespace

std::pair<double, double> wildClusterMedianInterval(const std::vector<std::vector<double>>& clusters,
                                                    double confidence, std::size_t replicates, std::uint64_t seed)
{
  checkConfidence(confidence);
  const std::vector<std::vector<double>> finite = finiteClusters(clusters);
  if (finite.size() < 2)
    return {kNaN, kNaN};
  std::vector<std::size_t> sizes;
  std::vector<double> values;
  for (const std::vector<double>& cluster : finite)
  {
    sizes.push_back(cluster.size());
    values.insert(values.end(), cluster.begin(), cluster.end());
  }
  const double median = finiteMedian(values);
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  // Walk out from the median to the first value rejected on each side. Below the median at least
  // half the values lie at or above any m, so only "too small" can reject there; above, only "too
  // large".
  const double tail = 0.5 * (1.0 - confidence);
  const auto first_above = std::upper_bound(values.begin(), values.end(), median);
  double lower = kNaN, upper = kNaN;
  for (auto it = first_above; it != values.begin();)
  {
    --it;
    if (medianRejected(finite, sizes, *it, true, tail, replicates, seed))
      break;
    lower = *it;
  }
  for (auto it = std::lower_bound(values.begin(), values.end(), median); it != values.end(); ++it)
  {
    if (medianRejected(finite, sizes, *it, false, tail, replicates, seed))
      break;
    upper = *it;
  }
  return {lower, upper};
}

std::pair<double, double> wildClusterShareInterval(const std::vector<RatioCluster>& clusters, double confidence,
                                                   std::size_t replicates, std::uint64_t seed)
{
  for (const RatioCluster& c : clusters)
    if (!(c.numerator >= 0.0 && c.numerator <= c.denominator))
      throw std::invalid_argument("wild cluster share interval: a cluster's successes must lie within [0, trials]");
  return invertRatioTest(clusters, 0.0, 1.0, confidence, replicates, seed);
}

std::pair<double, double> wildClusterRatioInterval(const std::vector<RatioCluster>& clusters, double confidence,
                                                   std::size_t replicates, std::uint64_t seed,
                                                   RatioNumerators numerators)
{
  bool nonnegative = numerators == RatioNumerators::amounts;
  for (const RatioCluster& c : clusters)
  {
    if (!(c.denominator > 0.0) || !std::isfinite(c.numerator))
      throw std::invalid_argument("wild cluster ratio interval: every cluster needs a finite numerator and a positive "
                                  "denominator");
    nonnegative = nonnegative && c.numerator >= 0.0;
  }
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  return invertRatioTest(clusters, nonnegative ? 0.0 : -kInfinity, kInfinity, confidence, replicates, seed);
}

}  // namespace acc
