#include "acc_identification/campaign/link_evidence.h"
#include "acc_identification/model/car_following_run.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/diagnosis/final_model_bootstrap.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/parallel_tasks.h"

namespace acc
{
void collectLinkDips(const std::vector<PlatoonCheck>& platoons, const std::string& vehicle, const std::string& setting,
                     std::vector<double>* follower, std::vector<double>* leader, const LinkDipFilter& include)
{
  for (std::size_t r = 0; r < platoons.size(); ++r)
  {
    const PlatoonCheck& check = platoons[r];
    if (settingOfCar(check.car_settings, check.setting, vehicle) != setting)
      continue;
    for (std::size_t q = 0; q < check.perturbations.size(); ++q)
    {
      const auto& rows = check.perturbations[q].positions;
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        if (rows[i].name == vehicle && rows[i - 1].position + 1 == rows[i].position &&
            (!include || include(r, q, rows[i].position)))
        {
          follower->push_back(rows[i].measured.dip_mps);
          leader->push_back(rows[i - 1].measured.dip_mps);
        }
      }
    }
  }
}

AugmentedRefit refitAsCampaignFitted(const PlatoonCandidate& candidate, const AccParameters& base_fit,
                                     const AugmentedFit& diagnosed_fit, const RefitBootstrapOptions& options)
{
  // By value: the procedure outlives this call and the references it was given.
  return [candidate, base_fit, diagnosed_fit, options](const std::vector<CarFollowingRun>& replicate) {
    AugmentedFit replicate_base;
    replicate_base.base = refitBaseModel(base_fit, replicate, options).parameters;
    return fitCandidate(candidate, replicate, {replicate_base, diagnosed_fit});
  };
}

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kDipRatioReplicates = 1999;

/// Every segment of the group's runs in one series, a NaN sample between segments so that no
/// Welch segment straddles two; and the median step.
void concatenateSegments(const CampaignGroup& group, std::vector<double>* leader, std::vector<double>* follower,
                         double* step_s, double* median_speed_mps)
{
  std::vector<double> speeds;
  const std::vector<CarFollowingRun> segments = group.segments();
  for (const CarFollowingRun& segment : segments)
  {
    if (!leader->empty())
    {
      leader->push_back(kNaN);
      follower->push_back(kNaN);
    }
    leader->insert(leader->end(), segment.leader_speed_mps.begin(), segment.leader_speed_mps.end());
    follower->insert(follower->end(), segment.follower_speed_mps.begin(), segment.follower_speed_mps.end());
    speeds.insert(speeds.end(), segment.follower_speed_mps.begin(), segment.follower_speed_mps.end());
  }
  *step_s = medianStepS(segments);
  *median_speed_mps = finiteMedian(speeds);
}

/// Above this the 10 Hz records are spline-interpolated GNSS and the ACC's own dynamics are long
/// over: car-following perturbations and ACC responses live below 1 rad/s.
constexpr double kMaxLinkFrequencyRadS = 2.0;
constexpr std::size_t kLinkWelchSegmentSamples = 512;

/// Ranges of consecutive bins (up to kMaxLinkFrequencyRadS) where the empirical gain is
/// informative and the model's gain lies outside its band.
std::vector<std::pair<double, double>> departures(const EmpiricalResponse& response, const std::vector<double>& model)
{
  std::vector<std::pair<double, double>> ranges;
  if (response.effective_segments < kMinEffectiveSegments)
    return ranges;
  bool open = false;
  for (std::size_t k = 0; k < response.frequency_rad_s.size() && k < model.size(); ++k)
  {
    const bool departs = response.frequency_rad_s[k] <= kMaxLinkFrequencyRadS && response.informative[k] &&
                         std::isfinite(model[k]) &&
                         (model[k] < response.gain_lower[k] || model[k] > response.gain_upper[k]);
    if (departs && !open)
      ranges.push_back({response.frequency_rad_s[k], response.frequency_rad_s[k]});
    if (departs)
      ranges.back().second = response.frequency_rad_s[k];
    open = departs;
  }
  return ranges;
}

