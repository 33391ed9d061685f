#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace acc
{
// Model-free evidence of string stability, per car and per link (a car and the car directly
// ahead of it): what the measured speeds say without any fitted ACC model.
//  - linkDipRatio: over a run's perturbations (evidence/perturbation.h), how the follower's dips
//    compare with its leader's, with a bootstrap confidence interval over the perturbations.
//  - empiricalResponse: Welch's estimate of the link's frequency response |Gamma(jw)| from the
//    two speed series, with its coherence and a confidence band; the caller compares it with a
//    model's transferGain (model/string_stability.h) where the coherence makes it informative.

/// What a link's dip ratios say of amplification.
enum class DipAmplification
{
  Amplifies,    ///< the confidence interval of the ratio lies above 1
  Attenuates,   ///< the confidence interval of the ratio lies below 1
  Undecided,    ///< the confidence interval contains 1, or the perturbations give none
  Insufficient  ///< fewer than 2 usable perturbations: no interval
};

/// "amplifies", "attenuates", "undecided", "insufficient".
std::string toString(DipAmplification state);

/// The ratio of a follower's dips to its leader's over the perturbations of one link.
struct DipRatioEstimate
{
  std::size_t count = 0;    ///< perturbations used
  std::size_t skipped = 0;  ///< perturbations skipped: a non-finite dip, or the leader's below the floor
  /// sum of follower dips / sum of leader dips over the used perturbations: a leader dip near the
  /// floor weighs by its size here instead of blowing up one ratio.
  double ratio_of_means = std::numeric_limits<double>::quiet_NaN();
  /// The median, smallest and largest of the per-perturbation ratios follower dip / leader dip:
  /// what the perturbations show without an interval (a link that grows in one braking and decays
  /// in the next has them on both sides of 1).
  double median_ratio = std::numeric_limits<double>::quiet_NaN();
  double smallest_ratio = std::numeric_limits<double>::quiet_NaN();
  double largest_ratio = std::numeric_limits<double>::quiet_NaN();
  /// The interval of ratio_of_means at `confidence` (clusteredRatioOfSums): an end is infinite
  /// where the perturbations do not bound it (two never do at 95 %), both NaN with fewer than 2
  /// used or when every one gave the same ratio.
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  double confidence = 0.95;
  std::size_t replicates = 0;
  DipAmplification amplifies = DipAmplification::Insufficient;
  std::string reason;  ///< one line: the ratio, its interval, the counts and the verdict
};

/// A leader dip below this [m/s] is within GNSS noise and driving jitter: a follower's ratio to
/// it (or to its shape) is noise, so it is not scored.
constexpr double kMinLeaderDipMps = 0.3;

/// The dip ratio of one link over its perturbations. follower_dips_mps[i] and leader_dips_mps[i]
/// are the two cars' dips in perturbation i (dipDepthMps); the vectors must have one size.
/// A pair is skipped (and counted) when either dip is not finite or the leader's is below
/// min_leader_dip_mps or not positive: a ratio to a dip the GNSS noise could make is noise.
/// Each perturbation is a cluster of one, and the interval inverts the wild cluster bootstrap-t
/// (wildClusterRatioInterval): with up to seven perturbations every weight pattern is visited and
/// the seed does not matter; beyond, `replicates` patterns are drawn from `seed`. It holds its
/// coverage with a handful of perturbations, so two can never decide a link (the interval is
/// [0, inf)), and three only when they agree.
/// Throws std::invalid_argument for vectors of different sizes, no replicates, or a confidence
/// outside (0, 1).
DipRatioEstimate linkDipRatio(const std::vector<double>& follower_dips_mps, const std::vector<double>& leader_dips_mps,
                              std::size_t replicates, std::uint64_t seed, double confidence = 0.95,
                              double min_leader_dip_mps = kMinLeaderDipMps);

/// linkDipRatio's ratio_of_means alone, without its interval (the same pairs used): NaN without a
/// usable pair. Throws std::invalid_argument for vectors of different sizes.
double linkDipRatioOfMeans(const std::vector<double>& follower_dips_mps, const std::vector<double>& leader_dips_mps,
                           double min_leader_dip_mps = kMinLeaderDipMps);

/// Options of Welch's estimate of a link's frequency response.
struct WelchOptions
{
  /// Samples per segment. 1024 at 10 Hz is 102.4 s: bins 0.061 rad/s apart. ACC responses peak
  /// near 0.1-0.5 rad/s, and the window smooths a peak over about two bins: for an OVRV ACC with
  /// k1 = 0.1 /s^2, k2 = 0.25 /s, tau_e = 1 s (peak 1.24 at 0.25 rad/s) 256 samples estimate the
  /// peak 16 % low, 512 samples 7 % low, 1024 samples 3 % low, a bias the band does not hold. A
  /// 15-minute run still gives about 16 segments at 50 % overlap. Any length >= 4; Eigen's FFT
  /// is fastest for lengths with small prime factors.
  std::size_t segment_samples = 1024;
  /// Fraction of a segment shared with the next one, in [0, 1).
  double overlap_fraction = 0.5;
  /// Two-sided confidence of the gain band, in (0, 1).
  double confidence = 0.95;
  /// Bins with coherence at least this are informative (see informativeCoherence).
  double informative_coherence = 0.5;
};

/// Welch's estimate of a link's frequency response from the leader's speed u and the follower's
/// speed v, one entry per frequency bin (DC excluded: the segments are detrended by their mean).
///
/// Method: segments of segment_samples, shifted by segment_samples * (1 - overlap_fraction)
/// (rounded, at least 1); each detrended by its mean and weighted by a periodic Hann window;
/// auto- and cross-spectra averaged over segments, Puv = mean(conj(U) V). Segments are laid
/// within each stretch of samples where u and v are both finite, from its start (runs joined by
/// NaN, or a hole, start a new stretch): interpolating over gaps would invent coherence. Finite
/// samples no segment covers (a stretch shorter than a segment, a stretch's tail) are counted in
/// samples_unused.
///   gain      = |H1| = |Puv| / Puu        (H1: unbiased by noise on v, biased low by noise on u)
///   phase_rad = arg(Puv)                  (a delay d gives -w d)
///   coherence = |Puv|^2 / (Puu Pvv)
///   band      = gain (1 -+ z eps), the lower end clamped at 0, z the two-sided normal quantile of
///               `confidence`, eps = sqrt(1 - coherence) / (sqrt(coherence) sqrt(2 n_d)): the
///               normalized random error of |H1| (Bendat & Piersol, Random Data, chapter 9:
///               random errors of single-input/output frequency response estimates), a normal
///               approximation valid for eps up to about 0.2; n_d = effective_segments.
/// Known biases the band does not hold: noise on u (GNSS speed noise of the leader) lowers gain;
/// the window smooths the response over about two bins (see segment_samples); a delay d between u
/// and v lowers gain by the window's normalized autocorrelation at d (negligible while d << the
/// segment); and a bin chosen for its high estimated coherence near the informative threshold
/// is more often one whose error happened to be favourable, so the band covers less there.
/// The band assumes stationary data. The spectra are summed over segments, so segments in which
/// the leader is quiet (no perturbation) weigh little in the gain; but then fewer segments carry
/// the estimate than n_d counts, and for runs of a few perturbations the band is too narrow.
struct EmpiricalResponse
{
  std::vector<double> frequency_rad_s;  ///< bin k = 1 .. segment_samples / 2: 2 pi k / (N dt)
  std::vector<double> gain;             ///< |H1| (NaN where Puu = 0 or no segment was used)
  std::vector<double> phase_rad;        ///< arg(Puv) in (-pi, pi]
  std::vector<double> coherence;        ///< magnitude-squared coherence in [0, 1]
  std::vector<double> gain_lower;       ///< lower end of the gain's band, >= 0
  std::vector<double> gain_upper;       ///< upper end of the gain's band
  std::vector<bool> informative;        ///< coherence >= options.informative_coherence
  /// One-sided power spectral densities of u and v [(m/s)^2 per rad/s]: their sum over the bins
  /// times the bin spacing is the variance of the detrended, un-windowed signal (in expectation).
  std::vector<double> leader_psd;
  std::vector<double> follower_psd;
  std::size_t segments_used = 0;
  std::size_t samples_unused = 0;  ///< finite samples of u and v that no segment covers
  /// The number of independent averages the overlapping segments are worth (Welch 1967, with the
  /// Hann window's overlap correlation; all used segments taken as consecutive, which errs towards
  /// fewer): n_d of the band. 0 when no segment was used.
  double effective_segments = 0.0;
  double z = 0.0;  ///< the normal quantile used for the band
};

/// True where a bin's coherence is at least threshold: only there does the empirical |Gamma|
/// say something of the link (below it, most of v is not the linear response to u).
bool informativeCoherence(double coherence, double threshold = 0.5);

/// Welch's estimate of the response from leader_speed_mps to follower_speed_mps, sampled every
/// sample_period_s (uniformly; NaN marks a missing sample). Series shorter than one segment give
/// the frequency grid with NaN estimates and no segment used.
/// Throws std::invalid_argument for series of different sizes, a non-positive sample period,
/// fewer than 4 samples per segment, an overlap outside [0, 1) or a confidence outside (0, 1).
EmpiricalResponse empiricalResponse(const std::vector<double>& leader_speed_mps,
                                    const std::vector<double>& follower_speed_mps, double sample_period_s,
                                    const WelchOptions& options = {});

}  // namespace acc
