#include "acc_identification/diagnosis/residual_breakdown.h"
#include "acc_identification/model/car_following_run.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <map>

#include <unsupported/Eigen/FFT>

namespace acc
{
namespace
{
/// Sums of squared errors of one group.
struct Accumulator
{
  std::size_t samples = 0;
  double speed_before = 0.0;
  double gap_before = 0.0;
  double speed_after = 0.0;
  double gap_after = 0.0;

  void add(double sb, double gb, double sa, double ga)
  {
    ++samples;
    speed_before += sb;
    gap_before += gb;
    speed_after += sa;
    gap_after += ga;
  }
};

double rootMean(double sum, std::size_t count) { return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0; }

ResidualGroup toGroup(const std::string& name, const Accumulator& a, const Accumulator& total)
{
  ResidualGroup g;
  g.name = name;
  g.samples = a.samples;
  g.share_of_time = total.samples > 0 ? static_cast<double>(a.samples) / static_cast<double>(total.samples) : 0.0;
  g.rmse_speed_before_mps = rootMean(a.speed_before, a.samples);
  g.rmse_gap_before_m = rootMean(a.gap_before, a.samples);
  g.rmse_speed_after_mps = rootMean(a.speed_after, a.samples);
  g.rmse_gap_after_m = rootMean(a.gap_after, a.samples);
  g.share_of_squared_speed_error = total.speed_before > 0.0 ? a.speed_before / total.speed_before : 0.0;
  g.share_of_squared_gap_error = total.gap_before > 0.0 ? a.gap_before / total.gap_before : 0.0;
  return g;
}

/// Number of samples a run can be scored on: all, or up to its divergence.
std::size_t scoredSamples(const CarFollowingRun& run, const SimulatedFollower& a, const SimulatedFollower& b)
{
  std::size_t n = run.size();
  if (a.diverged)
  {
    n = std::min(n, a.diverged_at_index);
  }
  if (b.diverged)
  {
    n = std::min(n, b.diverged_at_index);
  }
  return n;
}

std::vector<double> centralDifference(const std::vector<double>& time_s, const std::vector<double>& values,
                                      double window_s)
{
  const std::size_t n = values.size();
  std::vector<double> rate(n, 0.0);
  if (n < 2)
  {
    return rate;
  }
  const double step = (time_s.back() - time_s.front()) / static_cast<double>(n - 1);
  const std::size_t half = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.5 * window_s / step)));
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::size_t lo = k >= half ? k - half : 0;
    const std::size_t hi = std::min(n - 1, k + half);
    rate[k] = (values[hi] - values[lo]) / (time_s[hi] - time_s[lo]);
  }
  return rate;
}

/// Two-sided |DFT|^2 / n folded onto the non-negative frequencies, so that the bins sum to the
/// sum of squares of the signal (Parseval) and band shares are shares of the squared error.
std::vector<double> foldedPower(const std::vector<double>& signal)
{
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, signal);
  const std::size_t n = signal.size();
  std::vector<double> power(n / 2 + 1, 0.0);
  for (std::size_t k = 0; k <= n / 2; ++k)
  {
    const bool paired = k != 0 && !(n % 2 == 0 && k == n / 2);
    power[k] = (paired ? 2.0 : 1.0) * std::norm(spectrum[k]) / static_cast<double>(n);
  }
  return power;
}

std::string bandName(double lower, double upper)
{
  char text[64];
  std::snprintf(text, sizeof text, "%g-%g Hz", lower, upper);
  return text;
}

void addSpectrum(const CarFollowingRun& run, std::size_t n, const SimulatedFollower& before,
                 const SimulatedFollower& after, const BreakdownOptions& options, std::vector<double>* band_before,
                 std::vector<double>* band_after, ResidualBreakdown* out)
{
  if (n < 8)
  {
    return;
  }
  std::vector<double> rb(n), ra(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    rb[k] = run.follower_speed_mps[k] - before.speed_mps[k];
    ra[k] = run.follower_speed_mps[k] - after.speed_mps[k];
  }
  const std::vector<double> pb = foldedPower(rb);
  const std::vector<double> pa = foldedPower(ra);
  const double step = medianStepS({run});
  const auto& edges = options.frequency_band_edges_hz;
  for (std::size_t k = 0; k < pb.size(); ++k)
  {
    const double f = static_cast<double>(k) / (static_cast<double>(n) * step);
    const std::size_t band = static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), f) - edges.begin());
    (*band_before)[band] += pb[k];
    (*band_after)[band] += pa[k];
    if (k > 0)
    {
      out->spectrum.push_back({run.name, f, pb[k], pa[k]});
    }
  }
}
}  // namespace

std::string regimeName(DrivingRegime regime)
{
  switch (regime)
  {
    case DrivingRegime::gap_opening_follower_accelerating: return "gap_opening_follower_accelerating";
    case DrivingRegime::leader_braking: return "leader_braking";
    case DrivingRegime::leader_accelerating: return "leader_accelerating";
    case DrivingRegime::steady_following: return "steady_following";
  }
  return "unknown";
}

std::vector<DrivingRegime> classifyRegimes(const CarFollowingRun& run, const BreakdownOptions& options)
{
  const auto leader_acc = centralDifference(run.time_s, run.leader_speed_mps, options.acceleration_window_s);
  const auto follower_acc = centralDifference(run.time_s, run.follower_speed_mps, options.acceleration_window_s);
  std::vector<DrivingRegime> regimes(run.size(), DrivingRegime::steady_following);
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    const double opening = run.leader_speed_mps[k] - run.follower_speed_mps[k];
    if (opening > options.gap_opening_speed_mps && follower_acc[k] > options.follower_acceleration_threshold_mps2)
    {
      regimes[k] = DrivingRegime::gap_opening_follower_accelerating;
    }
    else if (leader_acc[k] < -options.leader_acceleration_threshold_mps2)
    {
      regimes[k] = DrivingRegime::leader_braking;
    }
    else if (leader_acc[k] > options.leader_acceleration_threshold_mps2)
    {
      regimes[k] = DrivingRegime::leader_accelerating;
    }
  }
  return regimes;
}