/// The diagnosed model's refitting bootstrap when the group's runs are short (ShortRunsBootstrapOptions).
void bootstrapShortLink(const CampaignGroup& group, const GroupResult& result, const ShortRunsBootstrapOptions& options,
                        LinkEvidence* evidence)
{
  if (options.replicates == 0 || !evidence->diagnosed_available || evidence->diagnosed.effects.empty())
    return;  // before the runs are copied: the library's default asks for no bootstrap
  const std::vector<CarFollowingRun> runs = group.segments();
  if (!wantsShortRunsBootstrap(runs, options))
    return;
  RefitBootstrapOptions bootstrap;
  bootstrap.replicates = options.replicates;
  bootstrap.threads = 1;  // the links themselves run in parallel
  bootstrap.seed = result.seed;
  const AugmentedRefit refit = refitAsCampaignFitted(evidence->diagnosed, result.identification.calibration.parameters,
                                                     evidence->diagnosed_fit, bootstrap);
  evidence->diagnosed_bootstrap = bootstrapDiagnosedModel(
      evidence->diagnosed_fit, runs, candidateCalibrationOptions(evidence->diagnosed), bootstrap, refit);
}

/// The chosen candidate fitted on all the group's runs, warm-started from the group's base fit.
void fitDiagnosed(const CampaignGroup& group, const GroupResult& result, const PlatoonCandidate& candidate,
                  LinkEvidence* evidence)
{
  evidence->diagnosed = candidate;
  if (!result.fitted())
  {
    evidence->note = "no base fit: " + result.reason;
    return;
  }
  const AugmentedFit fit = fitOnAllRuns(candidate, group, result);
  evidence->diagnosed_available = fit.usable();
  if (!fit.diverged && !fit.locally_stable)
    evidence->note = "the diagnosed model's fit reached no locally stable model: not used";
  evidence->diagnosed_fit = fit;
  evidence->diagnosed_small_signal =
      analyzeAugmentedStability(fit.base, candidate.effects, fit.settings, evidence->operating_speed_mps);
}

LinkEvidence evidenceOf(const CampaignInputs& inputs, const CampaignGroup& group, const GroupResult& result,
                        const std::vector<PlatoonCheck>& platoons, const PlatoonCandidate& diagnosed,
                        const PlatoonCheckOptions& platoon_options, const ShortRunsBootstrapOptions& bootstrap)
{
  LinkEvidence evidence;
  evidence.vehicle = group.vehicle;
  evidence.setting = group.setting;
  std::vector<double> follower_dips, leader_dips;
  collectLinkDips(platoons, group.vehicle, group.setting, &follower_dips, &leader_dips);
  evidence.dip_ratio = linkDipRatio(follower_dips, leader_dips, kDipRatioReplicates, result.seed);
  std::vector<double> leader, follower;
  double step_s = kNaN;
  concatenateSegments(group, &leader, &follower, &step_s, &evidence.operating_speed_mps);
  if (step_s > 0.0)
  {
    // 51 s segments: platoon runs last 1-7 minutes, and a peak read a few per cent low (the
    // window's smoothing, empirical_response.h) beats no estimate from too few segments.
    WelchOptions welch;
    welch.segment_samples = kLinkWelchSegmentSamples;
    evidence.response = empiricalResponse(leader, follower, step_s, welch);
  }
  evidence.base_available = result.fitted();
  fitDiagnosed(group, result, diagnosed, &evidence);
  bootstrapShortLink(group, result, bootstrap, &evidence);
  for (double w : evidence.response.frequency_rad_s)
  {
    evidence.model_gain_base.push_back(result.fitted() ? transferGain(result.identification.calibration.parameters, w)
                                                       : kNaN);
    evidence.model_gain_diagnosed.push_back(
        evidence.diagnosed_available ? augmentedTransferGain(evidence.diagnosed_fit.base, evidence.diagnosed_fit.settings,
                                                             evidence.operating_speed_mps, w)
                                     : kNaN);
  }
  evidence.base_departs_rad_s = departures(evidence.response, evidence.model_gain_base);
  evidence.diagnosed_departs_rad_s = departures(evidence.response, evidence.model_gain_diagnosed);
  if (evidence.diagnosed_available)
    simulateLongPlatoon(inputs, group.setting, platoon_options, &evidence);
  else
    evidence.long_platoon_dip_ratio = kNaN;
  if (!responseRead(evidence))
    evidence.note += (evidence.note.empty() ? "" : "; ") +
                     std::string("fewer than 4 effective Welch segments of 512 samples: the empirical frequency "
                                 "response is not read");
  return evidence;
}
}  // namespace

