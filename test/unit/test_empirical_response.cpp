// Model-free evidence of a link's amplification: the dip ratio over perturbations and Welch's
// empirical frequency response, checked against systems whose answers are known.
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "acc_identification/evidence/empirical_response.h"
#include "acc_identification/model/normal_source.h"

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;
constexpr double kSamplePeriodS = 0.1;  // the campaigns' GNSS rate

/// A continuous second-order response (b1 s + b0) / (s^2 + a1 s + a0), discretised with Tustin's
/// bilinear transform: its exact discrete response at w is the continuous one at the prewarped
/// frequency (2 / T) tan(w T / 2), which is the truth the estimate is held to.
struct SecondOrder
{
  double b1, b0, a1, a0;

  double continuousGain(double frequency_rad_s) const
  {
    const std::complex<double> s(0.0, frequency_rad_s);
    return std::abs((b1 * s + b0) / (s * s + a1 * s + a0));
  }

  double discreteGain(double frequency_rad_s) const
  {
    return continuousGain(2.0 / kSamplePeriodS * std::tan(frequency_rad_s * kSamplePeriodS / 2.0));
  }

  std::vector<double> filter(const std::vector<double>& input) const
  {
    const double c = 2.0 / kSamplePeriodS;
    const double n0 = b1 * c + b0, n1 = 2.0 * b0, n2 = -b1 * c + b0;
    const double d0 = c * c + a1 * c + a0, d1 = -2.0 * c * c + 2.0 * a0, d2 = c * c - a1 * c + a0;
    std::vector<double> output(input.size(), 0.0);
    for (std::size_t k = 0; k < input.size(); ++k)
    {
      const double x1 = k >= 1 ? input[k - 1] : 0.0, x2 = k >= 2 ? input[k - 2] : 0.0;
      const double y1 = k >= 1 ? output[k - 1] : 0.0, y2 = k >= 2 ? output[k - 2] : 0.0;
      output[k] = (n0 * input[k] + n1 * x1 + n2 * x2 - d1 * y1 - d2 * y2) / d0;
    }
    return output;
  }
};

// The OVRV model's Gamma(s) = (k2 s + k1) / (s^2 + (k2 + k1 tau_e) s + k1) with k1 = 0.1 /s^2,
// k2 = 0.25 /s, tau_e = 1 s: a string-unstable ACC, peak gain about 1.3 near 0.3 rad/s.
const SecondOrder kUnstableAcc{0.25, 0.10, 0.35, 0.10};

std::vector<double> whiteNoise(std::size_t samples, double sigma, std::uint64_t seed)
{
  acc::NormalSource normal(seed);
  std::vector<double> x(samples);
  for (double& value : x)
    value = sigma * normal.standardNormal();
  return x;
}

/// A leader's speed around 25 m/s with broadband disturbances, and its follower through the
/// system; the first 60 s are dropped so that the filter's start-up transient is not data.
struct Link
{
  std::vector<double> leader_mps, follower_mps;
};

Link simulatedLink(const SecondOrder& system, std::size_t samples, std::uint64_t seed, double follower_noise_mps = 0.0)
{
  const std::size_t warm_up = 600;
  const std::vector<double> disturbance = whiteNoise(samples + warm_up, 0.5, seed);
  const std::vector<double> response = system.filter(disturbance);
  const std::vector<double> noise = whiteNoise(samples, follower_noise_mps, seed + 1);
  Link link;
  for (std::size_t k = 0; k < samples; ++k)
  {
    link.leader_mps.push_back(25.0 + disturbance[warm_up + k]);
    link.follower_mps.push_back(25.0 + response[warm_up + k] + noise[k]);
  }
  return link;
}

/// Bins below max_rad_s: the ACC's band (above it the response is small and the leader's
/// speed noise, not its dynamics, dominates real data).
std::vector<std::size_t> binsBelow(const acc::EmpiricalResponse& r, double max_rad_s)
{
  std::vector<std::size_t> bins;
  for (std::size_t b = 0; b < r.frequency_rad_s.size(); ++b)
  {
    if (r.frequency_rad_s[b] <= max_rad_s)
      bins.push_back(b);
  }
  return bins;
}

