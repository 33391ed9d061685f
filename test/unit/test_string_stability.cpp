#include <gtest/gtest.h>

#include <cmath>

#include "acc_identification/model/paper_settings.h"
#include "acc_identification/model/string_stability.h"


namespace
{
/// Brute-force maximum of |Gamma| on a fine grid: an independent check of the closed forms.
std::pair<double, double> gridPeak(const acc::AccParameters& p, double max_w, double step)
{
  double best_w = 0.0, best_db = acc::transferGainDb(p, 0.0);
  for (double w = step; w <= max_w; w += step)
  {
    const double db = acc::transferGainDb(p, w);
    if (db > best_db)
    {
      best_db = db;
      best_w = w;
    }
  }
  return {best_w, best_db};
}

/// Largest grid frequency with |Gamma| > 1: independent check of the closed-form band.
double gridBandUpper(const acc::AccParameters& p, double max_w, double step)
{
  double upper = 0.0;
  for (double w = step; w <= max_w; w += step)
  {
    if (acc::transferGain(p, w) > 1.0) upper = w;
  }
  return upper;
}
}  // namespace

// Table II prints lambda2 = 70.7 (minimum setting) and 8.36 (maximum setting): both reproduced.
TEST(StringStability, TableTwoLambda2)
{
  EXPECT_NEAR(acc::lambda2(acc::paperMinimumSetting()), 70.7, 0.05);
  EXPECT_NEAR(acc::lambda2(acc::paperMaximumSetting()), 8.36, 0.005);
  EXPECT_FALSE(acc::analyzeStringStability(acc::paperMinimumSetting()).string_stable);
  EXPECT_FALSE(acc::analyzeStringStability(acc::paperMaximumSetting()).string_stable);
}

// Section V-C: maximum setting amplifies below 0.118 rad/s, peak 0.386 dB at 0.062 rad/s. The
// closed-form band end is 0.11749 rad/s (the printed 0.118 is 0.4 % above it, as a read-off from
// a frequency grid would be); the peak is reproduced to the printed digits.
TEST(StringStability, MaximumSettingBandAndPeakMatchThePaper)
{
  const auto report = acc::analyzeStringStability(acc::paperMaximumSetting());
  EXPECT_NEAR(report.amplified_band_upper_rad_s, 0.11749, 0.00001);
  EXPECT_NEAR(report.amplified_band_upper_rad_s, 0.118, 0.001);
  EXPECT_NEAR(report.peak_frequency_rad_s, 0.062, 0.0005);
  EXPECT_NEAR(report.peak_gain_db, 0.386, 0.0005);
}

// The paper prints 0.358 rad/s and 1.25 dB at 0.204 rad/s for the minimum setting. Table II's
// printed parameters give 0.3448 rad/s and 1.111 dB at 0.1927 rad/s; the mathematics wins.
TEST(StringStability, MinimumSettingBandAndPeakFromTableTwo)
{
  const auto report = acc::analyzeStringStability(acc::paperMinimumSetting());
  EXPECT_NEAR(report.amplified_band_upper_rad_s, 0.3448, 0.0001);
  EXPECT_NEAR(report.peak_frequency_rad_s, 0.19274, 0.0001);
  EXPECT_NEAR(report.peak_gain_db, 1.1107, 0.0001);
}

TEST(StringStability, ClosedFormsAgreeWithAGridSearch)
{
  for (const auto& setting : acc::namedSettings())
  {
    SCOPED_TRACE(setting.name);
    const auto report = acc::analyzeStringStability(setting.parameters);
    const auto [grid_w, grid_db] = gridPeak(setting.parameters, 3.0, 1e-5);
    EXPECT_NEAR(report.peak_frequency_rad_s, grid_w, 2e-5);
    EXPECT_NEAR(report.peak_gain_db, grid_db, 1e-7);
    EXPECT_NEAR(report.amplified_band_upper_rad_s, gridBandUpper(setting.parameters, 3.0, 1e-5), 2e-5);
  }
}

TEST(StringStability, FigureTwoSettings)
{
  const auto unstable = acc::analyzeStringStability(acc::paperFigure2Setting(0.75));
  const auto stable = acc::analyzeStringStability(acc::paperFigure2Setting(3.2));
  EXPECT_FALSE(unstable.string_stable);
  EXPECT_GT(unstable.lambda2, 0.0);
  EXPECT_TRUE(stable.string_stable);
  EXPECT_LT(stable.lambda2, 0.0);
  EXPECT_EQ(stable.amplified_band_upper_rad_s, 0.0);
  EXPECT_EQ(stable.peak_gain_db, 0.0);
}

