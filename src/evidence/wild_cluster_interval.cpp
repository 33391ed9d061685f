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
constexpr double kShareTolerance = 1e-4;

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

/// Whether share s is rejected as too small (the successes significantly above s trials) or, for
/// `!too_small`, as too large.
bool shareRejected(const std::vector<RatioCluster>& clusters, const std::vector<std::size_t>& sizes, double s,
                   bool too_small, double tail, std::size_t replicates, std::uint64_t seed)
{
  std::vector<double> excess;
  for (const RatioCluster& c : clusters)
    excess.push_back(too_small ? c.numerator - s * c.denominator : s * c.denominator - c.numerator);
  return rejectsPositive(excess, sizes, tail, replicates, seed);
}

/// The end of the accepted shares between `accepted` and `bound` (bisection; `bound` itself when
/// it is not rejected).
template <typename Rejected>
double shareEnd(double accepted, double bound, Rejected rejected)
{
  if (!rejected(bound))
    return bound;
  double inside = accepted, outside = bound;
  while (std::abs(outside - inside) > kShareTolerance)
  {
    const double middle = 0.5 * (inside + outside);
    (rejected(middle) ? outside : inside) = middle;
  }
  return inside;
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
  checkConfidence(confidence);
  std::vector<RatioCluster> held;
  std::vector<std::size_t> sizes;
  double successes = 0.0, trials = 0.0;
  for (const RatioCluster& c : clusters)
  {
    if (!(c.numerator >= 0.0 && c.numerator <= c.denominator))
      throw std::invalid_argument("wild cluster share interval: a cluster's successes must lie within [0, trials]");
    if (c.denominator <= 0.0 || c.n == 0)
      continue;
    held.push_back(c);
    sizes.push_back(c.n);
    successes += c.numerator;
    trials += c.denominator;
  }
  // Clusters that all show the same share (every trial a success, say) have no spread to weigh:
  // every other share would be rejected as certainly false, which six links cannot say.
  const bool same_share = std::all_of(held.begin(), held.end(), [&](const RatioCluster& c) {
    return c.numerator * held.front().denominator == held.front().numerator * c.denominator;
  });
  if (held.size() < 2 || same_share)
    return {kNaN, kNaN};
  const double tail = 0.5 * (1.0 - confidence), share = successes / trials;
  // Below the share only "too small" can reject, above it only "too large".
  const auto too_small = [&](double s) { return shareRejected(held, sizes, s, true, tail, replicates, seed); };
  const auto too_large = [&](double s) { return shareRejected(held, sizes, s, false, tail, replicates, seed); };
  return {shareEnd(share, 0.0, too_small), shareEnd(share, 1.0, too_large)};
}

}  // namespace acc
