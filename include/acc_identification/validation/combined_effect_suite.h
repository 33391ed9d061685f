#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/validation/withheld_effect_suite.h"

namespace acc
{
/// Effects in combination, withheld: every pair of the six candidate effects hidden in one
/// synthetic run at once (the first magnitude of each in withheldCaseGrid's list, the steps
/// profile, noise as the suite's), 15 cases, seeds 101 on. The question: does the forward
/// selection's chain name both, and recover each magnitude?
std::vector<WithheldCase> combinedCaseGrid();

/// What the diagnosis said about one pair.
struct CombinedOutcome
{
  WithheldCase input;
  std::vector<std::pair<EffectKind, double>> withheld;  ///< each hidden effect and its true first parameter
  std::vector<double> fitted;             ///< per withheld effect: selectedMagnitude (NaN when not named)
  std::vector<EffectKind> chain;          ///< the forward selection's effects, dominant first
  double base_test_rmse_speed_mps = 0.0;
  double final_test_rmse_speed_mps = 0.0;  ///< of the last model of the chain (the base model's when empty)
  double seconds = 0.0;                    ///< wall time of the diagnosis

  /// How many of the withheld effects the chain names.
  std::size_t named() const;
  /// Effects the chain names that were not withheld.
  std::vector<EffectKind> extra() const;
};

/// Diagnoses the case's run with forward selection on and no string-stability test (not the
/// question here, and it doubles the cost).
CombinedOutcome runCombinedCase(const WithheldCase& c, const DiagnosisOptions& options);

/// Markdown: one row per pair (chain, each magnitude fitted against the truth, held-out RMSE base
/// to chain), then one row per effect (named in how many of the pairs that hid it, named wrongly
/// in how many of the others, median magnitude error when named), then the totals.
std::string formatCombinedTables(const std::vector<CombinedOutcome>& outcomes);

}  // namespace acc