std::vector<EffectSize> diagnosedEffectSizes(const LinkEvidence& evidence)
{
  std::vector<EffectSize> sizes;
  if (evidence.diagnosed_fit.effects.empty())
    return sizes;  // not fitted: the group has no base fit
  const double threshold = determinedThreshold(kDiagnosedSizeAlpha, evidence.diagnosed.effects);
  for (EffectKind kind : evidence.diagnosed.effects)
  {
    sizes.push_back(effectSizeIn(evidence.diagnosed_fit, kind, threshold));
    if (evidence.diagnosed_bootstrap)
      judgeByBootstrap(kind, *evidence.diagnosed_bootstrap, &sizes.back());
  }
  return sizes;
}

AugmentedFit fitOnAllRuns(const PlatoonCandidate& candidate, const CampaignGroup& group, const GroupResult& result)
{
  AugmentedFit warm;
  warm.base = result.identification.calibration.parameters;
  if (candidate == PlatoonCandidate{})
    return warm;
  return fitCandidate(candidate, group.segments(), warm);
}

namespace
{
/// The first car's speed over the rows [first, end) of the file, then kLongPlatoonTailS at its last
/// speed, at the data's median step.
CarFollowingRun leadWithTail(const OpenAccFile& file, std::size_t first, std::size_t end)
{
  CarFollowingRun run;
  run.time_s = sliceRows(file.time_s, first, end);
  run.leader_speed_mps = sliceRows(file.vehicle(1)->speed_mps, first, end);
  const double step_s = medianStepS({run});
  double last_mps = kNaN;
  for (auto v = run.leader_speed_mps.rbegin(); v != run.leader_speed_mps.rend() && !std::isfinite(last_mps); ++v)
    last_mps = *v;
  if (!(step_s > 0.0) || !std::isfinite(last_mps))
    return run;
  const double last_s = run.time_s.back();
  const auto tail = static_cast<std::size_t>(std::ceil(kLongPlatoonTailS / step_s));
  for (std::size_t i = 1; i <= tail; ++i)
  {
    run.time_s.push_back(last_s + static_cast<double>(i) * step_s);
    run.leader_speed_mps.push_back(last_mps);
  }
  return run;
}

/// The perturbation with its window running on to the next one's onset (or the record's end):
/// where the tenth car of a long platoon dips, long after the first car's window.
Perturbation untilNextOnset(const std::vector<Perturbation>& perturbations, std::size_t k, std::size_t samples)
{
  Perturbation whole = perturbations[k];
  whole.window_end = k + 1 < perturbations.size() ? perturbations[k + 1].onset : samples;
  return whole;
}

/// Whether the car is still slowing at the window's last sample (its minimum there): its dip is
/// cut short.
bool stillSlowingAtWindowEnd(const std::vector<double>& speed_mps, const Perturbation& window)
{
  const auto begin = speed_mps.begin() + static_cast<std::ptrdiff_t>(window.onset);
  const auto end = speed_mps.begin() + static_cast<std::ptrdiff_t>(std::min(window.window_end, speed_mps.size()));
  return end - begin > 1 && std::min_element(begin, end) == end - 1;
}
}  // namespace

