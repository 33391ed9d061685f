#include "acc_identification/validation/withheld_effect_suite.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "acc_identification/diagnosis/determined_effects.h"
#include "acc_identification/validation/injected_effect.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/normal_source.h"

namespace acc
{
namespace
{
/// Moves `speed` towards `target` at the given rates for one step.
double ramp(double speed, double target, double up_mps2, double down_mps2, double step_s)
{
  if (target > speed)
  {
    return std::min(target, speed + up_mps2 * step_s);
  }
  return std::max(target, speed - down_mps2 * step_s);
}

/// Held speeds [m/s] and how long each is held [s], cycled until the duration is filled.
std::vector<double> heldSpeeds(const std::vector<std::pair<double, double>>& holds, double up, double down,
                               double duration_s, double step_s)
{
  const std::size_t n = static_cast<std::size_t>(std::floor(duration_s / step_s)) + 1;
  std::vector<double> speed(n);
  double v = holds.front().first;
  std::size_t hold = 0;
  double held_for = 0.0;
  for (std::size_t k = 0; k < n; ++k)
  {
    speed[k] = v;
    const double target = holds[hold].first;
    if (std::abs(v - target) < 1e-9)
    {
      held_for += step_s;
      if (held_for >= holds[hold].second)
      {
        hold = (hold + 1) % holds.size();
        held_for = 0.0;
      }
    }
    v = ramp(v, holds[hold].first, up, down, step_s);
  }
  return speed;
}

/// Distance the leader covers over [t - delta, t] (trapezoid over the sampled true speed).
double distanceOver(const std::vector<double>& time_s, const std::vector<double>& speed, std::size_t k, double delta)
{
  const double step = time_s[1] - time_s[0];
  const double start = time_s[k] - delta;
  double distance = 0.0;
  const std::size_t substeps = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(std::abs(delta) / step * 4)));
  const double h = delta / static_cast<double>(substeps);
  auto speed_at = [&](double t) {
    const double position = std::clamp((t - time_s[0]) / step, 0.0, static_cast<double>(speed.size() - 1));
    const std::size_t i = std::min(static_cast<std::size_t>(position), speed.size() - 2);
    const double w = position - static_cast<double>(i);
    return speed[i] + w * (speed[i + 1] - speed[i]);
  };
  for (std::size_t i = 0; i < substeps; ++i)
  {
    const double a = start + h * static_cast<double>(i);
    distance += 0.5 * h * (speed_at(a) + speed_at(a + h));
  }
  return distance;
}

double primaryValue(const WithheldCase& c)
{
  return c.truth_values.empty() ? std::numeric_limits<double>::quiet_NaN() : c.truth_values.front();
}

}  // namespace

