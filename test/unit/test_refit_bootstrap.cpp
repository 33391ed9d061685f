// The refitting bootstrap (calibration/refit_bootstrap.h): on a minute of data its intervals hold
// where value +- t se runs short, and its draws are the seed's alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "acc_identification/calibration/calibrate_runs.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/refit_bootstrap.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/synthesis/synthetic_runs.h"

namespace
{
constexpr const char* kQuantities[] = {"k1", "k2", "tau_e", "eta", "stability_margin"};
constexpr std::size_t kCount = sizeof kQuantities / sizeof kQuantities[0];

acc::CarFollowingRun minuteDrive(std::uint32_t seed, const acc::MeasurementNoise& noise = {})
{
  return acc::synthesizeRun(acc::paperMinimumSetting(), 60.0, 0.1, 20.0, seed, noise);
}

bool covers(double low, double high, double reference)
{
  return low <= reference && reference <= high;
}
}  // namespace

// Seeded drives behind the paper's minimum setting (the synthetic default noise), each against the
// noise-free fit of the same drive, as test_standard_error_coverage measures the sandwich: the
// bootstrap-t intervals cover k1, k2, tau_e and the margin where value +- t se does not.
// docs/RESULTS.md prints this table ("What the standard errors cover").
TEST(RefitBootstrap, CoversAMinuteOfDataWhereTheSandwichRunsShort)
{
  constexpr std::uint32_t kDrives = 60;
  double bootstrap[kCount] = {}, sandwich[kCount] = {}, bootstrap_width[kCount] = {}, sandwich_width[kCount] = {};
  double seconds = 0.0;
  std::size_t drives = 0;
  for (std::uint32_t seed = 1; seed <= kDrives; ++seed)
  {
    const acc::CarFollowingRun run = minuteDrive(seed);
    const acc::Identification noisy = acc::identifyAcc({run}, {});
    const acc::Identification clean = acc::identifyAcc({minuteDrive(seed, {0.0, 0.0, 0.0})}, {});
    ASSERT_TRUE(noisy.quantities && clean.quantities) << noisy.note << clean.note;
    const acc::RefitBootstrap refits = acc::bootstrapRefits(noisy.calibration.parameters, {run});
    ASSERT_TRUE(refits.note.empty()) << refits.note;
    EXPECT_EQ(refits.refitted, refits.replicates);
    seconds += refits.wall_time_s;
    ++drives;
    for (std::size_t i = 0; i < kCount; ++i)
    {
      const double reference = clean.quantities->find(kQuantities[i])->value;
      const acc::QuantityEstimate& estimate = *noisy.quantities->find(kQuantities[i]);
      const acc::BootstrapQuantity& resampled = *refits.find(kQuantities[i]);
      bootstrap[i] += covers(resampled.interval_95_low, resampled.interval_95_high, reference);
      sandwich[i] += covers(estimate.interval_95_low, estimate.interval_95_high, reference);
      bootstrap_width[i] += resampled.interval_95_high - resampled.interval_95_low;
      sandwich_width[i] += estimate.interval_95_high - estimate.interval_95_low;
    }
  }
  std::printf("%zu drives of 60 s, %.2f s per bootstrap of %zu replicates:\n", drives, seconds / drives,
              acc::RefitBootstrapOptions{}.replicates);
  double bootstrap_mean = 0.0, sandwich_mean = 0.0;
  for (std::size_t i = 0; i < kCount; ++i)
  {
    std::printf("  %-16s bootstrap-t covers %3.0f %% (mean width %.4g); value +- t se %3.0f %% (mean width %.4g)\n",
                kQuantities[i], 100.0 * bootstrap[i] / drives, bootstrap_width[i] / drives,
                100.0 * sandwich[i] / drives, sandwich_width[i] / drives);
    bootstrap_mean += bootstrap[i] / drives / kCount;
    sandwich_mean += sandwich[i] / drives / kCount;
  }
  EXPECT_GE(bootstrap_mean, 0.85);
  EXPECT_GE(bootstrap_mean, sandwich_mean + 0.05);
}

TEST(RefitBootstrap, TheSeedAloneDecidesTheDraws)
{
  const acc::CarFollowingRun run = minuteDrive(3);
  const acc::AccParameters fit = acc::identifyAcc({run}, {}).calibration.parameters;
  acc::RefitBootstrapOptions options;
  options.replicates = 40;
  options.threads = 1;
  const acc::RefitBootstrap one_thread = acc::bootstrapRefits(fit, {run}, options);
  options.threads = 2;
  const acc::RefitBootstrap two_threads = acc::bootstrapRefits(fit, {run}, options);
  options.seed += 1;
  const acc::RefitBootstrap other_seed = acc::bootstrapRefits(fit, {run}, options);
  for (const char* name : kQuantities)
  {
    EXPECT_EQ(one_thread.find(name)->interval_95_low, two_threads.find(name)->interval_95_low) << name;
    EXPECT_EQ(one_thread.find(name)->standard_error, two_threads.find(name)->standard_error) << name;
    EXPECT_NE(one_thread.find(name)->standard_error, other_seed.find(name)->standard_error) << name;
  }
}

