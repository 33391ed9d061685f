#include "acc_identification/evidence/empirical_response.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <complex>
#include <stdexcept>

#include <unsupported/Eigen/FFT>

#include "acc_identification/evidence/clustered_ratio.h"
#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/model/angles.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void requireConfidence(double confidence, const char* what)
{
  if (!(confidence > 0.0 && confidence < 1.0))
  {
    throw std::invalid_argument(std::string(what) + ": the confidence must lie in (0, 1)");
  }
}

// ---- dip ratio ---------------------------------------------------------------------------------

struct DipPairs
{
  std::vector<double> follower_mps;
  std::vector<double> leader_mps;
  std::size_t skipped = 0;
};

DipPairs usableDipPairs(const std::vector<double>& follower_dips_mps, const std::vector<double>& leader_dips_mps,
                        double min_leader_dip_mps)
{
  DipPairs pairs;
  for (std::size_t i = 0; i < follower_dips_mps.size(); ++i)
  {
    const double follower = follower_dips_mps[i];
    const double leader = leader_dips_mps[i];
    const bool usable = std::isfinite(follower) && std::isfinite(leader) && leader >= min_leader_dip_mps && leader > 0.0;
    if (!usable)
    {
      ++pairs.skipped;
      continue;
    }
    pairs.follower_mps.push_back(follower);
    pairs.leader_mps.push_back(leader);
  }
  return pairs;
}

std::vector<double> ratiosOf(const DipPairs& pairs)
{
  std::vector<double> ratios;
  for (std::size_t i = 0; i < pairs.follower_mps.size(); ++i)
  {
    ratios.push_back(pairs.follower_mps[i] / pairs.leader_mps[i]);
  }
  return ratios;
}

DipAmplification classify(const DipRatioEstimate& e)
{
  if (e.count < 2)
    return DipAmplification::Insufficient;
  if (e.lower > 1.0)
    return DipAmplification::Amplifies;
  if (e.upper < 1.0)
    return DipAmplification::Attenuates;
  return DipAmplification::Undecided;
}

std::string dipReason(const DipRatioEstimate& e)
{
  if (e.count == 0)
    return printfText("no usable perturbation (%zu skipped): insufficient", e.skipped);
  if (e.count == 1)
    return printfText("dip ratio %.3g from 1 perturbation (%zu skipped): no interval, insufficient", e.ratio_of_means,
                      e.skipped);
  if (std::isnan(e.lower))
    return printfText("dip ratio %.3g, the same in each of %zu perturbations (%zu skipped): no spread to weigh, %s",
                      e.ratio_of_means, e.count, e.skipped, toString(e.amplifies).c_str());
  return printfText("dip ratio %.3g (%.0f%% CI %.3g to %.3g) over %zu perturbations (each %.3g to %.3g; %zu skipped): "
                    "%s",
                    e.ratio_of_means, 100.0 * e.confidence, e.lower, e.upper, e.count, e.smallest_ratio,
                    e.largest_ratio, e.skipped, toString(e.amplifies).c_str());
}

// ---- Welch -------------------------------------------------------------------------------------

void validateWelch(const std::vector<double>& u, const std::vector<double>& v, double sample_period_s,
                   const WelchOptions& options)
{
  const char* what = "empirical response";
  if (u.size() != v.size())
    throw std::invalid_argument(std::string(what) + ": leader and follower series differ in length");
  if (!(sample_period_s > 0.0))
    throw std::invalid_argument(std::string(what) + ": the sample period must be positive");
  if (options.segment_samples < 4)
    throw std::invalid_argument(std::string(what) + ": a segment needs at least 4 samples");
  if (!(options.overlap_fraction >= 0.0 && options.overlap_fraction < 1.0))
    throw std::invalid_argument(std::string(what) + ": the overlap must lie in [0, 1)");
  requireConfidence(options.confidence, what);
}

/// Periodic Hann window: its shifted copies at 50 % overlap sum to a constant.
std::vector<double> hannWindow(std::size_t length)
{
  std::vector<double> window(length);
  for (std::size_t n = 0; n < length; ++n)
  {
    window[n] = 0.5 * (1.0 - std::cos(2.0 * kPi * static_cast<double>(n) / static_cast<double>(length)));
  }
  return window;
}

std::size_t segmentShift(const WelchOptions& options)
{
  const double shift = std::round(static_cast<double>(options.segment_samples) * (1.0 - options.overlap_fraction));
  return std::max<std::size_t>(1, static_cast<std::size_t>(shift));
}

/// The segment detrended by its mean and windowed, then its DFT.
std::vector<std::complex<double>> windowedSpectrum(const std::vector<double>& x, std::size_t start,
                                                   const std::vector<double>& window, Eigen::FFT<double>& fft)
{
  const std::size_t length = window.size();
  double mean = 0.0;
  for (std::size_t n = 0; n < length; ++n)
    mean += x[start + n];
  mean /= static_cast<double>(length);
  std::vector<double> tapered(length);
  for (std::size_t n = 0; n < length; ++n)
    tapered[n] = (x[start + n] - mean) * window[n];
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, tapered);
  return spectrum;
}

