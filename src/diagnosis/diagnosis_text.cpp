#include "acc_identification/diagnosis/diagnosis_text.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "acc_identification/diagnosis/determined_effects.h"
#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
/// Each model's adequacy, then THE verdict: the final model's test where the diagnosis found a
/// better model, the base model's otherwise, and why.
void printVerdict(const DiagnosisResult& r, std::FILE* out)
{
  const DiagnosisVerdict verdict = statedVerdict(r);
  std::fprintf(out, "model adequacy, base model: %s\n", describeAdequacy(r.baseline_adequacy).c_str());
  if (!r.selected_effects.empty())
    std::fprintf(out, "model adequacy, %s: %s\n", verdict.model.c_str(), describeAdequacy(r.final_adequacy).c_str());
  std::fprintf(out, "verdict (string-stability test of the %s): %s\n  why this model: %s\n", verdict.model.c_str(),
              verdict.test ? verdictText(*verdict.test).c_str() : "not tested", verdict.why.c_str());
}

/// Whether the training data pin the size of the effect a step adds: the held-out rule can name
/// an effect whose size they leave open.
std::string describeAddedSize(const ForwardSelectionStep& step)
{
  const EffectSize& size = step.added_size;
  char text[256];
  if (!std::isfinite(size.z))
  {
    std::snprintf(text, sizeof text, "size of %s: not judged (%s)", effectName(step.added).c_str(),
                  std::isfinite(neutralValue(step.added)) ? "no finite standard error" : "no none value in its range");
  }
  else
  {
    std::snprintf(text, sizeof text, "size of %s: %s (%.1f standard errors from none%s)%s", effectName(step.added).c_str(),
                  size.determined ? "determined by the training data" : "NOT determined by the training data", size.z,
                  size.at_bound ? ", at a bound of its range" : "",
                  bootstrapVerdictText(size).c_str());
  }
  return text;
}

/// The forward selection's chain: one line per step with its held-out RMSE, gain and verdict,
/// then the parameters of that step's model with their standard errors and whether the training
/// data pin the added effect's size.
void printChain(const DiagnosisResult& r, std::FILE* out)
{
  std::fprintf(out, "effects in combination (forward selection): %s\n",
              r.selected_effects.empty() ? "none" : "");
  for (std::size_t i = 0; i < r.selected_effects.size(); ++i)
  {
    const ForwardSelectionStep& step = r.selected_effects[i];
    const ModelDiagnosis& m = step.model;
    std::fprintf(out, "  %zu. + %-26s test_v %.4f m/s, test_gap %.3f m, MSE -%.1f%% of the previous model's (lower bound %.4g m^2/s^2), %s",
                i + 1, effectName(step.added).c_str(), m.test_rmse_speed_mps, m.test_rmse_gap_m,
                100.0 * m.improvement.relative, m.improvement.lower_bound,
                m.stability.string_stable ? "point estimate stable" : "point estimate unstable");
    if (step.stability_test)
    {
      std::fprintf(out, ", test: %s", verdictText(*step.stability_test).c_str());
    }
    // No standard error (a diverged fit, or speeds that do not move with a parameter at the fit,
    // as a limit that never binds): "n/a", never "nan".
    auto se = [&m](std::size_t i) {
      const double error = i < m.fit.standard_errors.size() ? m.fit.standard_errors[i] : NAN;
      return std::isfinite(error) ? printfText("+- %.2g", error) : std::string("+- n/a");
    };
    std::fprintf(out, "\n     k1 %.4g %s, k2 %.4g %s, tau_e %.4g %s, eta %.4g %s", m.fit.base.k1_per_s2, se(0).c_str(),
                m.fit.base.k2_per_s, se(1).c_str(), m.fit.base.tau_e_s, se(2).c_str(), m.fit.base.eta_m, se(3).c_str());
    const std::vector<std::string> names = effectParameterNames(effectsOf(m.fit));
    for (std::size_t j = 0; j < names.size() && j < m.fit.effect_values.size(); ++j)
    {
      std::fprintf(out, ", %s %.4g %s", names[j].c_str(), m.fit.effect_values[j],
                  se(AugmentedParameterBox::kBaseDimension + j).c_str());
    }
    std::fprintf(out, "\n     %s\n", describeAddedSize(step).c_str());
  }
  std::fprintf(out, "  stopped: %s\n", r.forward_stop_reason.c_str());
}

}  // namespace