// lambda2 < 0 and |Gamma| <= 1 everywhere are the same condition, k1 tau^2 + 2 k2 tau >= 2,
// except on the boundary itself.
TEST(StringStability, Lambda2AndTransferFunctionVerdictsAgreeOnAGrid)
{
  int checked = 0;
  for (double k1 = 0.01; k1 < 1.0; k1 += 0.07)
    for (double k2 = 0.0; k2 < 1.5; k2 += 0.11)
      for (double tau = 0.1; tau < 4.0; tau += 0.23)
      {
        const acc::AccParameters p{k1, k2, tau, 5.0};
        const double margin = k1 * tau * tau + 2 * k2 * tau - 2;
        if (std::abs(margin) < 1e-9) continue;
        const auto report = acc::analyzeStringStability(p);
        EXPECT_EQ(report.string_stable, report.lambda2 < 0.0) << k1 << " " << k2 << " " << tau;
        EXPECT_EQ(report.string_stable, margin > 0.0);
        ++checked;
      }
  EXPECT_GT(checked, 1000);
}

// On the boundary k1 tau_e^2 + 2 k2 tau_e = 2 the model is string stable (|Gamma| <= 1): written in
// decimal, such parameters round to either side of m = 0 by a few ulps, and 21 of 71 were called
// unstable (band 3e-9 rad/s, peak -1e-15 dB) by that rounding alone.
TEST(StringStability, TheBoundaryIsStableWhateverTheRounding)
{
  int on_boundary = 0;
  for (double tau = 0.2; tau < 3.0; tau += 0.2)
    for (double k2 = 0.05; 2.0 * k2 * tau < 2.0; k2 += 0.15)
    {
      const double k1 = (2.0 - 2.0 * k2 * tau) / (tau * tau);  // m = 0 up to rounding
      const auto report = acc::analyzeStringStability({k1, k2, tau, 5.0});
      EXPECT_TRUE(report.string_stable) << k1 << " " << k2 << " " << tau << ": band "
                                        << report.amplified_band_upper_rad_s;
      EXPECT_EQ(report.peak_gain_db, 0.0);
      ++on_boundary;
    }
  EXPECT_GT(on_boundary, 50);
  EXPECT_TRUE(acc::analyzeStringStability({0.1, 0.95, 1.0, 5.0}).string_stable);
  EXPECT_TRUE(acc::analyzeStringStability({0.2, 2.46, 0.4, 5.0}).string_stable);
  // Just off it, by far more than rounding, the band opens.
  EXPECT_FALSE(acc::analyzeStringStability({0.1, 0.95 - 1e-9, 1.0, 5.0}).string_stable);
}

TEST(StringStability, EtaPlaysNoPart)
{
  auto p = acc::paperMinimumSetting();
  const auto before = acc::analyzeStringStability(p);
  p.eta_m = 30.0;
  const auto after = acc::analyzeStringStability(p);
  EXPECT_DOUBLE_EQ(before.lambda2, after.lambda2);
  EXPECT_DOUBLE_EQ(before.peak_gain_db, after.peak_gain_db);
}

TEST(StringStability, DegenerateGains)
{
  // No spacing feedback: Gamma = k2 / (j w + k2) never exceeds 1.
  const auto no_spacing = acc::analyzeStringStability({0.0, 0.5, 1.0, 5.0});
  EXPECT_TRUE(no_spacing.string_stable);
  EXPECT_EQ(no_spacing.lambda2, 0.0);
  EXPECT_NEAR(no_spacing.peak_gain_db, 0.0, 1e-12);
  // Zero time gap with spacing feedback: every low frequency grows.
  const auto no_time_gap = acc::analyzeStringStability({0.2, 0.5, 0.0, 5.0});
  EXPECT_FALSE(no_time_gap.string_stable);
  EXPECT_TRUE(std::isinf(no_time_gap.lambda2));
  EXPECT_NEAR(no_time_gap.amplified_band_upper_rad_s, std::sqrt(0.4), 1e-12);
  // k2 = 0: the peak equation degenerates to a linear one.
  const acc::AccParameters no_relative{0.3, 0.0, 0.5, 5.0};
  const auto report = acc::analyzeStringStability(no_relative);
  EXPECT_NEAR(report.peak_frequency_rad_s, gridPeak(no_relative, 3.0, 1e-5).first, 2e-5);
  // A spacing gain so small that its square underflows: a peak at 0 rad/s and 0 dB, not 0/0.
  const auto tiny_spacing = acc::analyzeStringStability({1e-300, 0.1, 1.0, 0.0});
  EXPECT_EQ(tiny_spacing.peak_frequency_rad_s, 0.0);
  EXPECT_FALSE(std::isnan(tiny_spacing.peak_gain_db));
}

// Without damping (k2 = tau_e = 0) the law resonates at sqrt(k1): the peak is infinite, not the
// finite 313 dB a rounded square of the root once gave.
TEST(StringStability, AnUndampedLawHasAnInfinitePeakAtItsResonance)
{
  const acc::StringStabilityReport report = acc::analyzeStringStability(acc::AccParameters{0.25, 0.0, 0.0, 5.0});
  EXPECT_FALSE(report.string_stable);
  EXPECT_TRUE(std::isinf(report.peak_gain_db) && report.peak_gain_db > 0.0) << report.peak_gain_db;
  EXPECT_DOUBLE_EQ(report.peak_frequency_rad_s, 0.5);
}