/// Sums over segments of |U|^2, |V|^2 and conj(U) V, per bin k = 1 .. N/2.
struct SpectralSums
{
  std::vector<double> uu, vv;
  std::vector<std::complex<double>> uv;
  std::size_t used = 0;
  std::size_t samples_unused = 0;  ///< finite samples no segment covers
};

/// Adds the segment starting at `start` to the sums.
void addSegment(const std::vector<double>& u, const std::vector<double>& v, std::size_t start,
                const std::vector<double>& window, Eigen::FFT<double>& fft, SpectralSums* sums)
{
  const auto U = windowedSpectrum(u, start, window, fft);
  const auto V = windowedSpectrum(v, start, window, fft);
  for (std::size_t b = 0; b < sums->uu.size(); ++b)
  {
    const std::size_t k = b + 1;
    sums->uu[b] += std::norm(U[k]);
    sums->vv[b] += std::norm(V[k]);
    sums->uv[b] += std::conj(U[k]) * V[k];
  }
  ++sums->used;
}

SpectralSums accumulateSegments(const std::vector<double>& u, const std::vector<double>& v,
                                const std::vector<double>& window, std::size_t shift)
{
  const std::size_t length = window.size();
  const std::size_t bins = length / 2;
  SpectralSums sums{std::vector<double>(bins, 0.0), std::vector<double>(bins, 0.0),
                    std::vector<std::complex<double>>(bins, 0.0), 0, 0};
  Eigen::FFT<double> fft;
  // Segments are laid from the start of each stretch of finite samples: one grid over the whole
  // series lost every segment a hole fell into (5 of a car's 8 possible, on runs joined by NaN).
  std::size_t stretch_start = 0;
  for (std::size_t i = 0; i <= u.size(); ++i)
  {
    if (i < u.size() && std::isfinite(u[i]) && std::isfinite(v[i]))
      continue;
    std::size_t covered_end = stretch_start;
    for (std::size_t start = stretch_start; start + length <= i; start += shift)
    {
      addSegment(u, v, start, window, fft, &sums);
      covered_end = start + length;
    }
    sums.samples_unused += i - covered_end;
    stretch_start = i + 1;
  }
  return sums;
}

/// Welch's (1967) equivalent number of independent averages of `segments` consecutive windowed
/// segments `shift` apart: K / (1 + 2 sum_j (1 - j/K) rho_j^2), rho_j the window's normalized
/// overlap correlation at shift j * shift. For Hann at 50 %, rho_1 = 1/6 and n_d is about 0.95 K.
double effectiveSegments(std::size_t segments, const std::vector<double>& window, std::size_t shift)
{
  if (segments == 0)
    return 0.0;
  double energy = 0.0;
  for (double w : window)
    energy += w * w;
  const double K = static_cast<double>(segments);
  double inflation = 1.0;
  for (std::size_t j = 1; j < segments && j * shift < window.size(); ++j)
  {
    double overlap = 0.0;
    for (std::size_t n = 0; n + j * shift < window.size(); ++n)
      overlap += window[n] * window[n + j * shift];
    const double rho = overlap / energy;
    inflation += 2.0 * (1.0 - static_cast<double>(j) / K) * rho * rho;
  }
  return K / inflation;
}

/// A one-sided density per rad/s from a segment-averaged |X|^2: |X|^2 dt / (pi sum w^2), the
/// Nyquist bin (unpaired) half of that.
double oneSidedDensity(double mean_power, bool nyquist, double sample_period_s, double window_energy)
{
  const double density = mean_power * sample_period_s / (kPi * window_energy);
  return nyquist ? 0.5 * density : density;
}

void fillBin(const SpectralSums& sums, std::size_t b, double z, EmpiricalResponse* out)
{
  const double segments = static_cast<double>(sums.used);
  const double puu = sums.uu[b] / segments, pvv = sums.vv[b] / segments;
  const std::complex<double> puv = sums.uv[b] / segments;
  if (!(puu > 0.0 && pvv > 0.0))
    return;  // no power in this bin: no response to speak of (estimates stay NaN)
  const double gain = std::abs(puv) / puu;
  const double coherence = std::min(1.0, std::norm(puv) / (puu * pvv));
  out->gain[b] = gain;
  out->phase_rad[b] = std::arg(puv);
  out->coherence[b] = coherence;
  const double relative_error =
      std::sqrt(1.0 - coherence) / (std::sqrt(coherence) * std::sqrt(2.0 * out->effective_segments));
  // No coherence: nothing bounds the gain from above (and 0 * inf would be NaN).
  const bool unbounded = !std::isfinite(relative_error);
  out->gain_lower[b] = unbounded ? 0.0 : std::max(0.0, gain * (1.0 - z * relative_error));
  out->gain_upper[b] = unbounded ? std::numeric_limits<double>::infinity() : gain * (1.0 + z * relative_error);
}