// Several runs (segments between holes, or several files) of different lengths: every replicate
// of both is refitted, and each interval holds the fit's value.
TEST(RefitBootstrap, RefitsSeveralRunsOfDifferentLengthsTogether)
{
  const acc::CarFollowingRun first = minuteDrive(4);
  const acc::CarFollowingRun second = minuteDrive(5).slice(0, 400, " (40 s)");
  const acc::AccParameters fit = acc::identifyAcc({first, second}, {}).calibration.parameters;
  acc::RefitBootstrapOptions options;
  options.replicates = 40;
  const acc::RefitBootstrap refits = acc::bootstrapRefits(fit, {first, second}, options);
  ASSERT_TRUE(refits.note.empty()) << refits.note;
  EXPECT_EQ(refits.refitted, 40u);
  for (const char* name : kQuantities)
  {
    const acc::BootstrapQuantity& q = *refits.find(name);
    EXPECT_TRUE(q.interval_95_low < q.value && q.value < q.interval_95_high) << name << ": " << q.note;
  }
}

// calibrate makes it on short data only, and says so in the JSON and the text.
TEST(RefitBootstrap, CalibrateMakesItOnShortData)
{
  acc::CalibrateSettings settings;
  settings.quiet = true;
  settings.starts = 20;
  settings.stability_test = false;
  settings.bootstrap_replicates = 40;
  std::ostringstream text, log;
  const acc::CalibrateOutcome minute = acc::calibrateRuns({{minuteDrive(1), "minute.csv"}}, {}, settings, text, log);
  ASSERT_TRUE(minute.json.contains("refit_bootstrap")) << minute.json.dump(1);
  EXPECT_EQ(minute.json["refit_bootstrap"]["replicates"], 40);
  const nlohmann::json& k1 = minute.json["refit_bootstrap"]["quantities"]["k1"];
  EXPECT_TRUE(k1["interval_95"].is_array());
  // The standard error that scales the interval, and the refits' own beside it.
  EXPECT_GT(k1["fit_standard_error"].get<double>(), 0.0) << k1.dump();
  EXPECT_GT(k1["refits_standard_error_median"].get<double>(), 0.0) << k1.dump();
  EXPECT_NE(text.str().find("the refits' own"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("Refitting bootstrap"), std::string::npos) << text.str();
  settings.bootstrap_below_s = 50.0;
  EXPECT_FALSE(acc::calibrateRuns({{minuteDrive(1), "minute.csv"}}, {}, settings, text, log).json.contains(
      "refit_bootstrap"));
}

// A quantity held at a bound of the fit has no bootstrap interval, and says why.
TEST(RefitBootstrap, NoIntervalAtABound)
{
  const acc::CarFollowingRun run = minuteDrive(2);
  acc::AccParameters fit = acc::identifyAcc({run}, {}).calibration.parameters;
  fit.tau_e_s = 0.0;  // on the lower bound: the quantities it moves are held there
  acc::RefitBootstrapOptions options;
  options.replicates = 40;
  const acc::RefitBootstrap refits = acc::bootstrapRefits(fit, {run}, options);
  ASSERT_TRUE(refits.note.empty()) << refits.note;
  EXPECT_TRUE(std::isnan(refits.find("tau_e")->interval_95_low));
  EXPECT_NE(refits.find("tau_e")->note.find("bound"), std::string::npos);
  EXPECT_NE(refits.caution().find("tau_e"), std::string::npos) << refits.caution();
  EXPECT_TRUE(std::isfinite(refits.find("k2")->interval_95_low));
}

// The margin k1 tau_e^2 + 2 k2 tau_e - 2 cannot go below -2: near it, as near a parameter's bound,
// no interval (one reached -8.5 on a real car with tau_e near 0).
TEST(RefitBootstrap, NoMarginIntervalNearItsLeastValue)
{
  const acc::CarFollowingRun run = minuteDrive(2);
  acc::AccParameters fit = acc::identifyAcc({run}, {}).calibration.parameters;
  fit.tau_e_s = 0.02;  // near the lower bound: the margin near -2
  acc::RefitBootstrapOptions options;
  options.replicates = 40;
  const acc::RefitBootstrap refits = acc::bootstrapRefits(fit, {run}, options);
  ASSERT_TRUE(refits.note.empty()) << refits.note;
  const acc::BootstrapQuantity& margin = *refits.find("stability_margin");
  EXPECT_LT(margin.value, -1.9);
  EXPECT_TRUE(std::isnan(margin.interval_95_low)) << margin.interval_95_low;
  EXPECT_NE(margin.note.find("lower bound -2"), std::string::npos) << margin.note;
}

// Fewer refits than a 95 % interval needs (one in each 2.5 % tail: 39) give the refits' spread and
// bias but no interval, and say why: with one refit the "interval" was a point.
TEST(RefitBootstrap, NoIntervalFromTooFewRefits)
{
  const acc::CarFollowingRun run = minuteDrive(6);
  const acc::AccParameters fit = acc::identifyAcc({run}, {}).calibration.parameters;
  acc::RefitBootstrapOptions options;
  options.replicates = acc::kMinRefitsFor95Interval - 1;
  const acc::RefitBootstrap few = acc::bootstrapRefits(fit, {run}, options);
  ASSERT_TRUE(few.note.empty()) << few.note;
  for (const char* name : kQuantities)
  {
    const acc::BootstrapQuantity& q = *few.find(name);
    EXPECT_TRUE(std::isnan(q.interval_95_low) && std::isnan(q.interval_95_high)) << name;
    EXPECT_NE(q.note.find("needs at least 39"), std::string::npos) << name << ": " << q.note;
    EXPECT_TRUE(std::isfinite(q.standard_error)) << name;
  }
  options.replicates = acc::kMinRefitsFor95Interval;
  const acc::RefitBootstrap enough = acc::bootstrapRefits(fit, {run}, options);
  EXPECT_TRUE(std::isfinite(enough.find("k2")->interval_95_low)) << enough.find("k2")->note;
}