double relativeHalfWidth(const acc::EmpiricalResponse& r, std::size_t b)
{
  return (r.gain_upper[b] - r.gain[b]) / r.gain[b];
}
}  // namespace

// ---- Welch's empirical response -----------------------------------------------------------------

TEST(EmpiricalResponse, GainOfAKnownSecondOrderSystemWithinTenPercentAndCoherenceNearOne)
{
  const Link link = simulatedLink(kUnstableAcc, 18000, 11);  // 30 minutes at 10 Hz
  const acc::EmpiricalResponse r = acc::empiricalResponse(link.leader_mps, link.follower_mps, kSamplePeriodS);
  ASSERT_EQ(r.segments_used, 34u);  // (18000 - 1024) / 512 + 1
  EXPECT_EQ(r.samples_unused, 18000u - 33u * 512u - 1024u);
  // Hann at 50 % overlap: rho_1 = 1/6, n_d = 34 / (1 + 2 (33/34) / 36) = 32.26.
  EXPECT_NEAR(r.effective_segments, 34.0 / (1.0 + 2.0 * (33.0 / 34.0) / 36.0), 0.01);
  EXPECT_NEAR(r.z, 1.959964, 1e-5);
  EXPECT_NEAR(r.frequency_rad_s[0], 2.0 * kPi / 102.4, 1e-12);
  const auto bins = binsBelow(r, 3.0);
  ASSERT_GT(bins.size(), 40u);
  for (std::size_t b : bins)
  {
    const double truth = kUnstableAcc.discreteGain(r.frequency_rad_s[b]);
    EXPECT_GT(r.coherence[b], 0.95) << r.frequency_rad_s[b] << " rad/s";
    EXPECT_TRUE(r.informative[b]);
    EXPECT_NEAR(r.gain[b], truth, 0.1 * truth) << r.frequency_rad_s[b] << " rad/s";
  }
  // The estimate sees the amplification the truth has near 0.25 rad/s (bin 4).
  EXPECT_GT(r.gain[3], 1.15);
}

TEST(EmpiricalResponse, ShortSegmentsFlattenTheResonance)
{
  // Why the default is 1024 samples: 256 samples (0.245 rad/s bins) smear the peak of 1.24.
  const Link link = simulatedLink(kUnstableAcc, 18000, 11);
  acc::WelchOptions short_segments;
  short_segments.segment_samples = 256;
  const acc::EmpiricalResponse r = acc::empiricalResponse(link.leader_mps, link.follower_mps, kSamplePeriodS, short_segments);
  ASSERT_NEAR(r.frequency_rad_s[0], 0.245, 0.001);
  EXPECT_LT(r.gain[0], 0.9 * kUnstableAcc.discreteGain(r.frequency_rad_s[0]));
}

TEST(EmpiricalResponse, FollowerNoiseLowersCoherenceAndWidensTheBand)
{
  const Link clean = simulatedLink(kUnstableAcc, 18000, 21);
  const Link noisy = simulatedLink(kUnstableAcc, 18000, 21, 0.3);
  const acc::EmpiricalResponse rc = acc::empiricalResponse(clean.leader_mps, clean.follower_mps, kSamplePeriodS);
  const acc::EmpiricalResponse rn = acc::empiricalResponse(noisy.leader_mps, noisy.follower_mps, kSamplePeriodS);
  const auto bins = binsBelow(rn, 3.0);
  for (std::size_t b : bins)
  {
    EXPECT_LT(rn.coherence[b], rc.coherence[b]) << rn.frequency_rad_s[b] << " rad/s";
    EXPECT_GT(relativeHalfWidth(rn, b), relativeHalfWidth(rc, b)) << rn.frequency_rad_s[b] << " rad/s";
  }
  // The noise is white at (0.3 m/s)^2 while the follower's response falls off with frequency:
  // the low bins stay informative, the high ones do not.
  EXPECT_TRUE(rn.informative[0]);
  EXPECT_TRUE(rn.informative[3]);
  EXPECT_FALSE(rn.informative[bins.back()]);
}