EmpiricalResponse emptyResponse(std::size_t length, double sample_period_s)
{
  const std::size_t bins = length / 2;
  EmpiricalResponse r;
  for (std::size_t b = 0; b < bins; ++b)
    r.frequency_rad_s.push_back(2.0 * kPi * static_cast<double>(b + 1) / (static_cast<double>(length) * sample_period_s));
  r.gain = r.phase_rad = r.coherence = r.gain_lower = r.gain_upper = r.leader_psd = r.follower_psd =
      std::vector<double>(bins, kNaN);
  r.informative = std::vector<bool>(bins, false);
  return r;
}
}  // namespace

std::string toString(DipAmplification state)
{
  switch (state)
  {
    case DipAmplification::Amplifies: return "amplifies";
    case DipAmplification::Attenuates: return "attenuates";
    case DipAmplification::Undecided: return "undecided";
    case DipAmplification::Insufficient: return "insufficient";
  }
  return "insufficient";
}

DipRatioEstimate linkDipRatio(const std::vector<double>& follower_dips_mps, const std::vector<double>& leader_dips_mps,
                              std::size_t replicates, std::uint64_t seed, double confidence, double min_leader_dip_mps)
{
  if (follower_dips_mps.size() != leader_dips_mps.size())
    throw std::invalid_argument("link dip ratio: follower and leader dips differ in number");
  if (replicates == 0)
    throw std::invalid_argument("link dip ratio: the bootstrap needs at least one replicate");
  requireConfidence(confidence, "link dip ratio");
  const DipPairs pairs = usableDipPairs(follower_dips_mps, leader_dips_mps, min_leader_dip_mps);
  DipRatioEstimate e;
  e.count = pairs.follower_mps.size();
  e.skipped = pairs.skipped;
  e.confidence = confidence;
  e.replicates = replicates;
  // Each perturbation of a pair is its own cluster (one follower per input).
  std::vector<RatioCluster> clusters;
  for (std::size_t i = 0; i < e.count; ++i)
    clusters.push_back({pairs.follower_mps[i], pairs.leader_mps[i], 1});
  const ClusteredRatio ratio = clusteredRatioOfSums(clusters, replicates, seed, confidence);
  e.ratio_of_means = ratio.ratio;
  e.lower = ratio.lower;
  e.upper = ratio.upper;
  if (e.count > 0)
  {
    const std::vector<double> ratios = ratiosOf(pairs);
    e.median_ratio = finiteMedian(ratios);
    const auto [smallest, largest] = std::minmax_element(ratios.begin(), ratios.end());
    e.smallest_ratio = *smallest;
    e.largest_ratio = *largest;
  }
  e.amplifies = classify(e);
  e.reason = dipReason(e);
  return e;
}

double linkDipRatioOfMeans(const std::vector<double>& follower_dips_mps, const std::vector<double>& leader_dips_mps,
                           double min_leader_dip_mps)
{
  if (follower_dips_mps.size() != leader_dips_mps.size())
    throw std::invalid_argument("link dip ratio: follower and leader dips differ in number");
  const DipPairs pairs = usableDipPairs(follower_dips_mps, leader_dips_mps, min_leader_dip_mps);
  double follower = 0.0, leader = 0.0;  // summed in order, as clusteredRatioOfSums sums them
  for (std::size_t i = 0; i < pairs.follower_mps.size(); ++i)
  {
    follower += pairs.follower_mps[i];
    leader += pairs.leader_mps[i];
  }
  return pairs.follower_mps.empty() ? std::numeric_limits<double>::quiet_NaN() : follower / leader;
}

bool informativeCoherence(double coherence, double threshold)
{
  return coherence >= threshold;  // false for NaN: a bin without power says nothing
}

EmpiricalResponse empiricalResponse(const std::vector<double>& leader_speed_mps,
                                    const std::vector<double>& follower_speed_mps, double sample_period_s,
                                    const WelchOptions& options)
{
  validateWelch(leader_speed_mps, follower_speed_mps, sample_period_s, options);
  const std::size_t length = options.segment_samples;
  const std::vector<double> window = hannWindow(length);
  const std::size_t shift = segmentShift(options);
  EmpiricalResponse out = emptyResponse(length, sample_period_s);
  out.z = twoSidedNormalQuantile(1.0 - options.confidence);
  const SpectralSums sums = accumulateSegments(leader_speed_mps, follower_speed_mps, window, shift);
  out.segments_used = sums.used;
  out.samples_unused = sums.samples_unused;
  out.effective_segments = effectiveSegments(sums.used, window, shift);
  if (sums.used == 0)
    return out;
  double window_energy = 0.0;
  for (double w : window)
    window_energy += w * w;
  for (std::size_t b = 0; b < out.frequency_rad_s.size(); ++b)
  {
    const bool nyquist = length % 2 == 0 && b + 1 == length / 2;
    const double segments = static_cast<double>(sums.used);
    out.leader_psd[b] = oneSidedDensity(sums.uu[b] / segments, nyquist, sample_period_s, window_energy);
    out.follower_psd[b] = oneSidedDensity(sums.vv[b] / segments, nyquist, sample_period_s, window_energy);
    fillBin(sums, b, out.z, &out);
    out.informative[b] = informativeCoherence(out.coherence[b], options.informative_coherence);
  }
  return out;
}

}  // namespace acc
