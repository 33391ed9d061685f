// The string-stability test as text, for the calibrate tool (the JSON is in string_stability_verdict_json.cpp).
#include <cmath>
#include <cstdio>
#include <ostream>

#include "acc_identification/calibration/string_stability_verdict.h"

namespace acc
{
namespace
{
std::string sideFitLine(const char* label, const SideFit& fit)
{
  char line[400];
  if (!fit.found)
  {
    std::snprintf(line, sizeof line, "  %-26s none found\n", label);
    return line;
  }
  const AccParameters& p = fit.parameters;
  std::snprintf(line, sizeof line,
                "  %-26s k1 %.4f k2 %.4f tau_e %.4f eta %.3f  margin %+.3f  speed RMSE train %.3f, held-out %.3f m/s%s\n",
                label, p.k1_per_s2, p.k2_per_s, p.tau_e_s, p.eta_m, fit.margin, fit.train_rmse_speed_mps,
                fit.test_rmse_speed_mps, fit.unconstrained_optimum ? "  (the unconstrained optimum)" : "");
  return line;
}

std::string marginEnd(double value)
{
  if (std::isinf(value))
    return value > 0 ? "+inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%+.3f", value);
  return text;
}

}  // namespace

std::string allowedMarginsText(const StabilityTestResult& result)
{
  std::vector<std::array<double, 2>> pieces = result.margin_allowed_pieces;
  if (pieces.empty())
    pieces.push_back({result.margin_low, result.margin_high});
  std::string text;
  for (const auto& [low, high] : pieces)
    text += (text.empty() ? "[" : " and [") + marginEnd(low) + ", " + marginEnd(high) + "]";
  return text;
}

namespace
{
}  // namespace

void printStabilityTest(const StabilityTestResult& result, std::ostream& out)
{
  char line[400];
  std::snprintf(line, sizeof line,
                "String stability decided from the data, fixed-sample test (one look at all the data: each run's first "
                "half fits, its second half judges; "
                "alpha %.3g):\n",
                result.alpha);
  out << line;
  // THE verdict, each p-value named by the hypothesis it tests: nothing above (a point estimate's
  // lambda2) competes with it.
  out << "  verdict: " << verdictText(result, "  ") << "\n";
  if (result.tested)
  {
    out << sideFitLine("best string-stable model", result.best_stable);
    out << sideFitLine("best string-unstable model", result.best_unstable);
    out << "  margins k1 tau_e^2 + 2 k2 tau_e - 2 the data allow: " << allowedMarginsText(result);
    if (!result.margin_interval_note.empty())
      out << " (" << result.margin_interval_note << ")";
    out << "\n";
    std::snprintf(line, sizeof line,
                  "  (%zu held-out samples in %zu segments; moving-block bootstrap, %zu replicates of %.1f s blocks, "
                  "seed %llu; %.3f s)\n",
                  result.held_out_samples, result.held_out_segments, result.bootstrap_replicates,
                  result.block_length_s, static_cast<unsigned long long>(result.seed), result.solve_time_s);
    out << line;
  }
  out << "  why: " << result.reason << "\n";
}

std::string pValueHypothesis(const StabilityTestResult& result)
{
  switch (result.verdict)
  {
    case StabilityVerdict::Unstable: return "stable";
    case StabilityVerdict::Stable: return "unstable";
    case StabilityVerdict::Undecided: break;
  }
  return result.p_value_stable_rejected <= result.p_value_unstable_rejected ? "stable" : "unstable";
}

}  // namespace acc