TEST(EmpiricalResponse, BandMatchesTheSpreadOverRealisationsAndHoldsTheTruth)
{
  // Over 40 seeded realisations of the noisy link, at the low bins where the coherence is high
  // (about 0.75-0.85): the band's half-width / z, the predicted standard error of |H1|, must match
  // the observed spread of |H1|, and the 95 % band must hold the truth about 95 % of the time.
  const std::size_t realisations = 40, bins = 8;
  std::vector<double> sum(bins, 0.0), sum_squares(bins, 0.0), predicted(bins, 0.0);
  std::size_t trials = 0, covered = 0;
  for (std::size_t i = 0; i < realisations; ++i)
  {
    const Link link = simulatedLink(kUnstableAcc, 18000, 100 + 2 * i, 0.3);
    const acc::EmpiricalResponse r = acc::empiricalResponse(link.leader_mps, link.follower_mps, kSamplePeriodS);
    for (std::size_t b = 0; b < bins; ++b)
    {
      sum[b] += r.gain[b];
      sum_squares[b] += r.gain[b] * r.gain[b];
      predicted[b] += (r.gain_upper[b] - r.gain[b]) / r.z / static_cast<double>(realisations);
      const double truth = kUnstableAcc.discreteGain(r.frequency_rad_s[b]);
      ++trials;
      covered += r.gain_lower[b] <= truth && truth <= r.gain_upper[b] ? 1 : 0;
    }
  }
  for (std::size_t b = 0; b < bins; ++b)
  {
    const double n = static_cast<double>(realisations);
    const double observed = std::sqrt((sum_squares[b] - sum[b] * sum[b] / n) / (n - 1.0));
    EXPECT_GT(predicted[b], 0.7 * observed) << "bin " << b;
    EXPECT_LT(predicted[b], 1.4 * observed) << "bin " << b;
  }
  const double coverage = static_cast<double>(covered) / static_cast<double>(trials);
  EXPECT_GT(coverage, 0.88);
  EXPECT_LT(coverage, 0.99);
}

TEST(EmpiricalResponse, PureDelayHasGainOneAndLinearPhase)
{
  const std::size_t delay_samples = 10;  // 1 s, an ACC's order of reaction
  const std::vector<double> u = whiteNoise(12000 + delay_samples, 1.0, 31);
  std::vector<double> leader(u.begin() + delay_samples, u.end());
  std::vector<double> follower(u.begin(), u.end() - delay_samples);
  const acc::EmpiricalResponse r = acc::empiricalResponse(leader, follower, kSamplePeriodS);
  for (std::size_t b = 0; b < r.frequency_rad_s.size(); ++b)
  {
    EXPECT_NEAR(r.gain[b], 1.0, 0.05) << r.frequency_rad_s[b] << " rad/s";
    EXPECT_GT(r.coherence[b], 0.95) << r.frequency_rad_s[b] << " rad/s";
  }
  // arg(Puv) = -w d, checked below pi/d where it has not wrapped.
  for (std::size_t b : binsBelow(r, 0.9 * kPi / (delay_samples * kSamplePeriodS)))
  {
    EXPECT_NEAR(r.phase_rad[b], -r.frequency_rad_s[b] * delay_samples * kSamplePeriodS, 0.05);
  }
}

TEST(EmpiricalResponse, WhiteNoiseDensityIsItsVarianceSpreadOverTheBand)
{
  const double sigma_mps = 0.7;
  const std::vector<double> u = whiteNoise(40000, sigma_mps, 41);
  const acc::EmpiricalResponse r = acc::empiricalResponse(u, u, kSamplePeriodS);
  const double expected = sigma_mps * sigma_mps * kSamplePeriodS / kPi;  // one-sided, per rad/s
  double mean_density = 0.0;
  for (std::size_t b = 0; b + 1 < r.leader_psd.size(); ++b)
    mean_density += r.leader_psd[b] / static_cast<double>(r.leader_psd.size() - 1);
  EXPECT_NEAR(mean_density, expected, 0.03 * expected);
  EXPECT_NEAR(r.leader_psd.back(), 0.5 * expected, 0.2 * expected);  // the unpaired Nyquist bin
  EXPECT_NEAR(r.gain[5], 1.0, 1e-12);
  EXPECT_NEAR(r.coherence[5], 1.0, 1e-12);
}

