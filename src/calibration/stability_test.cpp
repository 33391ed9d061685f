#include "acc_identification/calibration/stability_test.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include "acc_identification/model/block_bootstrap.h"
#include "acc_identification/calibration/calibration_report.h"
#include "acc_identification/calibration/fit_statistics.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Margins closer than this count as the same profile point (the boundary fits sit a few ulps
/// above 0).
constexpr double kSameMargin = 1e-9;

double rms(const std::vector<double>& x)
{
  double sum = 0.0;
  for (double value : x)
  {
    sum += value * value;
  }
  return x.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(x.size()));
}

/// a^2 - b^2 term by term.
std::vector<double> squaredErrorDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  std::vector<double> d(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    d[i] = a[i] * a[i] - b[i] * b[i];
  }
  return d;
}

double mean(const std::vector<double>& x)
{
  double sum = 0.0;
  for (double value : x)
  {
    sum += value;
  }
  return x.empty() ? 0.0 : sum / static_cast<double>(x.size());
}

std::string formatNumber(double value, int precision = 4)
{
  std::ostringstream out;
  out.precision(precision);
  out << value;
  return out.str();
}

/// A profile point's fit, before its held-out scoring.
struct ProfileFit
{
  double margin = 0.0;
  AccParameters parameters;
  double train_mse = kInfinity;
  bool fitted = false;
};

/// [margin_low, margin_high] from the allowed profile points (sorted by margin), and its note;
/// fits with k1 <= k1_near_zero are pointed out (without spacing feedback the margin is moot).
void spanAllowedMargins(StabilityTestResult& result, double least, double largest, double k1_near_zero,
                        double alpha)
{
  const std::vector<MarginProfilePoint>& points = result.margin_profile;
  double low = kInfinity, high = -kInfinity;
  bool allowed_without_spacing_gain = false;
  for (const MarginProfilePoint& point : points)
  {
    if (point.allowed)
    {
      low = std::min(low, point.margin);
      high = std::max(high, point.margin);
      allowed_without_spacing_gain =
          allowed_without_spacing_gain || point.parameters.k1_per_s2 <= k1_near_zero;
    }
  }
  std::ostringstream note;
  note << "margins m0 whose best training fit (m = m0) predicts the held-out data not significantly worse "
          "(one-sided, alpha "
       << alpha << ") than the better side fit; " << points.size() << " margins tried";
  result.margin_low = low;
  result.margin_high = high;
  if (points.front().allowed)
  {
    if (points.front().margin <= least + kSameMargin)
    {
      result.margin_low = least;
      note << "; the low end is the least margin within the bounds (" << least << ")";
    }
    else
    {
      result.margin_low = -kInfinity;
      note << "; open below (-inf): the least margin tried (" << points.front().margin << ") is still allowed";
    }
  }
  if (points.back().allowed)
  {
    if (points.back().margin >= largest - kSameMargin)
    {
      result.margin_high = largest;
      note << "; the high end is the largest margin within the bounds (" << largest << ")";
    }
    else
    {
      result.margin_high = kInfinity;
      note << "; open above (+inf): the largest margin tried (" << points.back().margin << ") is still allowed";
    }
  }
  note << "; each true end lies between the end reported and the next margin tried beyond it";
  if (allowed_without_spacing_gain)
  {
    note << "; some allowed fits have k1 near 0 (no spacing feedback), where tau_e and so the margin hardly change "
            "the fit";
  }
  result.margin_interval_note = note.str();
}

