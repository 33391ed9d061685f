#include "acc_identification/reproduction/simulated_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/platoon_simulation.h"
#include "acc_identification/model/string_stability.h"
#include "acc_identification/reproduction/figure_csv.h"
#include "acc_identification/reproduction/figure_summary.h"
#include "acc_identification/reproduction/frequency_response.h"
#include "acc_identification/reproduction/lambda2_map.h"
#include "acc_identification/reproduction/lead_inputs.h"
#include "acc_identification/reproduction/lead_profiles.h"
#include "acc_identification/reproduction/platoon_responses.h"

namespace acc
{
using nlohmann::json;

namespace
{
/// Cars times samples of a simulated platoon at most this: its speeds and gaps then take under a
/// gigabyte.
constexpr double kMaxPlatoonSamples = 6e7;

/// Refuses a platoon too large to simulate and hold, saying which options make it so, before any
/// of it is allocated.
void requireSimulable(std::size_t followers, double duration_s, double time_step_s)
{
  const double samples = static_cast<double>(followers + 1) * (duration_s / time_step_s + 1.0);
  if (samples > kMaxPlatoonSamples)
  {
    throw FigureUsageError(printfText("%zu cars over %g s at a %g s step are %.3g samples, above the %.3g this tool "
                                      "simulates: fewer --vehicles, a shorter --duration or --tail, or a coarser "
                                      "--time-step",
                                      followers + 1, duration_s, time_step_s, samples, kMaxPlatoonSamples));
  }
}
/// Why a simulated platoon of the law p at step h ran away: one car's Euler recursion unstable, the
/// law itself amplifying from car to car, or the Euler map amplifying where the law does not.
std::string runawayCause(const acc::AccParameters& p, double h)
{
  if (!acc::eulerRecursionStable(p, h))
    return printfText("one car's explicit Euler recursion at --time-step %g s is unstable for these parameters "
                      "(a finer --time-step)", h);
  if (!acc::analyzeStringStability(p).string_stable)
    return "the law amplifies from car to car (string unstable) until the platoon leaves it";
  return printfText("the Euler recursion at --time-step %g s amplifies from car to car (peak %.3f dB) where the law "
                    "does not (a finer --time-step)", h, acc::eulerPeak(p, h).gain_db);
}

/// Where a simulated platoon runs away (isRunaway: a speed or gap beyond the simulable range, or
/// not a number), and why (runawayCause). Said as a warning and returned for the summary (null
/// while it stays bounded), since the figure's numbers past it are not a platoon's: a
/// stable-looking peak of 1e200 m/s was printed as is.
json runawayJson(const PlatoonTrajectory& platoon, const NamedSetting& setting, const FigureRequest& request)
{
  for (std::size_t vehicle = 1; vehicle < platoon.vehicleCount(); ++vehicle)
  {
    for (std::size_t k = 0; k < platoon.sampleCount(); ++k)
    {
      if (!isRunaway(platoon.speed_mps[vehicle][k], platoon.space_gap_m[vehicle][k]))
        continue;
      const double t_s = static_cast<double>(k) * platoon.time_step_s;
      const std::string cause = runawayCause(setting.parameters, platoon.time_step_s);
      std::fprintf(request.streams.notes,
                   "warning: %s: DIVERGED: follower %zu leaves the simulable range (|speed| or |gap| beyond %g) at "
                   "t = %.1f s: %s; the numbers printed for this setting are not a platoon's\n",
                   setting.name.c_str(), vehicle, kDivergenceBound, t_s, cause.c_str());
      return {{"vehicle", vehicle}, {"time_s", t_s}, {"cause", cause}};
    }
  }
  return nullptr;
}

/// The step's times in order within the run, and a lead that keeps driving forwards.
void requireStepInsideRun(double speed, double step, double down_s, double up_s, double duration_s)
{
  if (!(down_s > 0.0 && down_s < up_s && up_s < duration_s))
  {
    throw FigureUsageError(printfText("--step-down-at %g and --step-up-at %g s must satisfy 0 < down < up < "
                                      "--duration (%g s): the lead cruises, steps down, then back up within the run",
                                      down_s, up_s, duration_s));
  }
  if (step >= speed)
  {
    throw FigureUsageError(printfText("--step %g m/s must be below --speed %g m/s: the lead would stop or drive "
                                      "backwards",
                                      step, speed));
  }
}
}  // namespace

json lambda2MapFigure(const FigureRequest& request)
{
  const FigureOptions& options = request.options;
  acc::Lambda2MapGrid grid;
  if (options.has("map-tau-e"))
  {
    grid.tau_e_s = parseNumberList(options.text("map-tau-e", ""), "map-tau-e");
  }
  grid.k1_max_per_s2 = options.positive("k1-max", grid.k1_max_per_s2);
  grid.k2_max_per_s = options.positive("k2-max", grid.k2_max_per_s);
  grid.k1_min_per_s2 = std::min(grid.k1_min_per_s2, grid.k1_max_per_s2 / 100.0);
  grid.k1_points = grid.k2_points = options.count("grid", 100, 2);
  if (grid.k1_points > 2000)
    throw FigureUsageError("--grid must be at most 2000 (points per axis of the map, for each tau_e)");
  const auto map = acc::lambda2Map(grid);
  CsvWriter csv(request.csv_path, "tau_e_s,k1_per_s2,k2_per_s,lambda2,string_stable");
  for (const acc::Lambda2MapSample& s : map)
  {
    csv.row() << s.tau_e_s << ',' << s.k1_per_s2 << ',' << s.k2_per_s << ',' << s.lambda2 << ','
              << (s.string_stable ? 1 : 0) << '\n';
  }
  csv.close();
  const std::size_t disagreements = acc::closedFormDisagreements(map);
  json summary = {{"figure", "lambda2-map"}, {"samples", map.size()}, {"closed_form_disagreements", disagreements}};
  std::fprintf(request.streams.numbers, "lambda2 map (paper Fig. 1): %zu samples, k1 in [%g, %g], k2 in [%g, %g]\n",
               map.size(), grid.k1_min_per_s2, grid.k1_max_per_s2, grid.k2_min_per_s, grid.k2_max_per_s);
  for (double tau : grid.tau_e_s)
  {
    const double fraction = acc::stableFraction(map, tau);
    summary["stable_fraction"][std::to_string(tau)] = fraction;
    std::fprintf(request.streams.numbers, "  tau_e = %5.2f s: %5.1f %% of the grid string stable\n", tau,
                 100.0 * fraction);
  }
  std::fprintf(request.streams.numbers, "  grid points where the verdict differs from k1 tau^2 + 2 k2 tau >= 2: %zu\n",
               disagreements);
  return summary;
}

json stepFigure(const FigureRequest& request)
{
  const FigureOptions& options = request.options;
  const double h = request.time_step_s;
  const auto settings = resolveSettings(options, {"fig2-unstable", "fig2-stable"});
  const std::size_t vehicles = options.count("vehicles", 9, 1);
  const double speed = options.positive("speed", 25.0), step = options.positive("step", 5.0);
  const double duration_s = options.positive("duration", 200.0);
  const double down_s = options.number("step-down-at", 20.0), up_s = options.number("step-up-at", 60.0);
  requireStepInsideRun(speed, step, down_s, up_s, duration_s);
  requireSimulable(vehicles, duration_s, h);
  const auto lead = acc::stepDownUpLeadProfile(speed, step, down_s, up_s, duration_s, h);
  std::vector<std::pair<std::string, acc::PlatoonTrajectory>> runs;
  json summary = {{"figure", "step"}, {"vehicles", vehicles}, {"cruise_speed_mps", speed}, {"step_mps", step}};
  std::fprintf(request.streams.numbers, "lead step %g -> %g -> %g m/s, %zu followers (paper Fig. 2)\n", speed,
               speed - step, speed, vehicles);
  for (const auto& setting : settings)
  {
    runs.emplace_back(setting.name, acc::simulatePlatoon(setting.parameters, lead, h, vehicles));
    const auto response = acc::measureDisturbanceResponse(runs.back().second);
    const auto& last = response.per_vehicle.back();
    const auto excursion = acc::lastFollowerStepExcursion(response, speed - step);
    const double undershoot = excursion.undershoot_below_low_speed_mps;
    const double overshoot = excursion.overshoot_above_cruise_mps;
    summary["settings"].push_back({{"parameters", settingSummaryJson(setting)},
                                   {"response", disturbanceJson(response)},
                                   {"last_undershoot_below_low_speed_mps", undershoot},
                                   {"last_overshoot_above_cruise_mps", overshoot},
                                   {"runaway", runawayJson(runs.back().second, setting, request)}});
    std::fprintf(request.streams.numbers,
                 "  %-14s last follower: minimum %.3f m/s (undershoot %.3f below the lead's low speed), maximum "
                 "%.3f m/s (overshoot %.3f above cruise)\n",
                 setting.name.c_str(), last.minimum_speed_mps, undershoot, last.maximum_speed_mps, overshoot);
  }
  writePlatoonCsv(request.csv_path, runs);
  return summary;
}

json bodeFigure(const FigureRequest& request)
{
  const FigureOptions& options = request.options;
  const double h = request.time_step_s;
  const auto settings = resolveSettings(options, {"min", "max"});
  const auto frequencies = acc::logSpacedFrequencies(options.positive("min-frequency", 1e-3),
                                                     options.positive("max-frequency", 10.0),
                                                     options.count("points", 400, 2));
  CsvWriter csv(request.csv_path, "setting,frequency_rad_s,gain_db,euler_gain_db");
  json summary = {{"figure", "bode"}, {"time_step_s", h}};
  std::fprintf(request.streams.numbers, "Bode magnitude of the speed-to-speed transfer function (paper Fig. 6)\n");
  for (const auto& setting : settings)
  {
    for (const acc::BodeSample& s : acc::bodeMagnitude(setting.parameters, frequencies, h))
    {
      csv.row() << setting.name << ',' << s.frequency_rad_s << ',' << s.gain_db << ',' << s.euler_gain_db << '\n';
    }
    const json p = settingSummaryJson(setting);
    // The CSV's Euler column is what a platoon simulated at this step passes on: its peak beside
    // the law's, since at a coarse step it amplifies where the law does not.
    const acc::EulerPeak euler = acc::eulerPeak(setting.parameters, h);
    summary["settings"].push_back({{"parameters", p},
                                   {"euler_peak_gain_db", euler.gain_db},
                                   {"euler_peak_frequency_rad_s", euler.frequency_rad_s},
                                   {"euler_recursion_stable", acc::eulerRecursionStable(setting.parameters, h)}});
    std::fprintf(request.streams.numbers, "  %-14s amplified below %.4f rad/s, peak %.3f dB at %.4f rad/s\n",
                 setting.name.c_str(), p["amplified_band_upper_rad_s"].get<double>(), p["peak_gain_db"].get<double>(),
                 p["peak_frequency_rad_s"].get<double>());
    std::fprintf(request.streams.numbers, "  %-14s its Euler recursion at %g s: peak %.3f dB at %.4f rad/s%s\n", "", h,
                 euler.gain_db, euler.frequency_rad_s,
                 euler.gain_db > 1e-9 && p["peak_gain_db"].get<double>() <= 1e-9
                     ? " (amplifies where the law does not: a simulation at this step is not the law's)"
                     : "");
  }
  csv.close();
  return summary;
}

json sinusoidFigure(const FigureRequest& request)
{
  const FigureOptions& options = request.options;
  const double h = request.time_step_s;
  const auto settings = resolveSettings(options, {"min", "max"});
  const std::size_t vehicles = options.count("vehicles", 10, 1);
  const double w = options.positive("frequency", 0.204);
  const double duration = options.positive("duration", 620.0);
  requireSimulable(vehicles, duration, h);
  const double fit_s = options.positive("fit-periods", 5.0) * 2.0 * M_PI / w;
  const double lead_in_s = options.between("lead-in", 20.0, 0.0, duration);
  if (options.positive("amplitude", 1.0) >= options.positive("speed", 20.0))
  {
    throw FigureUsageError("--amplitude must be below --speed: the lead would stop or drive backwards");
  }
  if (fit_s >= duration - lead_in_s)
  {
    throw FigureUsageError("--fit-periods covers more than the oscillating part of --duration");
  }
  const auto lead = acc::sinusoidLeadProfile(options.positive("speed", 20.0), options.positive("amplitude", 1.0), w,
                                             lead_in_s, duration, h);
  const std::size_t fit_from = lead.size() - static_cast<std::size_t>(std::round(fit_s / h));
  std::vector<std::pair<std::string, acc::PlatoonTrajectory>> runs;
  json summary = {{"figure", "sinusoid"}, {"vehicles", vehicles}, {"frequency_rad_s", w},
                  {"fit_from_s", static_cast<double>(fit_from) * h}};
  std::fprintf(request.streams.numbers,
               "sinusoidal lead at %.4f rad/s, %zu followers, amplitudes fitted over the last %.0f s (paper Fig. 7)\n",
               w, vehicles, fit_s);
  for (const auto& setting : settings)
  {
    runs.emplace_back(setting.name, acc::simulatePlatoon(setting.parameters, lead, h, vehicles));
    const auto r = acc::measureSinusoidResponse(runs.back().second, setting.parameters, w, fit_from);
    summary["settings"].push_back({{"parameters", settingSummaryJson(setting)},
                                   {"amplitude_mps", r.amplitude_mps},
                                   {"last_to_first_follower", r.last_to_first_follower},
                                   {"last_follower_to_lead", r.last_follower_to_lead},
                                   {"model_gain", r.model_gain},
                                   {"model_gain_db", 20.0 * std::log10(r.model_gain)},
                                   {"euler_gain", r.euler_gain},
                                   {"model_gain_to_the_n", r.model_gain_over_platoon},
                                   {"euler_gain_to_the_n", r.euler_gain_over_platoon},
                                   {"runaway", runawayJson(runs.back().second, setting, request)}});
    std::fprintf(request.streams.numbers,
                 "  %-14s |Gamma| = %.4f (%+.3f dB); follower %zu / lead = %.4f (|Gamma|^%zu = %.4f, Euler %.4f); "
                 "follower %zu / follower 1 = %.4f\n",
                 setting.name.c_str(), r.model_gain, 20.0 * std::log10(r.model_gain), vehicles, r.last_follower_to_lead,
                 vehicles, r.model_gain_over_platoon, r.euler_gain_over_platoon, vehicles, r.last_to_first_follower);
  }
  writePlatoonCsv(request.csv_path, runs);
  return summary;
}

json leadProfileFigure(const FigureRequest& request)
{
  const FigureOptions& options = request.options;
  const double h = request.time_step_s;
  const auto settings = resolveSettings(options, {"min", "max"});
  const std::string id = options.text("profile", "I");
  if (id.size() != 1 || !acc::isLeadProfileId(id[0]))
  {
    throw FigureUsageError("--profile must be one of " + acc::leadProfileIds());
  }
  acc::LeadProfileSpec spec = acc::leadProfileSpec(id[0]);
  // A gentler ramp than 0.01 m/s^2 would make a profile of hours out of one speed change.
  spec.ramp.acceleration_mps2 = options.between("lead-accel", spec.ramp.acceleration_mps2, 0.01, 20.0);
  spec.ramp.deceleration_mps2 = options.between("lead-decel", spec.ramp.deceleration_mps2, 0.01, 20.0);
  const std::size_t vehicles = options.count("vehicles", 60, 1);
  const std::size_t short_platoon = std::min(vehicles, options.count("short-platoon", 15, 1));
  const auto profile = acc::sampleLeadProfile(spec, h);
  const double tail_s = options.between("tail", 600.0, 0.0, std::numeric_limits<double>::infinity());
  requireSimulable(vehicles, static_cast<double>(profile.size()) * h + tail_s, h);
  const auto lead = acc::withFinalHold(profile, tail_s, h);
  const std::string description = spec.description + "; " + acc::describeLeadRamp(spec.ramp);
  json summary = {{"figure", "lead-profile"}, {"profile", description}, {"vehicles", vehicles},
                  {"short_platoon", short_platoon}, {"profile_duration_s", static_cast<double>(profile.size() - 1) * h},
                  {"lead_accel_mps2", spec.ramp.acceleration_mps2}, {"lead_decel_mps2", spec.ramp.deceleration_mps2}};
  std::fprintf(
      request.streams.numbers,
      "lead profile %s\n  %zu followers (first %zu = the short platoon), record %.0f s (profile %.0f s + hold)\n",
      description.c_str(), vehicles, short_platoon, static_cast<double>(lead.size() - 1) * h,
      static_cast<double>(profile.size() - 1) * h);
  std::vector<std::pair<std::string, acc::PlatoonTrajectory>> runs;
  for (const auto& setting : settings)
  {
    runs.emplace_back(setting.name, acc::simulatePlatoon(setting.parameters, lead, h, vehicles));
    const auto full = acc::measureDisturbanceResponse(runs.back().second);
    const auto shorter = acc::measureDisturbanceResponse(acc::firstFollowers(runs.back().second, short_platoon));
    summary["settings"].push_back({{"parameters", settingSummaryJson(setting)},
                                   {"long", disturbanceJson(full)},
                                   {"short", disturbanceJson(shorter)},
                                   {"runaway", runawayJson(runs.back().second, setting, request)}});
    const auto& lead_d = full.per_vehicle.front();
    const auto& short_d = shorter.per_vehicle.back();
    const auto& long_d = full.per_vehicle.back();
    std::fprintf(request.streams.numbers,
                 "  %-8s drop below cruise: lead %.2f, follower %zu %.2f, follower %zu %.2f m/s; peak-to-peak: "
                 "%.2f, %.2f, %.2f m/s\n",
                 setting.name.c_str(), lead_d.drop_below_reference_mps, short_platoon, short_d.drop_below_reference_mps,
                 vehicles, long_d.drop_below_reference_mps, lead_d.peak_to_peak_mps, short_d.peak_to_peak_mps,
                 long_d.peak_to_peak_mps);
    std::fprintf(request.streams.numbers, "           by drop: %s\n           by peak-to-peak: %s\n",
                 onsetText(full.by_drop).c_str(), onsetText(full.by_peak_to_peak).c_str());
    if (full.first_negative_speed_vehicle)
    {
      std::fprintf(request.streams.numbers,
                   "           speeds go negative from follower %zu on: the linear model no longer describes a car\n",
                   *full.first_negative_speed_vehicle);
    }
    if (!full.last_follower_settled)
    {
      std::fprintf(request.streams.notes,
                   "warning: %s: the last follower has not settled by the end; lengthen --tail\n",
                   setting.name.c_str());
    }
  }
  writePlatoonCsv(request.csv_path, runs);
  return summary;
}

}  // namespace acc
