#include "acc_identification/validation/combined_effect_suite.h"
#include "acc_identification/validation/withheld_effect_suite.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

namespace acc
{
namespace
{
/// The first magnitude of withheldCaseGrid's list for each effect: one case per effect there.
std::vector<double> firstMagnitude(EffectKind kind)
{
  const std::vector<WithheldCase> one_each = withheldCaseGrid(1, {SyntheticLeadProfile::steps}, {1.0}, 1);
  for (const WithheldCase& c : one_each)
  {
    if (c.truth == kind)
    {
      return c.truth_values;
    }
  }
  return {};
}

bool contains(const std::vector<EffectKind>& list, EffectKind kind)
{
  return std::find(list.begin(), list.end(), kind) != list.end();
}

std::string text(const char* format, double x)
{
  if (!std::isfinite(x))
  {
    return "-";
  }
  char out[64];
  std::snprintf(out, sizeof out, format, x);
  return out;
}

double relativeError(double fitted, double truth) { return (fitted - truth) / std::abs(truth); }

}  // namespace

std::vector<WithheldCase> combinedCaseGrid()
{
  std::vector<WithheldCase> grid;
  const std::vector<CandidateEffect>& effects = candidateEffects();
  std::uint32_t seed = 101;
  for (std::size_t i = 0; i < effects.size(); ++i)
  {
    for (std::size_t j = i + 1; j < effects.size(); ++j)
    {
      WithheldCase c;
      c.truth = effects[i].kind;
      c.truth_values = firstMagnitude(effects[i].kind);
      c.also_withheld = {{effects[j].kind, firstMagnitude(effects[j].kind)}};
      c.profile = SyntheticLeadProfile::steps;
      c.seed = seed++;
      grid.push_back(c);
    }
  }
  return grid;
}

std::size_t CombinedOutcome::named() const
{
  return static_cast<std::size_t>(std::count_if(withheld.begin(), withheld.end(),
                                                [&](const auto& hidden) { return contains(chain, hidden.first); }));
}

std::vector<EffectKind> CombinedOutcome::extra() const
{
  std::vector<EffectKind> out;
  for (EffectKind kind : chain)
  {
    const bool hidden = std::any_of(withheld.begin(), withheld.end(), [&](const auto& h) { return h.first == kind; });
    if (!hidden)
    {
      out.push_back(kind);
    }
  }
  return out;
}

CombinedOutcome runCombinedCase(const WithheldCase& c, const DiagnosisOptions& options)
{
  DiagnosisOptions chain_only = options;
  chain_only.with_stability_test = false;
  chain_only.forward_selection = true;
  const auto start = std::chrono::steady_clock::now();
  const DiagnosisResult result = diagnoseRuns({synthesizeWithheldRun(c)}, chain_only);
  CombinedOutcome outcome;
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.input = c;
  outcome.withheld.emplace_back(c.truth, c.truth_values.front());
  for (const auto& [kind, values] : c.also_withheld)
  {
    outcome.withheld.emplace_back(kind, values.front());
  }
  outcome.chain = selectedChain(result);
  if (outcome.chain.empty() && result.selection.dominant != EffectKind::none)
  {
    outcome.chain.push_back(result.selection.dominant);  // forward selection found nothing on top
  }
  for (const auto& hidden : outcome.withheld)
  {
    outcome.fitted.push_back(selectedMagnitude(result, hidden.first).value_or(std::numeric_limits<double>::quiet_NaN()));
  }
  outcome.base_test_rmse_speed_mps = result.baseline.test_rmse_speed_mps;
  outcome.final_test_rmse_speed_mps = finalModel(result).test_rmse_speed_mps;
  return outcome;
}

namespace
{
std::string caseTable(const std::vector<CombinedOutcome>& outcomes)
{
  std::ostringstream out;
  out << "| withheld | true values | chain named | fitted (error) | both named | held-out RMSE base -> chain [m/s] | "
         "time [s] |\n|---|---|---|---|---|---|---|\n";
  for (const CombinedOutcome& o : outcomes)
  {
    std::string names, truths, fitted;
    for (std::size_t i = 0; i < o.withheld.size(); ++i)
    {
      const std::string sep = i == 0 ? "" : ", ";
      names += sep + effectName(o.withheld[i].first);
      truths += sep + text("%.3g", o.withheld[i].second);
      fitted += sep + (std::isfinite(o.fitted[i]) ? text("%.3g", o.fitted[i]) + " (" +
                                                        text("%+.0f%%", 100.0 * relativeError(o.fitted[i], o.withheld[i].second)) + ")"
                                                  : std::string("-"));
    }
    out << "| " << names << " | " << truths << " | " << chainText(o.chain) << " | " << fitted << " | "
        << (o.named() == o.withheld.size() ? "yes" : "NO") << " | " << text("%.3f", o.base_test_rmse_speed_mps)
        << " -> " << text("%.3f", o.final_test_rmse_speed_mps) << " | " << text("%.1f", o.seconds) << " |\n";
  }
  return out.str();
}

std::string effectTable(const std::vector<CombinedOutcome>& outcomes)
{
  std::ostringstream out;
  out << "| effect | named where withheld | named where not withheld | median abs. magnitude error when named |\n"
         "|---|---|---|---|\n";
  // Every effect the diagnosis can name, so that a response effect named where none was hidden
  // counts as named wrongly.
  for (EffectKind kind : diagnosableEffects())
  {
    if (kind == EffectKind::none)
      continue;
    const CandidateEffect& effect = candidateEffect(kind);
    std::size_t hidden = 0, found = 0, others = 0, wrongly = 0;
    std::vector<double> errors;
    for (const CombinedOutcome& o : outcomes)
    {
      const bool named = contains(o.chain, effect.kind);
      bool was_hidden = false;
      for (std::size_t i = 0; i < o.withheld.size(); ++i)
      {
        if (o.withheld[i].first != effect.kind)
        {
          continue;
        }
        was_hidden = true;
        if (named && std::isfinite(o.fitted[i]))
        {
          errors.push_back(std::abs(relativeError(o.fitted[i], o.withheld[i].second)));
        }
      }
      hidden += was_hidden ? 1 : 0;
      found += was_hidden && named ? 1 : 0;
      others += was_hidden ? 0 : 1;
      wrongly += !was_hidden && named ? 1 : 0;
    }
    out << "| " << effectName(effect.kind) << " | " << found << " of " << hidden << " | " << wrongly << " of "
        << others << " | " << text("%.0f%%", 100.0 * medianOf(errors)) << " |\n";
  }
  return out.str();
}
}  // namespace

std::string formatCombinedTables(const std::vector<CombinedOutcome>& outcomes)
{
  std::size_t both = 0, one = 0, neither = 0, with_extra = 0;
  for (const CombinedOutcome& o : outcomes)
  {
    const std::size_t named = o.named();
    both += named == o.withheld.size() ? 1 : 0;
    one += named > 0 && named < o.withheld.size() ? 1 : 0;
    neither += named == 0 ? 1 : 0;
    with_extra += o.extra().empty() ? 0 : 1;
  }
  std::ostringstream out;
  out << caseTable(outcomes) << "\n" << effectTable(outcomes) << "\n";
  out << "pairs: " << outcomes.size() << "; both named: " << both << "; one named: " << one << "; neither: " << neither
      << "; chain names an effect not withheld: " << with_extra << "\n";
  return out.str();
}

}  // namespace acc