/// The verdict from the two p-values and the interval, with its reason.
std::string decideVerdict(StabilityTestResult& result, double alpha)
{
  const double D = result.mean_squared_error_difference;
  std::ostringstream why;
  why << "held-out speed RMSE best stable " << formatNumber(result.best_stable.test_rmse_speed_mps)
      << " m/s (m = " << formatNumber(result.best_stable.margin) << "), best unstable "
      << formatNumber(result.best_unstable.test_rmse_speed_mps) << " m/s (m = "
      << formatNumber(result.best_unstable.margin) << "), mean paired squared-error difference " << formatNumber(D)
      << " m^2/s^2 over " << result.held_out_samples << " samples; p(stable rejected) = "
      << formatNumber(result.p_value_stable_rejected)
      << ", p(unstable rejected) = " << formatNumber(result.p_value_unstable_rejected) << " (moving-block bootstrap, "
      << result.bootstrap_replicates << " replicates, blocks of " << formatNumber(result.block_length_s) << " s)";
  const bool reject_stable = result.p_value_stable_rejected <= alpha;
  const bool reject_unstable = result.p_value_unstable_rejected <= alpha;
  if (reject_stable && result.margin_high < -kSameMargin)
  {
    result.verdict = StabilityVerdict::Unstable;
    result.p_value = result.p_value_stable_rejected;
    why << ": the data reject string stability; allowed margins [" << formatNumber(result.margin_low) << ", "
        << formatNumber(result.margin_high) << "]";
  }
  else if (reject_unstable && result.margin_low > kSameMargin)
  {
    result.verdict = StabilityVerdict::Stable;
    result.p_value = result.p_value_unstable_rejected;
    why << ": the data reject string instability; allowed margins [" << formatNumber(result.margin_low) << ", "
        << formatNumber(result.margin_high) << "]";
  }
  else
  {
    result.verdict = StabilityVerdict::Undecided;
    result.p_value = std::min(result.p_value_stable_rejected, result.p_value_unstable_rejected);
    if (reject_stable || reject_unstable)
    {
      why << ": the paired test rejects " << (reject_stable ? "stability" : "instability")
          << ", but the held-out data still allow margins on both sides of 0 or on the boundary (allowed ["
          << formatNumber(result.margin_low) << ", " << formatNumber(result.margin_high)
          << "]): a model at or across m = 0 predicts as well";
    }
    else
    {
      why << ": neither model predicts the held-out data significantly better (alpha " << alpha << ")";
    }
  }
  return why.str();
}

}  // namespace

std::vector<double> StabilityTestOptions::defaultMarginGrid()
{
  return {-2.0, -1.5, -1.0, -0.75, -0.5, -0.35, -0.2, -0.1, -0.05, 0.0, 0.05, 0.1, 0.2,
          0.35, 0.5,  0.75, 1.0,   1.5,  2.0,   3.0,  4.0,  6.0,   8.0, 12.0, 16.0, 20.0};
}

ConstrainedFitOptions StabilityTestOptions::defaultProfileOptions()
{
  ConstrainedFitOptions options;
  options.starts = 0;
  options.max_local_solves = 0;
  options.max_warm_solves = 1;
  options.max_evaluations_per_solve = 100;
  options.relative_f_tolerance = 1e-8;
  return options;
}

StabilityTestResult testStringStability(const std::vector<CarFollowingRun>& runs, const StabilityTestOptions& options)
{
  std::vector<CarFollowingRun> training, held_out;
  for (const CarFollowingRun& run : runs)
  {
    if (!describeRunProblem(run).empty() || run.size() < 4)
    {
      continue;  // the two-argument form reports what is left
    }
    auto [first, second] = splitRunInHalf(run);
    training.push_back(std::move(first));
    held_out.push_back(std::move(second));
  }
  StabilityTestResult result = testStringStability(training, held_out, options);
  if (training.size() < runs.size())
  {
    result.reason += " (" + std::to_string(runs.size() - training.size()) +
                     " run(s) left out: fewer than 4 samples or not simulable)";
  }
  return result;
}

namespace
{
/// The held-out comparison of one pass: the bootstrap on the held-out segments, and the errors of
/// the side fit that predicts them better, which every profile point is scored against.
struct HeldOutComparison
{
  std::optional<MovingBlockBootstrap> bootstrap;
  std::vector<double> reference_errors;
  bool stable_wins = true;
};

/// One run of the test (testStringStability below), its stages as methods: the data, the two
/// side fits, then up to two passes of the held-out comparison and the margin profile.
class StringStabilityTestRun
{
public:
  explicit StringStabilityTestRun(const StabilityTestOptions& options)
    : options_(options), started_(std::chrono::steady_clock::now())
  {
    result_.alpha = options.alpha;
    result_.seed = options.seed;
    result_.bootstrap_replicates = options.bootstrap_replicates;
  }