/// The perturbation-window criterion, beside the whole-run ranking above it.
void printPerturbationWindows(const PerturbationWindowCriterion& c, std::FILE* out)
{
  const std::string base_rmse = std::isfinite(c.base_window_rmse_speed_mps)
                                    ? printfText("%.4f m/s", c.base_window_rmse_speed_mps)
                                    : std::string("none (no window)");
  std::fprintf(out, "inside the leaders' perturbations of the held-out parts (%zu; the pair-level criterion beside the "
                    "whole-run one): base window speed RMSE %s\n",
               c.perturbations, base_rmse.c_str());
  if (!c.reason.empty())
  {
    std::fprintf(out, "  not judged: %s\n", c.reason.c_str());
    return;
  }
  for (const PerturbationWindowScore& e : c.effects)
  {
    std::fprintf(out, "  %-26s window_v %.4f  MSE %+.1f%%  p %.4f (alone %.4f)%s\n", effectName(e.effect).c_str(),
                 e.window_rmse_speed_mps, -100.0 * e.versus_base.relative_improvement, e.family_p_value,
                 e.versus_base.p_value, e.significant ? "  significant" : "");
  }
  std::fprintf(out, "  named on the perturbation windows: %s\n", effectName(c.named).c_str());
}

void printDiagnosisSummary(const DiagnosisResult& r, std::FILE* out)
{
  if (r.held_out_whole_runs)
    std::fprintf(out, "fitted on %zu run(s) whole, scored on %zu run(s) kept aside\n", r.train.size(), r.test.size());
  if (!r.steady_training.empty())
    std::fprintf(out, "the parts fitted on: %s: the fits below leave open what these data do not pin, and no model's "
                      "stability is stated\n", r.steady_training.c_str());
  std::fprintf(out, "%-26s %10s %10s %10s %9s %11s  %s\n", "model", "train_v", "test_v", "test_gap", "improve", "significant",
              "point estimate's stability (not a verdict)");
  const bool steady = !r.steady_training.empty();
  auto row = [out, steady](const ModelDiagnosis& m, bool is_base) {
    const std::string stability =
        steady ? "- (steady data)"
               : printfText("%s (peak %.3f dB)", m.stability.string_stable ? "stable" : "UNSTABLE", m.stability.peak_gain_db);
    std::fprintf(out, "%-26s %10.4f %10.4f %10.3f %8.1f%% %11s  %s\n", effectName(m.fit.effect).c_str(),
                m.train_rmse_speed_mps, m.test_rmse_speed_mps, m.test_rmse_gap_m, 100.0 * m.improvement.relative,
                is_base ? "-" : (m.significant ? "yes" : "no"), stability.c_str());
  };
  row(r.baseline, true);
  for (const ModelDiagnosis& m : r.effects)
  {
    row(m, false);
  }
  if (!r.selection.candidates.empty())
    std::fprintf(out, "significant: bound above 0 at level %.4g per effect (family-wise %g over %zu effects; Bonferroni's %.4g)\n",
                 r.selection.level, r.selection.family_wise_alpha, r.selection.candidates.size(),
                 r.selection.family_wise_alpha / static_cast<double>(r.selection.candidates.size()));
  std::fprintf(out, "dominant effect: %s; plausible:", effectName(r.selection.dominant).c_str());
  for (EffectKind kind : r.selection.plausible)
  {
    std::fprintf(out, " %s", effectName(kind).c_str());
  }
  std::fprintf(out, "%s\n", r.selection.plausible.empty() ? " (none)" : "");
  printPerturbationWindows(r.perturbation_windows, out);
  // What the training data pin down, named by the held-out rule or not (determined_effects.h).
  std::fprintf(out, "determined by the training data (size away from none, Bonferroni):%s\n", r.determined.empty() ? " none" : "");
  for (const DeterminedEffect& e : r.determined)
  {
    std::fprintf(out, "  %s\n", describeDeterminedEffect(e).c_str());
  }
  for (const UnmeasuredEffect& e : r.unmeasured)
  {
    std::fprintf(out, "  not measurable here: %s\n", describeUnmeasuredEffect(e).c_str());
  }
  if (r.stability_test)
  {
    const AugmentedStabilityTestResult& t = *r.stability_test;
    std::fprintf(out, "string-stability test of the %s model on the held-out parts: %s\n  why: %s\n",
                effectName(t.effect).c_str(), verdictText(t).c_str(), t.reason.c_str());
  }
  printChain(r, out);
  if (r.final_bootstrap)
  {
    std::ostringstream text;
    printRefitBootstrap(*r.final_bootstrap, text);
    std::fprintf(out, "final model (%s):\n%s", combinedEffectName(effectsOf(finalModel(r).fit)).c_str(),
                 text.str().c_str());
  }
  printVerdict(r, out);
}

void writeUnusedRunNotes(const DiagnosisResult& result, std::ostream& log)
{
  for (const std::string& note : result.notes)
    log << "note: " << note << "\n";
  if (!result.notes.empty())  // said only when there is something to say
    log << result.notes.size() << " run(s) or part(s) not used\n";
}

}  // namespace acc
