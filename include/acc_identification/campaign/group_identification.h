#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "acc_identification/calibration/euler_step_bias.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/calibration/refit_bootstrap.h"
#include "acc_identification/calibration/string_stability_verdict.h"
#include "acc_identification/campaign/campaign_inputs.h"

namespace acc
{
/// Which groups get refitting bootstraps (calibration/refit_bootstrap.h) of their base fit and of
/// their diagnosed model: those whose runs span less than below_s [s], where standard errors run
/// short (as calibrate and diagnose decide), with `replicates` replicates each (0: none; the
/// campaign tool asks for 199), drawn from the group's seed.
struct ShortRunsBootstrapOptions
{
  std::size_t replicates = 0;
  double below_s = 300.0;
};

/// The paper's protocol for one (vehicle, setting) group.
struct GroupIdentificationOptions
{
  std::size_t starts = 100;   ///< Halton starts of every multistart (fit and test)
  double alpha = 0.05;        ///< level of the string-stability test
  std::uint64_t seed = 20240601;  ///< the campaign's seed; each group draws from its own stream
  ShortRunsBootstrapOptions bootstrap;
};

/// Whether a group's runs are short enough for its bootstraps (options.replicates > 0 and the runs
/// span less than options.below_s).
bool wantsShortRunsBootstrap(const std::vector<CarFollowingRun>& runs, const ShortRunsBootstrapOptions& options);

/// Everything the campaign reports of one group.
struct GroupResult
{
  std::string vehicle;
  std::string setting;
  std::size_t runs = 0;
  std::size_t samples = 0;
  Identification identification;       ///< identifyAcc on all the group's runs
  StabilityTestResult stability_test;  ///< testStringStability on held-out halves
  std::uint64_t seed = 0;              ///< the test's bootstrap seed (groupSeed)
  /// Why the parameters are NaN (no excitation, no fit, an exception), "" when a fit was made.
  std::string reason;
  /// Does the fit describe the group's runs (checks a-c of model_adequacy.h on all its runs); the
  /// campaign adds the dip check (d) from the platoon check's pair-level predictions.
  ModelAdequacy model_adequacy;
  /// What the Euler step at the data's rate does to the fit (calibrate's check); with a fit only.
  std::optional<EulerStepBias> euler_step_bias;
  /// The base fit's refitting bootstrap (bootstrapRefits, as calibrate's) when the group's runs
  /// are short (GroupIdentificationOptions::bootstrap); with a fit only.
  std::optional<RefitBootstrap> refit_bootstrap;

  /// A fit exists (solved, not diverged): the parameters that are determined are meaningful.
  bool fitted() const;
  /// k1, k2 and tau_e are determined: lambda2, the amplified band and the peak are meaningful.
  bool dynamicsDetermined() const;
};

/// The group's own seed: the campaign seed mixed with its vehicle and setting (streamSeed), so
/// that a group's numbers depend neither on the thread that computes it nor on the other groups.
std::uint64_t groupSeed(std::uint64_t seed, const std::string& vehicle, const std::string& setting);

/// identifyAcc on all the group's runs (options.starts Halton starts), then testStringStability
/// on the runs' halves warm-started from that fit, as the calibrate tool does. Never throws: a
/// group whose data lack excitation, or whose fit fails, gets a reason and no fit.
GroupResult identifyGroup(const CampaignGroup& group, const GroupIdentificationOptions& options);

}  // namespace acc