// Holes split the series into stretches, and segments are laid within each from its start: a
// grid over the whole series lost the three segments the two holes fell into (19 of 22 used).
TEST(EmpiricalResponse, SegmentsAreLaidWithinEachStretchBetweenNaNs)
{
  Link link = simulatedLink(kUnstableAcc, 12000, 51);
  const acc::EmpiricalResponse full = acc::empiricalResponse(link.leader_mps, link.follower_mps, kSamplePeriodS);
  ASSERT_EQ(full.segments_used, 22u);  // (12000 - 1024) / 512 + 1
  link.follower_mps[3000] = kNaN;
  link.leader_mps[10] = kNaN;
  const acc::EmpiricalResponse gappy = acc::empiricalResponse(link.leader_mps, link.follower_mps, kSamplePeriodS);
  // [0, 10): none, 10 unused; [11, 3000): 4 segments to 2571, 429 unused; [3001, 12000): 16
  // segments to 11705, 295 unused.
  EXPECT_EQ(gappy.segments_used, 20u);
  EXPECT_EQ(gappy.samples_unused, 10u + 429u + 295u);
  for (std::size_t b : binsBelow(gappy, 3.0))
  {
    ASSERT_TRUE(std::isfinite(gappy.gain[b]));
    EXPECT_NEAR(gappy.gain[b], full.gain[b], 0.1 * full.gain[b]);
  }
}

TEST(EmpiricalResponse, TooShortSeriesGiveTheGridWithoutEstimates)
{
  const std::vector<double> u(1000, 1.0), v(1000, 1.0);
  const acc::EmpiricalResponse r = acc::empiricalResponse(u, v, kSamplePeriodS);
  EXPECT_EQ(r.segments_used, 0u);
  EXPECT_EQ(r.frequency_rad_s.size(), 512u);
  EXPECT_TRUE(std::isnan(r.gain[0]));
  EXPECT_FALSE(r.informative[0]);
  EXPECT_EQ(r.effective_segments, 0.0);
}

TEST(EmpiricalResponse, RejectsInconsistentInputs)
{
  const std::vector<double> u(1000, 1.0), v(999, 1.0);
  EXPECT_THROW(acc::empiricalResponse(u, v, kSamplePeriodS), std::invalid_argument);
  EXPECT_THROW(acc::empiricalResponse(u, u, 0.0), std::invalid_argument);
  acc::WelchOptions options;
  options.overlap_fraction = 1.0;
  EXPECT_THROW(acc::empiricalResponse(u, u, kSamplePeriodS, options), std::invalid_argument);
}

TEST(EmpiricalResponse, InformativeMeansCoherenceAtLeastTheThreshold)
{
  EXPECT_TRUE(acc::informativeCoherence(0.5));
  EXPECT_FALSE(acc::informativeCoherence(0.49));
  EXPECT_FALSE(acc::informativeCoherence(kNaN));
  EXPECT_TRUE(acc::informativeCoherence(0.8, 0.8));
  EXPECT_FALSE(acc::informativeCoherence(0.79, 0.8));
}

// ---- dip ratio ----------------------------------------------------------------------------------

namespace
{
std::vector<double> scaled(const std::vector<double>& dips, const std::vector<double>& ratios)
{
  std::vector<double> out;
  for (std::size_t i = 0; i < dips.size(); ++i)
    out.push_back(dips[i] * ratios[i]);
  return out;
}

const std::vector<double> kLeaderDipsMps{2.0, 3.5, 1.2, 4.0, 2.6, 3.1};
}  // namespace

TEST(LinkDipRatio, FollowerDipsOneAndAHalfTimesTheLeadersAmplify)
{
  const std::vector<double> ratios{1.45, 1.55, 1.5, 1.4, 1.6, 1.5};
  const acc::DipRatioEstimate e = acc::linkDipRatio(scaled(kLeaderDipsMps, ratios), kLeaderDipsMps, 2000, 7);
  EXPECT_EQ(e.count, 6u);
  EXPECT_EQ(e.skipped, 0u);
  EXPECT_NEAR(e.ratio_of_means, 1.5, 0.05);
  EXPECT_NEAR(e.median_ratio, 1.5, 1e-12);
  EXPECT_GT(e.lower, 1.0);
  EXPECT_LE(e.lower, e.ratio_of_means);
  EXPECT_GE(e.upper, e.ratio_of_means);
  EXPECT_EQ(e.amplifies, acc::DipAmplification::Amplifies);
  EXPECT_NE(e.reason.find("amplifies"), std::string::npos) << e.reason;
}