  StabilityTestResult run(const std::vector<CarFollowingRun>& training_in,
                          const std::vector<CarFollowingRun>& held_out_in)
  {
    std::string failure = takeData(training_in, held_out_in);
    if (failure.empty())
      failure = fitSides();
    if (!failure.empty())
      return finish(failure);
    grid_ = marginGrid();
    for (int pass = 0; pass < 2; ++pass)
    {
      HeldOutComparison comparison;
      failure = compareSides(comparison);
      if (!failure.empty())
        return finish(failure);
      // A profile fit better on the training data than the side fit of its side (a local search
      // missed it) replaces that side fit, and the test is made again with it (once).
      if (adoptBetterProfileFits(profileOutwards(comparison)) && pass == 0)
        continue;
      refineEnds(comparison);
      break;
    }
    spanAllowedMargins(result_, leastMargin(options_.bounds), largestMargin(options_.bounds),
                       1e-3 * options_.multistart.start_box_upper.k1_per_s2, options_.alpha);
    return finish(decideVerdict(result_, options_.alpha));
  }

private:
  StabilityTestResult finish(std::string reason)
  {
    result_.reason = std::move(reason);
    result_.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    return result_;
  }

  /// The simulable runs, and whether there are enough of them to test; "" when there are.
  std::string takeData(const std::vector<CarFollowingRun>& training_in, const std::vector<CarFollowingRun>& held_out_in)
  {
    for (const CarFollowingRun& run : training_in)
    {
      if (describeRunProblem(run).empty())
      {
        training_.push_back(run);
        result_.training_samples += run.size();
      }
    }
    for (const CarFollowingRun& run : held_out_in)
    {
      if (describeRunProblem(run).empty())
      {
        held_out_.push_back(run);
        segment_lengths_.push_back(run.size() - 1);
        result_.held_out_samples += run.size() - 1;
        held_out_duration_s_ += run.durationS();
      }
    }
    result_.held_out_segments = held_out_.size();
    if (result_.training_samples < options_.min_training_samples)
      return "too few training samples (" + std::to_string(result_.training_samples) + " < " +
             std::to_string(options_.min_training_samples) + ")";
    if (result_.held_out_samples < options_.min_held_out_samples ||
        held_out_duration_s_ < options_.min_held_out_duration_s)
      return "too few held-out samples (" + std::to_string(result_.held_out_samples) + " over " +
             formatNumber(held_out_duration_s_) + " s; need " + std::to_string(options_.min_held_out_samples) +
             " samples and " + formatNumber(options_.min_held_out_duration_s) + " s)";
    const double speed_std = followerSpeedStdMps(training_);
    if (speed_std < options_.min_training_speed_std_mps)
      return "flat data: the training follower speed varies by " + formatNumber(speed_std) + " m/s (std) < " +
             formatNumber(options_.min_training_speed_std_mps) +
             " m/s; without speed changes the data pin only eta + tau_e v, not the margin";
    return "";
  }

  /// The unconstrained fit U and the best fit on the other side of m = 0; "" when both are found.
  std::string fitSides()
  {
    try
    {
      objective_.emplace(training_, options_.bounds);
    }
    catch (const std::exception& error)
    {
      return std::string("training data cannot be simulated: ") + error.what();
    }
    const SideFits side_fits = fitBothSides(*objective_, options_.multistart, options_.constrained, options_.warm_starts);
    result_.unconstrained_evaluations = side_fits.unconstrained_evaluations;
    result_.constrained_evaluations = side_fits.constrained_evaluations;
    if (!side_fits.failure.empty())
      return side_fits.failure;
    u_ = side_fits.unconstrained;
    u_stable_ = side_fits.unconstrained_stable;
    stable_ = side_fits.stable;
    unstable_ = side_fits.unstable;
    if (options_.with_quantities)
    {
      const ParameterUncertainty uncertainty = estimateUncertainty(u_, training_);
      result_.quantities = assessQuantities(u_, uncertainty, training_, options_.quantity_criteria);
      result_.quantities->basis = "training data's unconstrained fit; " + result_.quantities->basis;
    }
    return "";
  }

