#include "acc_identification/calibration/string_stability_verdict.h"
#include "acc_identification/model/number_text.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include "acc_identification/calibration/fit_statistics.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
namespace
{
constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Margins closer than this count as the same profile point (the boundary fits sit a few ulps
/// above 0).
constexpr double kSameMargin = 1e-9;

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
  result.margin_allowed_pieces = allowedMarginPieces(points, result.margin_low, result.margin_high);
  if (result.margin_allowed_pieces.size() > 1)
  {
    note << "; not one interval: the margins tried between its pieces are rejected";
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
std::string decideVerdict(StabilityTestResult& result)
{
  std::string why = describeComparison(result, result.best_stable.test_rmse_speed_mps,
                                       "m = " + significant(result.best_stable.margin),
                                       result.best_unstable.test_rmse_speed_mps,
                                       "m = " + significant(result.best_unstable.margin));
  const std::string allowed = allowedMarginsText(result);
  switch (decideSides(result, result.margin_high < -kSameMargin, result.margin_low > kSameMargin))
  {
    case SideDecision::Decided:
      return why + (result.verdict == StabilityVerdict::Unstable ? ": the data reject string stability"
                                                                 : ": the data reject string instability") +
             "; allowed margins " + allowed;
    case SideDecision::RejectedWinnerNotInside:
      return why + ": the paired test rejects " +
             (result.p_value_stable_rejected <= result.alpha ? "stability" : "instability") +
             ", but the held-out data still allow margins on both sides of 0 or on the boundary (allowed " + allowed +
             "): a model at or across m = 0 predicts as well";
    case SideDecision::NeitherRejected:
      break;
  }
  return why + ": neither model predicts the held-out data significantly better (alpha " + significant(result.alpha) +
         ")";
}

}  // namespace

std::vector<std::array<double, 2>> allowedMarginPieces(const std::vector<MarginProfilePoint>& points, double low,
                                                       double high)
{
  std::vector<std::array<double, 2>> pieces;
  bool inside = false;
  for (const MarginProfilePoint& point : points)
  {
    if (point.allowed && !inside)
      pieces.push_back({point.margin, point.margin});
    if (point.allowed)
      pieces.back()[1] = point.margin;
    inside = point.allowed;
  }
  if (!pieces.empty())
  {
    pieces.front()[0] = low;
    pieces.back()[1] = high;
  }
  return pieces;
}

std::vector<double> StabilityTestOptions::defaultMarginGrid()
{
  return {-2.0, -1.5, -1.0, -0.75, -0.5, -0.35, -0.2, -0.1, -0.05, 0.0, 0.05, 0.1, 0.2,
          0.35, 0.5,  0.75, 1.0,   1.5,  2.0,   3.0,  4.0,  6.0,   8.0, 12.0, 16.0, 20.0};
}

ConstrainedFitOptions StabilityTestOptions::defaultProfileOptions()
{
  return ConstrainedFitOptions::warmStartsOnly(1, 100);
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
      std::optional<HeldOutSideComparison> compared;
      failure = compareSides(compared);
      if (!failure.empty())
        return finish(failure);
      const HeldOutSideComparison& comparison = *compared;
      // A profile fit better on the training data than the side fit of its side (a local search
      // missed it) replaces that side fit, and the test is made again with it (once).
      if (adoptBetterProfileFits(profileOutwards(comparison)) && pass == 0)
        continue;
      refineEnds(comparison);
      break;
    }
    spanAllowedMargins(result_, leastMargin(options_.bounds), largestMargin(options_.bounds),
                       1e-3 * options_.multistart.start_box_upper.k1_per_s2, options_.alpha);
    return finish(decideVerdict(result_));
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
      if (describeRunProblem(run).empty())
        held_out_.push_back(run);
    segments_ = heldOutSegmentsOf(held_out_);
    result_.held_out_samples = segments_.scored_samples;
    result_.held_out_duration_s = segments_.duration_s;
    result_.held_out_segments = segments_.scored_lengths.size();
    if (result_.training_samples < options_.min_training_samples)
      return "too few training samples (" + std::to_string(result_.training_samples) + " < " +
             std::to_string(options_.min_training_samples) + ")";
    if (const std::string shortage = heldOutShortage(segments_, options_); !shortage.empty())
      return shortage;
    const double speed_std = followerSpeedStdMps(training_);
    if (speed_std < options_.min_training_speed_std_mps)
      return "flat data: the training follower speed varies by " + significant(speed_std) + " m/s (std) < " +
             significant(options_.min_training_speed_std_mps) +
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
      result_.quantities = assessQuantities(u_, uncertainty, training_, options_.bounds, options_.quantity_criteria);
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
  std::string compareSides(std::optional<HeldOutSideComparison>& comparison)
  {
    result_.margin_profile.clear();
    stable_.train_rmse_speed_mps = evaluateFit(stable_.parameters, training_).rmse_speed_mps;
    unstable_.train_rmse_speed_mps = evaluateFit(unstable_.parameters, training_).rmse_speed_mps;
    const HeldOutSides sides =
        scoreHeldOutSides(heldOutErrors(stable_.parameters, held_out_), heldOutErrors(unstable_.parameters, held_out_));
    stable_.test_rmse_speed_mps = sides.stable_rmse_speed_mps;
    unstable_.test_rmse_speed_mps = sides.unstable_rmse_speed_mps;
    result_.best_stable = stable_;
    result_.best_unstable = unstable_;
    if (!sides.divergence.empty())
    {
      result_.tested = false;
      return sides.divergence;
    }
    comparison.emplace(sides.stable_squared, sides.unstable_squared, segments_, options_);
    comparison->report(result_);
    result_.tested = true;
    addSidePoints(*comparison);
    return "";
  }

  /// A profile point, scored against the better held-out side fit.
  MarginProfilePoint score(const HeldOutSideComparison& comparison, const ProfileFit& fit) const
  {
    MarginProfilePoint point;
    point.margin = fit.margin;
    point.fitted = fit.fitted;
    if (!fit.fitted)
      return point;
    point.parameters = fit.parameters;
    point.train_rmse_speed_mps = std::sqrt(fit.train_mse);
    const HeldOutErrors errors = heldOutErrors(fit.parameters, held_out_);
    const std::vector<double> squared_errors = squared(errors.error);
    point.test_rmse_speed_mps = rootMeanOf(squared_errors);
    point.p_value = errors.diverged ? 0.0 : comparison.pValueWorseThanBetterSide(squared_errors);
    point.allowed = point.p_value > options_.alpha;
    return point;
  }

  /// The side fits as profile points: the same numbers as the verdict's test (the same series and
  /// draws, up to sign).
  void addSidePoints(const HeldOutSideComparison& comparison)
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
      point.p_value = is_stable == comparison.stableWins() ? 1.0
                      : is_stable                          ? result_.p_value_stable_rejected
                                                           : result_.p_value_unstable_rejected;
      point.allowed = point.p_value > options_.alpha;
      if (points.empty() || std::abs(points.front().margin - point.margin) > kSameMargin)
        points.push_back(point);
    }
  }

  /// The profile outwards from m = 0 over the grid; the fits made (for adoptBetterProfileFits).
  std::vector<ProfileFit> profileOutwards(const HeldOutSideComparison& comparison)
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
  void profileInDirection(const HeldOutSideComparison& comparison, int direction, const AccParameters& at_zero,
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
  void refineEnds(const HeldOutSideComparison& comparison)
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
  HeldOutSegments segments_;
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