TEST(LinkDipRatio, FollowerDipsSixTenthsOfTheLeadersAttenuate)
{
  const std::vector<double> ratios{0.6, 0.55, 0.65, 0.6, 0.62, 0.58};
  const acc::DipRatioEstimate e = acc::linkDipRatio(scaled(kLeaderDipsMps, ratios), kLeaderDipsMps, 2000, 7);
  EXPECT_LT(e.upper, 1.0);
  EXPECT_EQ(e.amplifies, acc::DipAmplification::Attenuates);
}

TEST(LinkDipRatio, MixedRatiosAreUndecided)
{
  const std::vector<double> ratios{1.5, 0.6, 1.3, 0.7, 1.4, 0.65};
  const acc::DipRatioEstimate e = acc::linkDipRatio(scaled(kLeaderDipsMps, ratios), kLeaderDipsMps, 2000, 7);
  EXPECT_LT(e.lower, 1.0);
  EXPECT_GT(e.upper, 1.0);
  EXPECT_EQ(e.amplifies, acc::DipAmplification::Undecided);
  // Each perturbation's own ratio, on both sides of 1: the link grows in one braking, decays in the next.
  EXPECT_NEAR(e.smallest_ratio, 0.6, 1e-12);
  EXPECT_NEAR(e.largest_ratio, 1.5, 1e-12);
}

// The point estimate alone is linkDipRatio's, on the same pairs, and none without a usable pair.
// Fails when it sums other pairs than linkDipRatio uses.
TEST(LinkDipRatio, TheRatioOfMeansAloneIsTheEstimates)
{
  const std::vector<double> leader{2.0, kNaN, 0.1, 3.0, 0.0, 2.5, 1.6};
  const std::vector<double> follower{3.0, 2.0, 5.0, kNaN, 1.0, 3.0, 1.0};
  EXPECT_EQ(acc::linkDipRatioOfMeans(follower, leader), acc::linkDipRatio(follower, leader, 10, 3).ratio_of_means);
  EXPECT_NEAR(acc::linkDipRatioOfMeans(follower, leader), (3.0 + 3.0 + 1.0) / (2.0 + 2.5 + 1.6), 1e-12);
  EXPECT_TRUE(std::isnan(acc::linkDipRatioOfMeans({5.0}, {0.1})));
  EXPECT_THROW(acc::linkDipRatioOfMeans({1.0}, {}), std::invalid_argument);
}

TEST(LinkDipRatio, NonFiniteDipsAndTinyLeaderDipsAreSkippedAndCounted)
{
  const std::vector<double> leader{2.0, kNaN, 0.1, 3.0, 0.0, 2.5};
  const std::vector<double> follower{3.0, 2.0, 5.0, kNaN, 1.0, 3.75};
  const acc::DipRatioEstimate e = acc::linkDipRatio(follower, leader, 500, 3);
  EXPECT_EQ(e.count, 2u);
  EXPECT_EQ(e.skipped, 4u);
  // Only (3.0, 2.0) and (3.75, 2.5) are left: both ratio 1.5, with no spread between them to weigh.
  EXPECT_DOUBLE_EQ(e.ratio_of_means, 1.5);
  EXPECT_TRUE(std::isnan(e.lower));
  EXPECT_TRUE(std::isnan(e.upper));
  EXPECT_EQ(e.amplifies, acc::DipAmplification::Undecided);
  EXPECT_NE(e.reason.find("no spread"), std::string::npos) << e.reason;
}