  /// The margins of the profile: the grid within the bounds' margins, with 0.
  std::vector<double> marginGrid() const
  {
    std::vector<double> grid;
    const double least = leastMargin(options_.bounds), largest = largestMargin(options_.bounds);
    for (double m0 : options_.margin_grid)
      if (std::isfinite(m0) && m0 >= least && m0 <= largest)
        grid.push_back(m0);
    if (!grid.empty() && 0.0 >= least && 0.0 <= largest)
      grid.push_back(0.0);
    std::sort(grid.begin(), grid.end());
    grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
    return grid;
  }

  double trainMse(const AccParameters& p) const
  {
    const ReducedObjectiveValue value = objective_->evaluate(p.k1_per_s2, p.k2_per_s, p.tau_e_s, false);
    return value.diverged ? kInfinity : value.mse_speed_mps2;
  }

  /// The best training fit with m = m0.
  ProfileFit solveAt(double m0, const std::vector<AccParameters>& warm)
  {
    ProfileFit fit;
    fit.margin = m0;
    const ConstrainedFitResult r = fitWithMarginConstraint(*objective_, MarginSide::EqualTo, m0, options_.profile, warm);
    result_.profile_evaluations += r.evaluations;
    if (r.found)
    {
      fit.parameters = r.parameters;
      fit.margin = r.margin;
      fit.train_mse = r.rmse_speed_mps * r.rmse_speed_mps;
      fit.fitted = true;
    }
    return fit;
  }

  /// The verdict's test: both side fits on the held-out data, their paired squared errors, the
  /// bootstrap's p-values; then the side fits as the first profile points. "" when it ran.
  std::string compareSides(HeldOutComparison& comparison)
  {
    result_.margin_profile.clear();
    stable_.train_rmse_speed_mps = evaluateFit(stable_.parameters, training_).rmse_speed_mps;
    unstable_.train_rmse_speed_mps = evaluateFit(unstable_.parameters, training_).rmse_speed_mps;
    const HeldOutErrors stable_errors = heldOutErrors(stable_.parameters, held_out_);
    const HeldOutErrors unstable_errors = heldOutErrors(unstable_.parameters, held_out_);
    stable_.test_rmse_speed_mps = rms(stable_errors.error);
    unstable_.test_rmse_speed_mps = rms(unstable_errors.error);
    result_.best_stable = stable_;
    result_.best_unstable = unstable_;
    if (stable_errors.diverged || unstable_errors.diverged)
    {
      result_.tested = false;
      return std::string("the best ") + (stable_errors.diverged ? "stable" : "unstable") +
             " model's simulation diverges on the held-out data";
    }
    const std::vector<double> d = squaredErrorDifference(stable_errors.error, unstable_errors.error);
    result_.mean_squared_error_difference = mean(d);
    const std::size_t block_samples = blockSamples(d);
    comparison.bootstrap.emplace(segment_lengths_, block_samples, options_.bootstrap_replicates, options_.seed);
    result_.p_value_stable_rejected = comparison.bootstrap->pValueMeanPositive(d);
    result_.p_value_unstable_rejected = comparison.bootstrap->pValueMeanNegative(d);
    result_.tested = true;
    comparison.stable_wins = result_.mean_squared_error_difference <= 0.0;
    comparison.reference_errors = comparison.stable_wins ? stable_errors.error : unstable_errors.error;
    addSidePoints(comparison);
    return "";
  }