void simulateLongPlatoon(const CampaignInputs& inputs, const std::string& setting,
                         const PlatoonCheckOptions& platoon_options, LinkEvidence* evidence)
{
  std::vector<double> ratios;
  evidence->long_platoon_ran_away_at_car = 0;
  evidence->long_platoon_breaks_down_at_car = 0;
  evidence->long_platoon_breakdown.clear();
  evidence->long_platoon_collides = false;
  evidence->long_platoon_unfinished = 0;
  for (const CampaignFile& file : inputs.files)
  {
    if (file.setting != setting || file.contents.vehicle(1) == nullptr)
      continue;
    std::size_t first = 0, end = 0;
    const std::vector<Perturbation> perturbations = leadPerturbations(file.contents, platoon_options, &first, &end);
    if (perturbations.empty())
      continue;
    CarFollowingRun run = leadWithTail(file.contents, first, end);
    const std::vector<double> lead_speed = run.leader_speed_mps;
    const double v0 = run.leader_speed_mps.front();
    const AccParameters& p = evidence->diagnosed_fit.base;
    bool diverged = false;
    for (int car = 0; car < kLongPlatoonCars && !diverged; ++car)
    {
      run.follower_speed_mps.assign(run.size(), v0);
      run.space_gap_m.assign(run.size(), p.eta_m + p.tau_e_s * v0);
      const SimulatedFollower sim = simulateFollower(p, evidence->diagnosed_fit.settings, run);
      diverged = sim.diverged;
      if (diverged && evidence->long_platoon_ran_away_at_car == 0)
        evidence->long_platoon_ran_away_at_car = static_cast<std::size_t>(car) + 1;
      bool collision = false;
      const std::string breakdown = describeBreakdown(sim, run.time_s, &collision);
      const auto car_number = static_cast<std::size_t>(car) + 1;
      if (!breakdown.empty() &&
          (evidence->long_platoon_breaks_down_at_car == 0 || car_number < evidence->long_platoon_breaks_down_at_car))
      {
        evidence->long_platoon_breaks_down_at_car = car_number;
        evidence->long_platoon_collides = collision;
        evidence->long_platoon_breakdown = "car " + std::to_string(car_number) + " in " + file.name + ": " + breakdown;
      }
      run.leader_speed_mps = sim.speed_mps;
    }
    for (std::size_t k = 0; k < perturbations.size() && !diverged; ++k)
    {
      const double lead_dip = dipDepthMps(run.time_s, lead_speed, perturbations[k], platoon_options.perturbation);
      const Perturbation whole = untilNextOnset(perturbations, k, run.size());
      if (!(lead_dip > 0.3))
        continue;
      if (stillSlowingAtWindowEnd(run.leader_speed_mps, whole))
      {
        ++evidence->long_platoon_unfinished;
        continue;
      }
      const double last_dip = dipDepthMps(run.time_s, run.leader_speed_mps, whole, platoon_options.perturbation);
      if (std::isfinite(last_dip))
        ratios.push_back(last_dip / lead_dip);
    }
  }
  evidence->long_platoon_perturbations = ratios.size();
  evidence->long_platoon_dip_ratio = finiteMedian(ratios);
}

std::vector<LinkEvidence> gatherLinkEvidence(const CampaignInputs& inputs, const std::vector<GroupResult>& groups,
                                             const std::vector<PlatoonCheck>& platoons,
                                             const PlatoonCandidate& diagnosed, std::size_t threads,
                                             const PlatoonCheckOptions& platoon_options,
                                             const ShortRunsBootstrapOptions& bootstrap)
{
  std::vector<LinkEvidence> out(inputs.groups.size());
  runTasksInParallel(out.size(), threads, [&](std::size_t i) {
    out[i] = evidenceOf(inputs, inputs.groups[i], groups[i], platoons, diagnosed, platoon_options, bootstrap);
  });
  return out;
}

}  // namespace acc