double medianOf(std::vector<double> v)
{
  if (v.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string chainText(const std::vector<EffectKind>& chain)
{
  std::string text;
  for (EffectKind kind : chain)
  {
    text += (text.empty() ? "" : " + ") + effectName(kind);
  }
  return text.empty() ? "-" : text;
}

std::string leadProfileName(SyntheticLeadProfile profile)
{
  switch (profile)
  {
    case SyntheticLeadProfile::steps: return "steps";
    case SyntheticLeadProfile::oscillation: return "oscillation";
    case SyntheticLeadProfile::dip: return "dip";
  }
  return "unknown";
}

std::vector<double> syntheticLeaderSpeed(SyntheticLeadProfile profile, double duration_s, double step_s)
{
  switch (profile)
  {
    case SyntheticLeadProfile::steps:
      return heldSpeeds({{22.0, 30.0}, {30.0, 35.0}, {16.0, 30.0}, {27.0, 30.0}, {12.0, 25.0}}, 1.5, 2.5, duration_s,
                        step_s);
    case SyntheticLeadProfile::dip:
      return heldSpeeds({{28.0, 50.0}, {8.0, 15.0}, {28.0, 40.0}, {33.0, 30.0}, {15.0, 20.0}}, 2.0, 3.5, duration_s,
                        step_s);
    case SyntheticLeadProfile::oscillation:
    {
      const std::size_t n = static_cast<std::size_t>(std::floor(duration_s / step_s)) + 1;
      std::vector<double> speed(n);
      const double pi = 3.14159265358979323846;
      for (std::size_t k = 0; k < n; ++k)
      {
        const double t = static_cast<double>(k) * step_s;
        speed[k] = 22.0 + 5.0 * std::sin(2 * pi * t / 60.0) + 2.5 * std::sin(2 * pi * t / 23.0 + 1.0) +
                   1.2 * std::sin(2 * pi * t / 9.0 + 2.0);
      }
      return speed;
    }
  }
  return {};
}

CarFollowingRun synthesizeWithheldRun(const WithheldCase& c)
{
  // The truth on a fine grid.
  const int substeps = std::max(1, c.truth_substeps);
  const double fine_step = c.step_s / substeps;
  CarFollowingRun truth;
  truth.leader_speed_mps = syntheticLeaderSpeed(c.profile, c.duration_s, fine_step);
  const std::size_t fine_n = truth.leader_speed_mps.size();
  for (std::size_t k = 0; k < fine_n; ++k)
  {
    truth.time_s.push_back(static_cast<double>(k) * fine_step);
  }
  EffectSettings effects = makeEffectSettings(c.truth, c.truth_values);
  for (const auto& [kind, values] : c.also_withheld)
  {
    applyEffectValues(kind, values, &effects);
  }
  const double v0 = std::min(truth.leader_speed_mps[0], effects.set_speed_mps);
  const double s0 = c.base.eta_m + c.base.tau_e_s * v0 + effects.time_gap_speed_slope_s2_per_m * v0 * v0;
  truth.follower_speed_mps.assign(fine_n, v0);
  truth.space_gap_m.assign(fine_n, s0);
  // Simulate with the true leader (a clock offset changes only the record).
  const double offset = effects.sensor_time_offset_s;
  effects.sensor_time_offset_s = 0.0;
  const SimulatedFollower sim = simulateFollower(c.base, effects, truth);
  // The record: every substeps-th sample, leader delayed by the offset, gap read with it.
  CarFollowingRun recorded;
  recorded.name = effectName(c.truth) + "_" + leadProfileName(c.profile) + "_seed" + std::to_string(c.seed);
  for (std::size_t k = 0; k < fine_n; k += static_cast<std::size_t>(substeps))
  {
    double leader = truth.leader_speed_mps[k];
    double gap = sim.space_gap_m[k];
    if (offset != 0.0)
    {
      const double position = std::clamp((truth.time_s[k] - offset) / fine_step, 0.0, static_cast<double>(fine_n - 1));
      const std::size_t i = std::min(static_cast<std::size_t>(position), fine_n - 2);
      const double w = position - static_cast<double>(i);
      leader = truth.leader_speed_mps[i] + w * (truth.leader_speed_mps[i + 1] - truth.leader_speed_mps[i]);
      gap -= distanceOver(truth.time_s, truth.leader_speed_mps, k, offset);
    }
    recorded.time_s.push_back(truth.time_s[k]);
    recorded.leader_speed_mps.push_back(leader);
    recorded.follower_speed_mps.push_back(sim.speed_mps[k]);
    recorded.space_gap_m.push_back(gap);
  }
  const std::size_t n = recorded.size();
  NormalSource noise(c.seed);  // the same numbers with every standard library
  for (std::size_t k = 0; k < n; ++k)
  {
    recorded.follower_speed_mps[k] += c.speed_noise_std_mps * noise.standardNormal();
    recorded.leader_speed_mps[k] += c.speed_noise_std_mps * noise.standardNormal();
    recorded.space_gap_m[k] += c.gap_noise_std_m * noise.standardNormal();
  }
  return recorded;
}

WithheldOutcome runWithheldCase(const WithheldCase& c, const DiagnosisOptions& options)
{
  WithheldOutcome outcome;
  outcome.input = c;
  // The suite asks which effect is missing; the string-stability test of the chosen model is not
  // part of that question (test_diagnosis_stability covers it) and would double the suite's cost.
  DiagnosisOptions naming_only = options;
  naming_only.with_stability_test = false;
  // Likewise the chain of effects in combination: the suite's question is the dominant one.
  naming_only.forward_selection = false;
  const DiagnosisResult result = diagnoseRuns({synthesizeWithheldRun(c)}, naming_only);
  outcome.dominant = result.selection.dominant;
  outcome.plausible = result.selection.plausible;
  outcome.base_test_rmse_speed_mps = result.baseline.test_rmse_speed_mps;
  outcome.recovered_magnitude = std::numeric_limits<double>::quiet_NaN();
  outcome.recovered_standard_error = std::numeric_limits<double>::quiet_NaN();
  outcome.effect_test_rmse_speed_mps = result.baseline.test_rmse_speed_mps;
  for (const DeterminedEffect& effect : result.determined)
  {
    outcome.determined.push_back(effect.effect);
  }
  for (const ModelDiagnosis& model : result.effects)
  {
    if (model.fit.effect == c.truth)
    {
      outcome.recovered_magnitude = model.fit.effect_values.empty() ? outcome.recovered_magnitude
                                                                    : model.fit.effect_values.front();
      outcome.effect_test_rmse_speed_mps = model.test_rmse_speed_mps;
      // Standard errors are ordered (k1, k2, tau_e, eta, effect values...).
      outcome.recovered_standard_error =
          model.fit.standard_errors.size() > 4 ? model.fit.standard_errors[4] : outcome.recovered_standard_error;
    }
  }
  return outcome;
}

std::vector<EffectKind> diagnosableEffects()
{
  // Every effect of both catalogues: one a run's options add (--effect) is counted too.
  std::vector<EffectKind> kinds{EffectKind::none};
  for (const auto* list : {&candidateEffects(), &responseEffects()})
  {
    for (const CandidateEffect& effect : *list)
      kinds.push_back(effect.kind);
  }
  return kinds;
}

std::vector<EffectKind> exploratoryCandidates(const std::vector<EffectKind>& candidates)
{
  const std::vector<EffectKind> defaults = DiagnosisOptions{}.candidates;
  std::vector<EffectKind> out;
  for (EffectKind kind : candidates)
  {
    if (std::find(defaults.begin(), defaults.end(), kind) == defaults.end())
      out.push_back(kind);
  }
  return out;
}

std::vector<WithheldCase> withheldCaseGrid(std::size_t magnitudes_per_effect,
                                           const std::vector<SyntheticLeadProfile>& profiles,
                                           const std::vector<double>& noise_scales, std::size_t seeds,
                                           const std::vector<EffectKind>& exploratory)
{
  // Magnitudes in the range reported for production ACCs; set speeds are below the profiles'
  // top speeds (30-33 m/s) so that the leader pulls away at times.
  const std::map<EffectKind, std::vector<std::vector<double>>> magnitudes = {
      {EffectKind::none, {{}}},
      {EffectKind::actuation_lag, {{0.6}, {1.0}, {0.35}}},
      {EffectKind::reaction_delay, {{0.6}, {1.0}, {0.35}}},
      {EffectKind::acceleration_limits, {{1.0, 2.0}, {1.3, 1.5}, {0.8, 3.0}}},
      {EffectKind::sensor_time_offset, {{0.8}, {-0.6}, {1.5}}},
      {EffectKind::speed_dependent_time_gap, {{0.02}, {-0.015}, {0.01}}},
      {EffectKind::set_speed_cruise, {{25.0, 0.4}, {27.0, 0.25}, {24.0, 0.6}}},
      // Response effects among the default candidates: a closing gain 2-4 times the following
      // one (SUMO's ACC switches to gains of that order in its collision-avoidance mode), gains
      // that change by 4-6 % per m/s.
      {EffectKind::asymmetric_response, {{3.0, 3.0}, {2.0, 4.0}, {4.0, 1.5}}},
      {EffectKind::speed_dependent_gains, {{0.05}, {-0.04}, {0.06}}},
  };
  // Exploratory effects, hidden only when asked for: an anticipation of 15-50 % of the leader's
  // acceleration; braking at 2-7 times the kinematic deceleration (the range the ZalaZone cars
  // were fitted to in the platoon diagnosis); an anticipation of 15-60 % of the leader's braking
  // alone (the ZalaZone cars' 0-0.67).
  const std::map<EffectKind, std::vector<std::vector<double>>> exploratory_magnitudes = {
      {EffectKind::leader_acceleration_feedforward, {{0.3}, {0.5}, {0.15}}},
      {EffectKind::quadratic_closing_response, {{4.0}, {2.0}, {7.0}}},
      {EffectKind::leader_braking_anticipation, {{0.3}, {0.6}, {0.15}}},
  };
  std::vector<std::pair<EffectKind, std::vector<std::vector<double>>>> truths(magnitudes.begin(), magnitudes.end());
  for (EffectKind kind : exploratory)
  {
    const auto found = exploratory_magnitudes.find(kind);
    if (found != exploratory_magnitudes.end())
      truths.push_back(*found);
  }
  std::vector<WithheldCase> grid;
  std::uint32_t seed_base = 1;
  for (const auto& [kind, list] : truths)
  {
    // The no-effect case gets as many repetitions as an effect gets magnitudes.
    const std::size_t count = kind == EffectKind::none ? magnitudes_per_effect : std::min(magnitudes_per_effect, list.size());
    for (std::size_t m = 0; m < count; ++m)
    {
      for (SyntheticLeadProfile profile : profiles)
      {
        for (double noise : noise_scales)
        {
          for (std::size_t s = 0; s < seeds; ++s)
          {
            WithheldCase c;
            c.truth = kind;
            c.truth_values = list[kind == EffectKind::none ? 0 : m];
            c.profile = profile;
            c.speed_noise_std_mps *= noise;
            c.gap_noise_std_m *= noise;
            c.seed = seed_base++;
            grid.push_back(c);
          }
        }
      }
    }
  }
  return grid;
}

namespace
{
std::size_t labelIndex(const std::vector<EffectKind>& labels, EffectKind kind)
{
  const auto found = std::find(labels.begin(), labels.end(), kind);
  if (found == labels.end())
  {
    throw std::logic_error("effect " + effectName(kind) + " is not a label of the suite's tables");
  }
  return static_cast<std::size_t>(found - labels.begin());
}
}  // namespace

ConfusionMatrix confusionMatrix(const std::vector<WithheldOutcome>& outcomes)
{
  ConfusionMatrix matrix;
  matrix.labels = diagnosableEffects();
  matrix.counts.assign(matrix.labels.size(), std::vector<std::size_t>(matrix.labels.size(), 0));
  for (const WithheldOutcome& o : outcomes)
  {
    ++matrix.counts[labelIndex(matrix.labels, o.input.truth)][labelIndex(matrix.labels, o.dominant)];
    const bool in_plausible = o.input.truth == EffectKind::none
                                  ? o.plausible.empty()
                                  : std::find(o.plausible.begin(), o.plausible.end(), o.input.truth) != o.plausible.end();
    matrix.truth_in_plausible += in_plausible ? 1 : 0;
    ++matrix.cases;
  }
  return matrix;
}

namespace
{
/// Counts by truth (rows) and effect (columns) as a Markdown table; a row per truth with cases
/// (cases_per_truth, or the row's sum when that is empty), labelled with its cases when given.
/// Returns the diagonal's sum.
std::size_t writeCountTable(const std::vector<EffectKind>& labels, const std::vector<std::vector<std::size_t>>& counts,
                            const std::vector<std::size_t>& cases_per_truth, const std::string& corner,
                            std::ostream& out)
{
  out << "| " << corner << " |";
  for (EffectKind label : labels)
  {
    out << " " << effectName(label) << " |";
  }
  out << "\n|---|";
  for (std::size_t i = 0; i < labels.size(); ++i)
  {
    out << "---|";
  }
  out << "\n";
  std::size_t diagonal = 0;
  for (std::size_t r = 0; r < labels.size(); ++r)
  {
    // A truth never hidden has no row (an all-zero row would read as an effect never found); every
    // label stays a column, since any can be named.
    const std::size_t row_sum = std::accumulate(counts[r].begin(), counts[r].end(), std::size_t{0});
    const bool counted_cases = !cases_per_truth.empty();
    if ((counted_cases ? cases_per_truth[r] : row_sum) == 0)
      continue;
    out << "| " << effectName(labels[r]);
    if (counted_cases)
      out << " (" << cases_per_truth[r] << ")";
    out << " |";
    for (std::size_t c = 0; c < labels.size(); ++c)
    {
      out << " " << counts[r][c] << " |";
    }
    out << "\n";
    diagonal += counts[r][r];
  }
  return diagonal;
}
}  // namespace

std::string formatConfusionMatrix(const ConfusionMatrix& matrix)
{
  std::ostringstream out;
  const std::size_t correct = writeCountTable(matrix.labels, matrix.counts, {}, "truth \\ named", out);
  out << "\nnamed correctly: " << correct << " of " << matrix.cases << "; truth in the plausible set: "
      << matrix.truth_in_plausible << " of " << matrix.cases << "\n";
  return out.str();
}

DeterminedTable determinedTable(const std::vector<WithheldOutcome>& outcomes)
{
  DeterminedTable table;
  table.labels = diagnosableEffects();
  table.counts.assign(table.labels.size(), std::vector<std::size_t>(table.labels.size(), 0));
  table.cases_per_truth.assign(table.labels.size(), 0);
  for (const WithheldOutcome& o : outcomes)
  {
    const std::size_t row = labelIndex(table.labels, o.input.truth);
    ++table.cases_per_truth[row];
    for (EffectKind kind : o.determined)
    {
      ++table.counts[row][labelIndex(table.labels, kind)];
    }
    // Only an effect with a "none" value can be determined: limits and a set speed are not asked.
    if (o.input.truth != EffectKind::none && std::isfinite(neutralValue(o.input.truth)))
    {
      ++table.determinable_cases;
      table.truth_determined +=
          std::find(o.determined.begin(), o.determined.end(), o.input.truth) != o.determined.end() ? 1 : 0;
    }
  }
  return table;
}

std::string formatDeterminedTable(const DeterminedTable& table)
{
  std::ostringstream out;
  out << "Determined by the training data (an effect's single fit at least z standard errors from none; "
         "a case counts in every column it determines):\n\n";
  writeCountTable(table.labels, table.counts, table.cases_per_truth, "truth (cases) \\ determined", out);
  const std::size_t none_row = labelIndex(table.labels, EffectKind::none);
  const std::size_t none_any = std::accumulate(table.counts[none_row].begin(), table.counts[none_row].end(), std::size_t{0});
  out << "\nthe hidden effect determined: " << table.truth_determined << " of " << table.determinable_cases
      << " (the cases whose effect has a none value); determinations where nothing is hidden: " << none_any << " in "
      << table.cases_per_truth[none_row] << " cases\n";
  return out.str();
}

std::string formatMagnitudeRecovery(const std::vector<WithheldOutcome>& outcomes)
{
  std::ostringstream out;
  out << "| effect | parameter | cases named correctly | median abs. error | median rel. error |\n|---|---|---|---|---|\n";
  for (EffectKind kind : diagnosableEffects())
  {
    if (kind == EffectKind::none)
      continue;
    const CandidateEffect& effect = candidateEffect(kind);
    const bool hidden = std::any_of(outcomes.begin(), outcomes.end(),
                                    [&](const WithheldOutcome& o) { return o.input.truth == kind; });
    if (!hidden)
      continue;
    std::vector<double> absolute, relative;
    for (const WithheldOutcome& o : outcomes)
    {
      if (o.input.truth == effect.kind && o.dominant == effect.kind)
      {
        const double truth = primaryValue(o.input);
        absolute.push_back(std::abs(o.recovered_magnitude - truth));
        relative.push_back(std::abs(o.recovered_magnitude - truth) / std::abs(truth));
      }
    }
    char row[256];
    std::snprintf(row, sizeof row, "| %s | %s | %zu | %.4g | %.1f%% |\n", effect.name.c_str(),
                  effect.parameters.front().name.c_str(), absolute.size(), medianOf(absolute), 100.0 * medianOf(relative));
    out << row;
  }
  return out.str();
}

std::vector<SemiRealCase> semiRealCaseGrid()
{
  std::vector<SemiRealCase> grid;
  for (double offset_s : {-1.0, -0.5, 0.5, 1.0, 2.0, 3.0})
  {
    grid.push_back({EffectKind::sensor_time_offset, offset_s});
  }
  for (double lag_s : {0.5, 1.0, 1.5, 2.0})
  {
    grid.push_back({EffectKind::actuation_lag, lag_s});
  }
  return grid;
}

std::vector<CarFollowingRun> injectCase(const std::vector<CarFollowingRun>& runs, const SemiRealCase& c)
{
  if (c.injected != EffectKind::none && c.injected != EffectKind::sensor_time_offset &&
      c.injected != EffectKind::actuation_lag)
  {
    throw std::invalid_argument("no injection for effect " + effectName(c.injected));
  }
  std::vector<CarFollowingRun> out;
  for (const CarFollowingRun& run : runs)
  {
    if (c.injected == EffectKind::sensor_time_offset)
    {
      out.push_back(injectSensorTimeOffset(run, c.magnitude));
    }
    else if (c.injected == EffectKind::actuation_lag)
    {
      out.push_back(injectActuationLag(run, c.magnitude));
    }
    else
    {
      out.push_back(run);
    }
  }
  return out;
}

DiagnosisResult diagnoseSemiReal(const std::vector<CarFollowingRun>& runs, const DiagnosisOptions& options)
{
  DiagnosisOptions chosen = options;
  chosen.with_stability_test = false;
  chosen.forward_selection = true;
  return diagnoseRuns(runs, chosen);
}

std::optional<double> selectedMagnitude(const DiagnosisResult& result, EffectKind kind)
{
  if (!result.selected_effects.empty())
  {
    const AugmentedFit& last = result.selected_effects.back().model.fit;
    const std::vector<EffectKind> effects = effectsOf(last);
    if (std::find(effects.begin(), effects.end(), kind) != effects.end())
    {
      return effectValues(kind, last.settings).front();
    }
  }
  if (kind != EffectKind::none && result.selection.dominant == kind)
  {
    return effectValues(kind, dominantModel(result).fit.settings).front();
  }
  return std::nullopt;
}

namespace
{
/// The single-effect fit of kind (nullptr when kind was not a candidate).
const AugmentedFit* singleFit(const DiagnosisResult& result, EffectKind kind)
{
  for (const ModelDiagnosis& model : result.effects)
  {
    if (model.fit.effect == kind && !model.fit.effect_values.empty())
    {
      return &model.fit;
    }
  }
  return nullptr;
}

/// kind's first parameter in its single-effect fit (NaN when kind was not a candidate).
double singleFitMagnitude(const DiagnosisResult& result, EffectKind kind)
{
  const AugmentedFit* fit = singleFit(result, kind);
  return fit ? fit->effect_values.front() : std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

double SemiRealOutcome::foundMagnitude() const
{
  return selected ? recoveredMagnitude() : determined ? singleFitShift() : std::numeric_limits<double>::quiet_NaN();
}

bool SemiRealOutcome::detectable() const
{
  return !std::isfinite(baseline_standard_error) || std::abs(expectedNet()) >= detection_z * baseline_standard_error;
}

bool SemiRealOutcome::foundWithin(double tolerance) const
{
  return found() && std::abs(foundMagnitude() - expected_magnitude) <= tolerance * std::abs(expected_magnitude);
}

bool SemiRealOutcome::misattributed(double tolerance) const
{
  const bool other_named = std::any_of(chain.begin(), chain.end(), [&](EffectKind kind) {
    return kind != input.injected && std::find(baseline_chain.begin(), baseline_chain.end(), kind) == baseline_chain.end();
  });
  return other_named || (found() && !foundWithin(tolerance));
}

bool SemiRealOutcome::passed(double tolerance) const
{
  if (input.injected == EffectKind::none)
  {
    return true;  // the baseline is a measurement, not a check
  }
  // Found at its size passes wherever the limit puts the case: the limit predicts whether the data
  // can be asked to find it, and a find below it is judged as one above it (another timing effect
  // named beside it is a stand-in there, allowed above the limit, so it is allowed below it too).
  return foundWithin(tolerance) || (!detectable() && !misattributed(tolerance));
}

namespace
{
double expectedMagnitude(const SemiRealCase& c, const DiagnosisResult& baseline)
{
  return c.injected == EffectKind::actuation_lag ? closedLoopLagReading(c.magnitude, finalModel(baseline).fit.base)
                                                 : c.magnitude;
}

/// kind among the diagnosis's determined effects (nullptr when it is not).
const DeterminedEffect* determinedOf(const DiagnosisResult& result, EffectKind kind)
{
  const auto found = std::find_if(result.determined.begin(), result.determined.end(),
                                  [kind](const DeterminedEffect& e) { return e.effect == kind; });
  return found == result.determined.end() ? nullptr : &*found;
}

/// The standard error of a single-effect fit's (first) effect parameter: NaN without a fit.
double effectStandardError(const AugmentedFit* fit)
{
  return fit != nullptr ? effectSizeIn(*fit, fit->effect, 0.0).standard_error : std::numeric_limits<double>::quiet_NaN();
}

double baselineEstimate(const DiagnosisResult& baseline, EffectKind kind)
{
  if (const std::optional<double> named = selectedMagnitude(baseline, kind))
  {
    return *named;
  }
  const DeterminedEffect* determined = determinedOf(baseline, kind);
  return determined ? determined->value : 0.0;
}
}  // namespace

SemiRealOutcome runSemiRealCase(const SemiRealSet& set, const SemiRealCase& c, const DiagnosisResult& baseline,
                                const DiagnosisOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  const DiagnosisResult result =
      c.injected == EffectKind::none ? baseline : diagnoseSemiReal(injectCase(set.runs, c), options);
  SemiRealOutcome outcome;
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.set_name = set.name;
  outcome.input = c;
  outcome.dominant = result.selection.dominant;
  outcome.chain = selectedChain(result);
  outcome.base_test_rmse_speed_mps = result.baseline.test_rmse_speed_mps;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::optional<double> fitted = selectedMagnitude(result, c.injected);
  outcome.selected = c.injected != EffectKind::none && fitted.has_value();
  outcome.determined = c.injected != EffectKind::none && determinedOf(result, c.injected) != nullptr;
  outcome.fitted_magnitude = fitted.value_or(nan);
  outcome.baseline_magnitude = selectedMagnitude(baseline, c.injected).value_or(0.0);
  outcome.single_fit_magnitude = singleFitMagnitude(result, c.injected);
  outcome.baseline_single_fit_magnitude = singleFitMagnitude(baseline, c.injected);
  outcome.baseline_chain = selectedChain(baseline);
  if (c.injected != EffectKind::none)
  {
    outcome.expected_magnitude = expectedMagnitude(c, baseline);
    outcome.baseline_estimate = baselineEstimate(baseline, c.injected);
    outcome.baseline_standard_error = effectStandardError(singleFit(baseline, c.injected));
    if (!std::isfinite(outcome.baseline_standard_error) && !baseline.train.empty())
    {
      const AugmentedFit held = calibrateWithEffectHeld(c.injected, {outcome.expectedNet()}, baseline.train,
                                                        options.calibration, &baseline.baseline.fit);
      outcome.baseline_standard_error = effectStandardError(&held);
      outcome.standard_error_at_expected_size = std::isfinite(outcome.baseline_standard_error);
    }
    outcome.detection_z = determinedThreshold(options.selection.alpha, options.candidates);
  }
  return outcome;
}

namespace
{
std::string formatDouble(const char* format, double x)
{
  char text[64];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

std::string semiRealConfusion(const std::vector<SemiRealOutcome>& outcomes)
{
  const std::vector<EffectKind> labels = diagnosableEffects();
  const std::vector<EffectKind> rows{EffectKind::none, EffectKind::sensor_time_offset, EffectKind::actuation_lag};
  std::ostringstream out;
  out << "| injected \\ dominant named |";
  for (EffectKind label : labels)
  {
    out << " " << effectName(label) << " |";
  }
  out << "\n|---|";
  for (std::size_t i = 0; i < labels.size(); ++i)
  {
    out << "---|";
  }
  out << "\n";
  for (EffectKind row : rows)
  {
    out << "| " << (row == EffectKind::none ? std::string("none (baseline)") : effectName(row)) << " |";
    for (EffectKind label : labels)
    {
      const auto count = std::count_if(outcomes.begin(), outcomes.end(), [&](const SemiRealOutcome& o) {
        return o.input.injected == row && o.dominant == label;
      });
      out << " " << count << " |";
    }
    out << "\n";
  }
  return out.str();
}
}  // namespace

namespace
{
/// Per set and injected effect, one column per injected value: what the diagnosis named, and the
/// recovered value where it named the injected effect. Says from which size on an injection is
/// seen on top of the real run's own errors.
std::string semiRealDetection(const std::vector<SemiRealOutcome>& outcomes)
{
  std::vector<double> values;
  for (const SemiRealOutcome& o : outcomes)
  {
    if (o.input.injected != EffectKind::none &&
        std::find(values.begin(), values.end(), o.input.magnitude) == values.end())
    {
      values.push_back(o.input.magnitude);
    }
  }
  std::sort(values.begin(), values.end());
  std::ostringstream out;
  out << "| set | injected |";
  for (double v : values)
  {
    out << " " << formatDouble("%+.1f s", v) << " |";
  }
  out << "\n|---|---|";
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    out << "---|";
  }
  out << "\n";
  std::vector<std::pair<std::string, EffectKind>> rows;
  for (const SemiRealOutcome& o : outcomes)
  {
    const std::pair<std::string, EffectKind> row{o.set_name, o.input.injected};
    if (o.input.injected != EffectKind::none && std::find(rows.begin(), rows.end(), row) == rows.end())
    {
      rows.push_back(row);
    }
  }
  for (const auto& [set, kind] : rows)
  {
    out << "| " << set << " | " << effectName(kind) << " |";
    for (double v : values)
    {
      const auto o = std::find_if(outcomes.begin(), outcomes.end(), [&](const SemiRealOutcome& x) {
        return x.set_name == set && x.input.injected == kind && x.input.magnitude == v;
      });
      if (o == outcomes.end())
      {
        out << " |";
        continue;
      }
      const std::string found = o->selected     ? "**named " + formatDouble("%+.2f", o->foundMagnitude()) + "**"
                                : o->determined ? "determined " + formatDouble("%+.2f", o->foundMagnitude())
                                                : std::string("not found");
      const std::string expected = kind == EffectKind::actuation_lag ? formatDouble(" of %.2f", o->expected_magnitude) : "";
      out << " " << found << (o->found() ? expected : "") << (o->detectable() ? "" : " (below the limit)")
          << (o->selected || o->chain.empty() ? "" : " (named: " + chainText(o->chain) + ")") << (o->passed() ? "" : " FAIL")
          << " |";
    }
    out << "\n";
  }
  return out.str();
}
}  // namespace

std::string formatSemiRealTables(const std::vector<SemiRealOutcome>& outcomes)
{
  std::ostringstream out;
  out << semiRealConfusion(outcomes) << "\n" << semiRealDetection(outcomes) << "\n";
  out << "| set | injected | value [s] | expected [s] | untouched estimate +- SE | net / SE | dominant | chain | "
         "determined | selected: fitted | recovered | single fit | shift | found | pass | time [s] |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::size_t checks = 0, detectable = 0, found_within = 0, named_within = 0, below = 0, below_clean = 0,
              below_found = 0, shifts_within = 0, passed = 0;
  for (const SemiRealOutcome& o : outcomes)
  {
    const bool check = o.input.injected != EffectKind::none;
    auto number = [](double x) { return std::isfinite(x) ? formatDouble("%.3f", x) : std::string("-"); };
    out << "| " << o.set_name << " | " << effectName(o.input.injected) << " | " << formatDouble("%.2f", o.input.magnitude)
        << " | " << (check ? number(o.expected_magnitude) : "-") << " | "
        << (check ? number(o.baseline_estimate) + " +- " + number(o.baseline_standard_error) +
                        (o.standard_error_at_expected_size ? " (at the expected size)" : "")
                  : "-")
        << " | "
        << (check ? formatDouble("%.1f", std::abs(o.expectedNet()) / o.baseline_standard_error) : "-") << " | "
        << effectName(o.dominant) << " | " << chainText(o.chain) << " | " << (check ? (o.determined ? "yes" : "no") : "-")
        << " | " << number(o.fitted_magnitude) << " | " << number(o.recoveredMagnitude()) << " | "
        << number(o.single_fit_magnitude) << " | " << (check ? number(o.singleFitShift()) : "-") << " | "
        << (check ? number(o.foundMagnitude()) : "-") << " | "
        << (check ? std::string(o.passed() ? "yes" : "NO") + (o.detectable() ? "" : " (below)") : "-") << " | "
        << formatDouble("%.1f", o.seconds) << " |\n";
    if (!check)
    {
      continue;
    }
    ++checks;
    detectable += o.detectable() ? 1 : 0;
    found_within += o.detectable() && o.foundWithin() ? 1 : 0;
    named_within += o.detectable() && o.selected && o.foundWithin() ? 1 : 0;
    below += o.detectable() ? 0 : 1;
    below_clean += !o.detectable() && !o.misattributed() ? 1 : 0;
    below_found += !o.detectable() && o.foundWithin() ? 1 : 0;
    passed += o.passed() ? 1 : 0;
    shifts_within += std::abs(o.singleFitShift() - o.expected_magnitude) <= 0.25 * std::abs(o.expected_magnitude) ? 1 : 0;
  }
  out << "\ndetectable (net effect at least z standard errors of the untouched runs from none): " << detectable << " of "
      << checks << "; of them found within 25% of the expected size: " << found_within << " (named by the held-out rule: "
      << named_within << "); below the limit: " << below << ", nothing misattributed in " << below_clean
      << ", found at its size in " << below_found << "; passed: " << passed << " of " << checks
      << "; single-fit shift within 25% of the expected size: " << shifts_within << " of " << checks << "\n";
  return out.str();
}

}  // namespace acc