  /// The bootstrap's block length in samples: options.block_length_s, or from d's correlation.
  std::size_t blockSamples(const std::vector<double>& d)
  {
    const double mean_step_s =
        held_out_duration_s_ / static_cast<double>(std::max<std::size_t>(1, result_.held_out_samples));
    double block_s = options_.block_length_s;
    if (!(block_s > 0.0))
    {
      block_s = correlationBlockLengthS(d, segment_lengths_, mean_step_s, 5.0, options_.min_block_length_s,
                                        options_.max_block_length_s);
      block_s = std::min(block_s,
                         held_out_duration_s_ / static_cast<double>(std::max<std::size_t>(1, options_.min_blocks)));
    }
    const std::size_t block_samples =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(block_s / mean_step_s)));
    result_.block_length_s = static_cast<double>(block_samples) * mean_step_s;
    return block_samples;
  }

  /// A profile point, scored against the better held-out side fit.
  MarginProfilePoint score(const HeldOutComparison& comparison, const ProfileFit& fit) const
  {
    MarginProfilePoint point;
    point.margin = fit.margin;
    point.fitted = fit.fitted;
    if (!fit.fitted)
      return point;
    point.parameters = fit.parameters;
    point.train_rmse_speed_mps = std::sqrt(fit.train_mse);
    const HeldOutErrors errors = heldOutErrors(fit.parameters, held_out_);
    point.test_rmse_speed_mps = rms(errors.error);
    point.p_value = errors.diverged ? 0.0
                                    : comparison.bootstrap->pValueMeanPositive(
                                          squaredErrorDifference(errors.error, comparison.reference_errors));
    point.allowed = point.p_value > options_.alpha;
    return point;
  }

  /// The side fits as profile points: the same numbers as the verdict's test (the same series and
  /// draws, up to sign).
  void addSidePoints(const HeldOutComparison& comparison)
  {
    std::vector<MarginProfilePoint>& points = result_.margin_profile;
    for (const SideFit* side : {&stable_, &unstable_})
    {
      MarginProfilePoint point;
      point.margin = side->margin;
      point.fitted = true;
      point.parameters = side->parameters;
      point.train_rmse_speed_mps = side->train_rmse_speed_mps;
      point.test_rmse_speed_mps = side->test_rmse_speed_mps;
      const bool is_stable = side == &stable_;
      point.p_value = is_stable == comparison.stable_wins ? 1.0
                      : is_stable                          ? result_.p_value_stable_rejected
                                                           : result_.p_value_unstable_rejected;
      point.allowed = point.p_value > options_.alpha;
      if (points.empty() || std::abs(points.front().margin - point.margin) > kSameMargin)
        points.push_back(point);
    }
  }

  /// The profile outwards from m = 0 over the grid; the fits made (for adoptBetterProfileFits).
  std::vector<ProfileFit> profileOutwards(const HeldOutComparison& comparison)
  {
    std::vector<ProfileFit> grid_fits;
    if (grid_.empty())
      return grid_fits;
    // m = 0: the side fit on the boundary when there is one, else its own fit.
    const SideFit* boundary = nullptr;
    for (const SideFit* side : {&stable_, &unstable_})
      boundary = std::abs(side->margin) <= kSameMargin ? side : boundary;
    AccParameters at_zero = u_;
    if (boundary != nullptr)
    {
      at_zero = boundary->parameters;
    }
    else
    {
      const ProfileFit zero = solveAt(0.0, {u_, u_stable_ ? unstable_.parameters : stable_.parameters});
      result_.margin_profile.push_back(score(comparison, zero));
      grid_fits.push_back(zero);
      at_zero = zero.fitted ? zero.parameters : u_;
    }
    for (int direction : {+1, -1})
      profileInDirection(comparison, direction, at_zero, grid_fits);
    return grid_fits;
  }

  /// Each m0 warm-started from its neighbour and from U; a direction stops after
  /// profile_stop_after_rejections rejected margins in a row beyond its side fit.
  void profileInDirection(const HeldOutComparison& comparison, int direction, const AccParameters& at_zero,
                          std::vector<ProfileFit>& grid_fits)
  {
    const double side_margin = direction > 0 ? stable_.margin : unstable_.margin;
    AccParameters previous = at_zero;
    std::size_t rejected_in_a_row = 0;
    std::vector<double> ordered;
    for (double m0 : grid_)
      if (direction * m0 > 0.0)
        ordered.push_back(m0);
    if (direction < 0)
      std::reverse(ordered.begin(), ordered.end());
    for (double m0 : ordered)
    {
      if (options_.profile_stop_after_rejections > 0 && rejected_in_a_row >= options_.profile_stop_after_rejections)
        break;
      const ProfileFit fit = solveAt(m0, {previous, u_});
      const MarginProfilePoint point = score(comparison, fit);
      result_.margin_profile.push_back(point);
      grid_fits.push_back(fit);
      if (fit.fitted)
        previous = fit.parameters;
      const bool beyond_side = direction * m0 > direction * side_margin;
      rejected_in_a_row = beyond_side && !point.allowed ? rejected_in_a_row + 1 : 0;
    }
  }

  /// A profile fit better on the training data than the side fit of its side replaces it; true
  /// when one did.
  bool adoptBetterProfileFits(const std::vector<ProfileFit>& grid_fits)
  {
    bool improved = false;
    for (const ProfileFit& fit : grid_fits)
    {
      if (!fit.fitted)
        continue;
      // A fit on the boundary m = 0 belongs to both closed sides.
      for (SideFit* side : {&stable_, &unstable_})
      {
        const bool on_side = side == &stable_ ? fit.margin >= -kSameMargin : fit.margin <= kSameMargin;
        if (!on_side || !(fit.train_mse < trainMse(side->parameters) * (1.0 - 1e-9)))
          continue;
        AccParameters p = fit.parameters;
        if (side == &unstable_ && fit.margin > 0.0)
        {
          // The boundary fit sits a few ulps above 0: move it to m <= 0 by ulps of tau_e.
          const auto below = projectOntoMargin(p, 0.0, options_.bounds, MarginSide::AtMost);
          if (below.empty())
            continue;
          p = below.front();
          p.eta_m = objective_->evaluate(p.k1_per_s2, p.k2_per_s, p.tau_e_s, false).eta_m;
        }
        side->parameters = p;
        side->margin = stabilityMargin(p);
        side->unconstrained_optimum = false;
        side->status = "FROM_MARGIN_PROFILE";
        improved = true;
      }
    }
    return improved;
  }

  /// Each end of the allowed margins, when a rejected margin lies beyond it, refined by bisection
  /// between the two; the profile sorted by margin.
  void refineEnds(const HeldOutComparison& comparison)
  {
    std::vector<MarginProfilePoint>& points = result_.margin_profile;
    auto byMargin = [](const MarginProfilePoint& a, const MarginProfilePoint& b) { return a.margin < b.margin; };
    std::sort(points.begin(), points.end(), byMargin);
    for (int end : {-1, +1})
    {
      std::size_t inner = points.size();
      for (std::size_t i = 0; i < points.size(); ++i)
      {
        const std::size_t j = end < 0 ? i : points.size() - 1 - i;
        if (points[j].allowed)
        {
          inner = j;
          break;
        }
      }
      if (inner == points.size() || (end < 0 && inner == 0) || (end > 0 && inner + 1 == points.size()))
        continue;
      MarginProfilePoint allowed = points[inner];
      double outer = points[end < 0 ? inner - 1 : inner + 1].margin;
      for (std::size_t step = 0; step < options_.interval_bisections; ++step)
      {
        const double m0 = 0.5 * (allowed.margin + outer);
        const MarginProfilePoint point = score(comparison, solveAt(m0, {allowed.parameters, u_}));
        points.push_back(point);
        if (point.allowed)
          allowed = point;
        else
          outer = m0;
      }
    }
    std::sort(points.begin(), points.end(), byMargin);
  }

  const StabilityTestOptions& options_;
  const std::chrono::steady_clock::time_point started_;
  StabilityTestResult result_;
  std::vector<CarFollowingRun> training_, held_out_;
  std::vector<std::size_t> segment_lengths_;
  double held_out_duration_s_ = 0.0;
  std::optional<CalibrationObjective> objective_;
  AccParameters u_;
  bool u_stable_ = false;
  SideFit stable_, unstable_;
  std::vector<double> grid_;
};
}  // namespace

StabilityTestResult testStringStability(const std::vector<CarFollowingRun>& training_in,
                                        const std::vector<CarFollowingRun>& held_out_in,
                                        const StabilityTestOptions& options)
{
  return StringStabilityTestRun(options).run(training_in, held_out_in);
}

}  // namespace acc