// Two perturbations, both amplified by half, decide nothing at 95 %: their interval is [0, inf).
// The percentile bootstrap this replaced called such a link amplifying (or, on the ZalaZone runs,
// three links attenuating from two perturbations each).
TEST(LinkDipRatio, TwoPerturbationsNeverDecideALink)
{
  const acc::DipRatioEstimate e = acc::linkDipRatio({3.0, 5.6}, {2.0, 3.5}, 500, 3);
  EXPECT_EQ(e.count, 2u);
  EXPECT_EQ(e.lower, 0.0);
  EXPECT_TRUE(std::isinf(e.upper));
  EXPECT_EQ(e.amplifies, acc::DipAmplification::Undecided);
  EXPECT_NE(e.reason.find("CI 0 to inf"), std::string::npos) << e.reason;
  EXPECT_DOUBLE_EQ(e.smallest_ratio, 1.5);
  EXPECT_DOUBLE_EQ(e.largest_ratio, 1.6);
  EXPECT_NE(e.reason.find("each 1.5 to 1.6"), std::string::npos) << e.reason;
}

TEST(LinkDipRatio, OnePerturbationGivesARatioButNoInterval)
{
  const acc::DipRatioEstimate e = acc::linkDipRatio({3.0, kNaN}, {2.0, 2.0}, 500, 3);
  EXPECT_EQ(e.count, 1u);
  EXPECT_EQ(e.skipped, 1u);
  EXPECT_DOUBLE_EQ(e.ratio_of_means, 1.5);
  EXPECT_TRUE(std::isnan(e.lower));
  EXPECT_TRUE(std::isnan(e.upper));
  EXPECT_EQ(e.amplifies, acc::DipAmplification::Insufficient);
  EXPECT_EQ(acc::toString(e.amplifies), "insufficient");
}

TEST(LinkDipRatio, NoPerturbationIsInsufficient)
{
  const acc::DipRatioEstimate e = acc::linkDipRatio({}, {}, 500, 3);
  EXPECT_EQ(e.count, 0u);
  EXPECT_TRUE(std::isnan(e.ratio_of_means));
  EXPECT_EQ(e.amplifies, acc::DipAmplification::Insufficient);
}

// Up to seven perturbations every weight pattern is visited, so the seed does not matter; beyond,
// patterns are drawn, and the same seed gives the same interval bit for bit.
TEST(LinkDipRatio, TheIntervalIsTheSameForEverySeedUpToSevenPerturbationsAndForTheSameSeedBeyond)
{
  const std::vector<double> ratios{1.5, 0.6, 1.3, 0.7, 1.4, 0.65};
  const std::vector<double> follower = scaled(kLeaderDipsMps, ratios);
  const acc::DipRatioEstimate six = acc::linkDipRatio(follower, kLeaderDipsMps, 999, 12345);
  const acc::DipRatioEstimate six_other = acc::linkDipRatio(follower, kLeaderDipsMps, 99, 54321);
  EXPECT_EQ(six.lower, six_other.lower);  // exact equality on purpose
  EXPECT_EQ(six.upper, six_other.upper);
  std::vector<double> leader = kLeaderDipsMps, more = follower;
  for (std::size_t i = 0; i < kLeaderDipsMps.size(); ++i)
  {
    leader.push_back(kLeaderDipsMps[i] + 0.3);
    more.push_back(follower[i] * (i % 2 == 0 ? 1.1 : 0.9));
  }
  const acc::DipRatioEstimate a = acc::linkDipRatio(more, leader, 999, 12345);
  const acc::DipRatioEstimate b = acc::linkDipRatio(more, leader, 999, 12345);
  const acc::DipRatioEstimate other = acc::linkDipRatio(more, leader, 999, 54321);
  EXPECT_EQ(a.lower, b.lower);
  EXPECT_EQ(a.upper, b.upper);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_TRUE(a.lower != other.lower || a.upper != other.upper) << "twelve perturbations: the seed draws the patterns";
}

TEST(LinkDipRatio, RejectsInconsistentInputs)
{
  EXPECT_THROW(acc::linkDipRatio({1.0}, {1.0, 2.0}, 100, 1), std::invalid_argument);
  EXPECT_THROW(acc::linkDipRatio({1.0}, {1.0}, 0, 1), std::invalid_argument);
  EXPECT_THROW(acc::linkDipRatio({1.0}, {1.0}, 100, 1, 1.0), std::invalid_argument);
}