ResidualBreakdown breakDownResiduals(const std::vector<CarFollowingRun>& runs,
                                     const std::vector<SimulatedFollower>& before,
                                     const std::vector<SimulatedFollower>& after, const BreakdownOptions& options)
{
  ResidualBreakdown out;
  const DrivingRegime all_regimes[] = {DrivingRegime::steady_following, DrivingRegime::leader_accelerating,
                                       DrivingRegime::leader_braking,
                                       DrivingRegime::gap_opening_follower_accelerating};
  std::map<DrivingRegime, Accumulator> by_regime;
  std::map<int, Accumulator> by_speed;
  Accumulator total;
  const std::size_t bands = options.frequency_band_edges_hz.size() + 1;
  std::vector<double> band_before(bands, 0.0), band_after(bands, 0.0);
  std::vector<WorstSegment> windows;
  std::vector<double> window_sums;
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    const CarFollowingRun& run = runs[r];
    const std::size_t n = scoredSamples(run, before[r], after[r]);
    const std::vector<DrivingRegime> regimes = classifyRegimes(run, options);
    std::size_t window_start = 0;
    Accumulator window;
    std::map<DrivingRegime, std::size_t> window_regimes;
    for (std::size_t k = 0; k < n; ++k)
    {
      const double sb = std::pow(run.follower_speed_mps[k] - before[r].speed_mps[k], 2);
      const double gb = std::pow(run.space_gap_m[k] - before[r].space_gap_m[k], 2);
      const double sa = std::pow(run.follower_speed_mps[k] - after[r].speed_mps[k], 2);
      const double ga = std::pow(run.space_gap_m[k] - after[r].space_gap_m[k], 2);
      total.add(sb, gb, sa, ga);
      by_regime[regimes[k]].add(sb, gb, sa, ga);
      by_speed[static_cast<int>(std::floor(run.follower_speed_mps[k] / options.speed_band_width_mps))].add(sb, gb, sa, ga);
      window.add(sb, gb, sa, ga);
      ++window_regimes[regimes[k]];
      // Windows of segment_length_s: [t_start, t_start + length), closed before the sample that would overrun.
      const bool window_full =
          k + 1 < n && run.time_s[k + 1] - run.time_s[window_start] >= options.segment_length_s - 1e-9;
      if (window_full || k + 1 == n)
      {
        WorstSegment segment;
        segment.run = run.name;
        segment.start_s = run.time_s[window_start];
        segment.end_s = run.time_s[k];
        segment.rmse_speed_before_mps = rootMean(window.speed_before, window.samples);
        segment.rmse_speed_after_mps = rootMean(window.speed_after, window.samples);
        segment.rmse_gap_before_m = rootMean(window.gap_before, window.samples);
        const auto main = std::max_element(window_regimes.begin(), window_regimes.end(),
                                           [](const auto& a, const auto& b) { return a.second < b.second; });
        segment.main_regime = regimeName(main->first);
        windows.push_back(segment);
        window_sums.push_back(window.speed_before);
        window = Accumulator{};
        window_regimes.clear();
        window_start = k + 1;
      }
    }
    addSpectrum(run, n, before[r], after[r], options, &band_before, &band_after, &out);
  }
  for (DrivingRegime regime : all_regimes)
  {
    out.regimes.push_back(toGroup(regimeName(regime), by_regime[regime], total));
  }
  for (const auto& [band, acc] : by_speed)
  {
    const double lo = band * options.speed_band_width_mps;
    char name[64];
    std::snprintf(name, sizeof name, "%g-%g m/s", lo, lo + options.speed_band_width_mps);
    out.speed_bands.push_back(toGroup(name, acc, total));
  }
  double power_total = 0.0;
  for (double p : band_before)
  {
    power_total += p;
  }
  for (std::size_t b = 0; b < bands; ++b)
  {
    FrequencyBand band;
    band.lower_hz = b == 0 ? 0.0 : options.frequency_band_edges_hz[b - 1];
    band.upper_hz = b + 1 < bands ? options.frequency_band_edges_hz[b] : 0.0;
    if (b + 1 < bands)
    {
      band.name = bandName(band.lower_hz, band.upper_hz);
    }
    else
    {
      char name[64];
      std::snprintf(name, sizeof name, "above %g Hz", band.lower_hz);
      band.name = name;  // up to the Nyquist frequency of the data
    }
    band.share_of_speed_residual_power_before = power_total > 0.0 ? band_before[b] / power_total : 0.0;
    band.share_of_speed_residual_power_after = power_total > 0.0 ? band_after[b] / power_total : 0.0;
    out.frequency_bands.push_back(band);
  }
  std::vector<std::size_t> order(windows.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    order[i] = i;
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return window_sums[a] > window_sums[b]; });
  for (std::size_t i = 0; i < order.size() && i < options.worst_segments; ++i)
  {
    WorstSegment segment = windows[order[i]];
    segment.share_of_squared_speed_error = total.speed_before > 0.0 ? window_sums[order[i]] / total.speed_before : 0.0;
    out.segments.push_back(segment);
  }
  return out;
}

}  // namespace acc
