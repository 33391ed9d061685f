// platoon: the numbers and data behind the figures of Gunter et al. (issue 7), for the paper's
// settings or any calibration. Writes the figure's data as CSV, prints the key numbers and, on
// request, writes them as JSON for scripts/plot_figures.py and for comparisons.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/model/platoon_simulation.h"
#include "acc_identification/reproduction/equilibrium_regression.h"
#include "acc_identification/reproduction/lead_profiles.h"
#include "acc_identification/reproduction/frequency_response.h"
#include "acc_identification/reproduction/lambda2_map.h"
#include "acc_identification/reproduction/lead_inputs.h"
#include "acc_identification/reproduction/parameter_file.h"
#include "acc_identification/reproduction/platoon_responses.h"
#include "acc_identification/reproduction/run_comparison.h"
#include "acc_identification/model/string_stability.h"

using nlohmann::json;

namespace
{
const char* kFigures = R"(FIGURE: a name or the paper's figure number (fig1 to fig8), with each option's default:
  lambda2-map  (fig1)  lambda2 over (k1, k2) for several tau_e; --map-tau-e 0.5,1,1.5,2,3
                       --k1-max 1 --k2-max 1 --grid 100
  step         (fig2)  platoon behind a lead speed step down and back up; --vehicles 9 --speed 25
                       --step 5 --step-down-at 20 --step-up-at 60 --duration 200
                       (default settings: fig2-unstable, fig2-stable)
  bode         (fig6)  |Gamma(jw)| in dB; --min-frequency 0.001 --max-frequency 10 --points 400
  sinusoid     (fig7)  platoon behind a sinusoidal lead; --vehicles 10 --speed 20 --amplitude 1
                       --frequency 0.204 --lead-in 20 --duration 620 --fit-periods 5
  lead-profile (fig8)  platoon behind lead profile A..I of Sec. III; --profile I --vehicles 60
                       --short-platoon 15 --tail 600 [--lead-accel 1.5 --lead-decel 2.0]
  equilibrium  (fig5)  space gap against speed of runs with the equilibrium lines eta + tau_e v;
                       --run RUN.csv (repeatable) --max-relative-speed 0.5 --max-acceleration 0.1
  timeseries   (fig3, fig4) measured against simulated speed and gap of one run, split into
                       train and test parts; --run RUN.csv --train-fraction 0.5
settings (repeatable, in order; default min and max of Table II):
  --setting min|max|fig2-unstable|fig2-stable   --params CALIBRATE.json
  --k1 K1 --k2 K2 --tau-e TAU [--eta ETA]       (one custom set, named "custom")
common: --time-step 0.1 (Euler step of every simulation, s)
RUN.csv: canonical (time_s,space_gap_m,follower_speed_mps,leader_speed_mps) or OpenACC two-vehicle CSV.
)";

/// The paper's figure numbers, as a reader types them, for the names the figures have here.
const std::map<std::string, std::string> kFigureNumbers{
    {"fig1", "lambda2-map"}, {"fig2", "step"}, {"fig3", "timeseries"}, {"fig4", "timeseries"},
    {"fig5", "equilibrium"}, {"fig6", "bode"}, {"fig7", "sinusoid"},   {"fig8", "lead-profile"}};

/// Every FIGURE the command line accepts: the names and the figure numbers.
std::vector<std::string> acceptedFigures()
{
  std::vector<std::string> accepted{"lambda2-map", "step", "bode", "sinusoid", "lead-profile", "equilibrium", "timeseries"};
  for (const auto& number : kFigureNumbers)
    accepted.push_back(number.first);
  return accepted;
}

/// Thrown for bad input; main prints it with the usage and exits 2.
struct UsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Every value option the figures read: CLI11 parses them (unknown options and missing values
/// are its errors); each figure reads its own with the default it documents (kFigures).
const std::vector<std::string> kValueOptions{
    "setting", "params", "k1", "k2", "tau-e", "eta", "time-step", "vehicles", "map-tau-e", "k1-max", "k2-max",
    "grid", "speed", "step", "step-down-at", "step-up-at", "duration", "min-frequency", "max-frequency", "points",
    "amplitude", "frequency", "lead-in", "fit-periods", "profile", "short-platoon", "tail", "lead-accel",
    "lead-decel", "run", "max-relative-speed", "max-acceleration", "train-fraction"};

/// The parsed command line with typed access and each figure's defaults.
class Options
{
public:
  explicit Options(std::map<std::string, std::vector<std::string>> given) : given_(std::move(given)) {}

  double number(const std::string& name, double fallback) const
  {
    if (!has(name))
    {
      return fallback;
    }
    const std::string& text = given_.at(name).back();
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0')
    {
      throw UsageError("--" + name + ": '" + text + "' is not a number");
    }
    if (!std::isfinite(value))
    {
      throw UsageError("--" + name + " must be finite");
    }
    return value;
  }
  double positive(const std::string& name, double fallback) const
  {
    const double value = number(name, fallback);
    if (!(value > 0.0))
    {
      throw UsageError("--" + name + " must be positive");
    }
    return value;
  }
  std::size_t count(const std::string& name, std::size_t fallback, std::size_t minimum) const
  {
    const double value = number(name, static_cast<double>(fallback));
    if (value < static_cast<double>(minimum) || value != std::floor(value) || value > 1e6)
    {
      throw UsageError("--" + name + " must be a whole number >= " + std::to_string(minimum));
    }
    return static_cast<std::size_t>(value);
  }
  std::string text(const std::string& name, const std::string& fallback) const
  {
    return has(name) ? given_.at(name).back() : fallback;
  }
  std::vector<std::string> texts(const std::string& name) const
  {
    return has(name) ? given_.at(name) : std::vector<std::string>{};
  }
  bool has(const std::string& name) const { return given_.count(name) > 0 && !given_.at(name).empty(); }

private:
  std::map<std::string, std::vector<std::string>> given_;
};

std::vector<double> parseNumberList(const std::string& text, const std::string& option)
{
  std::vector<double> numbers;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(value))
    {
      throw UsageError("--" + option + ": '" + item + "' is not a number");
    }
    numbers.push_back(value);
  }
  return numbers;
}

/// The parameter sets to use, in command-line order, or the figure's defaults.
std::vector<acc::NamedSetting> resolveSettings(const Options& options, const std::vector<std::string>& defaults)
{
  std::vector<acc::NamedSetting> settings;
  for (const std::string& name : options.texts("setting"))
  {
    const auto found = acc::findNamedSetting(name);
    if (!found)
    {
      throw UsageError("unknown setting '" + name + "'");
    }
    settings.push_back(*found);
  }
  for (const std::string& path : options.texts("params"))
  {
    try
    {
      settings.push_back(acc::readParameterFile(path));
    }
    catch (const acc::ParameterFileError& error)
    {
      throw UsageError(error.what());
    }
  }
  if (options.has("k1") || options.has("k2") || options.has("tau-e") || options.has("eta"))
  {
    if (!options.has("k1") || !options.has("k2") || !options.has("tau-e"))
    {
      throw UsageError("--k1, --k2 and --tau-e go together (--eta defaults to 0)");
    }
    settings.push_back({"custom", "command line",
                        {options.number("k1", 0.0), options.number("k2", 0.0), options.number("tau-e", 0.0),
                         options.number("eta", 0.0)}});
  }
  for (const std::string& name : settings.empty() ? defaults : std::vector<std::string>{})
  {
    settings.push_back(*acc::findNamedSetting(name));
  }
  return settings;
}

json parametersJson(const acc::NamedSetting& setting)
{
  const acc::AccParameters& p = setting.parameters;
  const acc::StringStabilityReport report = acc::analyzeStringStability(p);
  return {{"name", setting.name},
          {"source", setting.source},
          {"k1_per_s2", p.k1_per_s2},
          {"k2_per_s", p.k2_per_s},
          {"tau_e_s", p.tau_e_s},
          {"eta_m", p.eta_m},
          {"lambda2", std::isfinite(report.lambda2) ? json(report.lambda2) : json("inf")},
          {"string_stable", report.string_stable},
          {"amplified_band_upper_rad_s", report.amplified_band_upper_rad_s},
          {"peak_gain_db", report.peak_gain_db},
          {"peak_frequency_rad_s", report.peak_frequency_rad_s}};
}

/// Writes a CSV; throws when the file cannot be written.
class CsvWriter
{
public:
  CsvWriter(const std::string& path, const std::string& header) : out_(path), path_(path)
  {
    if (!out_)
    {
      throw std::runtime_error("cannot write " + path);
    }
    out_.precision(9);
    out_ << header << '\n';
  }
  std::ostream& row() { return out_; }
  ~CsvWriter() = default;
  void close()
  {
    out_.close();
    if (!out_)
    {
      throw std::runtime_error("error writing " + path_);
    }
  }

private:
  std::ofstream out_;
  std::string path_;
};

/// Speeds of every vehicle of every platoon, one row per setting and sample.
void writePlatoonCsv(const std::string& path, const std::vector<std::pair<std::string, acc::PlatoonTrajectory>>& runs)
{
  const std::size_t vehicles = runs.front().second.vehicleCount();
  std::string header = "setting,time_s";
  for (std::size_t i = 0; i < vehicles; ++i)
  {
    header += ",v" + std::to_string(i) + "_mps";
  }
  CsvWriter csv(path, header);
  for (const auto& [name, platoon] : runs)
  {
    for (std::size_t k = 0; k < platoon.sampleCount(); ++k)
    {
      csv.row() << name << ',' << static_cast<double>(k) * platoon.time_step_s;
      for (std::size_t i = 0; i < platoon.vehicleCount(); ++i)
      {
        csv.row() << ',' << platoon.speed_mps[i][k];
      }
      csv.row() << '\n';
    }
  }
  csv.close();
}

template <typename T>
json optionalJson(const std::optional<T>& value)
{
  return value ? json(*value) : json(nullptr);
}

json disturbanceJson(const acc::DisturbanceResponse& response)
{
  json per_vehicle = json::array();
  for (const acc::VehicleDisturbance& d : response.per_vehicle)
  {
    per_vehicle.push_back({{"minimum_speed_mps", d.minimum_speed_mps},
                           {"maximum_speed_mps", d.maximum_speed_mps},
                           {"peak_to_peak_mps", d.peak_to_peak_mps},
                           {"drop_below_reference_mps", d.drop_below_reference_mps},
                           {"rise_above_reference_mps", d.rise_above_reference_mps}});
  }
  auto onset = [](const acc::GrowthOnset& o) {
    return json{{"decays_at_first", o.decays_at_first},
                {"smallest_at", o.smallest_at},
                {"growth_starts_at", optionalJson(o.growth_starts_at)},
                {"exceeds_lead_at", optionalJson(o.exceeds_lead_at)}};
  };
  return {{"followers", response.per_vehicle.size() - 1},
          {"reference_speed_mps", response.reference_speed_mps},
          {"per_vehicle", per_vehicle},
          {"growth_by_peak_to_peak", onset(response.by_peak_to_peak)},
          {"growth_by_drop", onset(response.by_drop)},
          {"first_negative_speed_vehicle", optionalJson(response.first_negative_speed_vehicle)},
          {"last_follower_settled", response.last_follower_settled}};
}

std::string onsetText(const acc::GrowthOnset& o)
{
  std::ostringstream text;
  text << (o.decays_at_first ? "decays first" : "grows from follower 1") << ", smallest at follower "
       << o.smallest_at;
  text << (o.growth_starts_at ? ", grows behind it" : ", still decaying at the end");
  if (o.exceeds_lead_at)
  {
    text << ", exceeds the lead's from follower " << *o.exceeds_lead_at;
  }
  else
  {
    text << ", never exceeds the lead's";
  }
  return text.str();
}

// ---- the figures -------------------------------------------------------------------------

json lambda2MapFigure(const Options& options, const std::string& csv_path)
{
  acc::Lambda2MapGrid grid;
  if (options.has("map-tau-e"))
  {
    grid.tau_e_s = parseNumberList(options.text("map-tau-e", ""), "map-tau-e");
  }
  grid.k1_max_per_s2 = options.positive("k1-max", grid.k1_max_per_s2);
  grid.k2_max_per_s = options.positive("k2-max", grid.k2_max_per_s);
  grid.k1_min_per_s2 = std::min(grid.k1_min_per_s2, grid.k1_max_per_s2 / 100.0);
  grid.k1_points = grid.k2_points = options.count("grid", 100, 2);
  const auto map = acc::lambda2Map(grid);
  CsvWriter csv(csv_path, "tau_e_s,k1_per_s2,k2_per_s,lambda2,string_stable");
  for (const acc::Lambda2MapSample& s : map)
  {
    csv.row() << s.tau_e_s << ',' << s.k1_per_s2 << ',' << s.k2_per_s << ',' << s.lambda2 << ','
              << (s.string_stable ? 1 : 0) << '\n';
  }
  csv.close();
  const std::size_t disagreements = acc::closedFormDisagreements(map);
  json summary = {{"figure", "lambda2-map"}, {"samples", map.size()}, {"closed_form_disagreements", disagreements}};
  std::printf("lambda2 map (paper Fig. 1): %zu samples, k1 in [%g, %g], k2 in [%g, %g]\n", map.size(),
              grid.k1_min_per_s2, grid.k1_max_per_s2, grid.k2_min_per_s, grid.k2_max_per_s);
  for (double tau : grid.tau_e_s)
  {
    const double fraction = acc::stableFraction(map, tau);
    summary["stable_fraction"][std::to_string(tau)] = fraction;
    std::printf("  tau_e = %5.2f s: %5.1f %% of the grid string stable\n", tau, 100.0 * fraction);
  }
  std::printf("  grid points where the verdict differs from k1 tau^2 + 2 k2 tau >= 2: %zu\n", disagreements);
  return summary;
}

json stepFigure(const Options& options, const std::string& csv_path, double h)
{
  const auto settings = resolveSettings(options, {"fig2-unstable", "fig2-stable"});
  const std::size_t vehicles = options.count("vehicles", 9, 1);
  const double speed = options.positive("speed", 25.0), step = options.positive("step", 5.0);
  const auto lead = acc::stepDownUpLeadProfile(speed, step, options.number("step-down-at", 20.0),
                                               options.number("step-up-at", 60.0), options.positive("duration", 200.0), h);
  std::vector<std::pair<std::string, acc::PlatoonTrajectory>> runs;
  json summary = {{"figure", "step"}, {"vehicles", vehicles}, {"cruise_speed_mps", speed}, {"step_mps", step}};
  std::printf("lead step %g -> %g -> %g m/s, %zu followers (paper Fig. 2)\n", speed, speed - step, speed, vehicles);
  for (const auto& setting : settings)
  {
    runs.emplace_back(setting.name, acc::simulatePlatoon(setting.parameters, lead, h, vehicles));
    const auto response = acc::measureDisturbanceResponse(runs.back().second);
    const auto& last = response.per_vehicle.back();
    const auto excursion = acc::lastFollowerStepExcursion(response, speed - step);
    const double undershoot = excursion.undershoot_below_low_speed_mps;
    const double overshoot = excursion.overshoot_above_cruise_mps;
    summary["settings"].push_back({{"parameters", parametersJson(setting)},
                                   {"response", disturbanceJson(response)},
                                   {"last_undershoot_below_low_speed_mps", undershoot},
                                   {"last_overshoot_above_cruise_mps", overshoot}});
    std::printf("  %-14s last follower: minimum %.3f m/s (undershoot %.3f below the lead's low speed), maximum "
                "%.3f m/s (overshoot %.3f above cruise)\n",
                setting.name.c_str(), last.minimum_speed_mps, undershoot, last.maximum_speed_mps, overshoot);
  }
  writePlatoonCsv(csv_path, runs);
  return summary;
}

json bodeFigure(const Options& options, const std::string& csv_path, double h)
{
  const auto settings = resolveSettings(options, {"min", "max"});
  const auto frequencies = acc::logSpacedFrequencies(options.positive("min-frequency", 1e-3),
                                                     options.positive("max-frequency", 10.0),
                                                     options.count("points", 400, 2));
  CsvWriter csv(csv_path, "setting,frequency_rad_s,gain_db,euler_gain_db");
  json summary = {{"figure", "bode"}, {"time_step_s", h}};
  std::printf("Bode magnitude of the speed-to-speed transfer function (paper Fig. 6)\n");
  for (const auto& setting : settings)
  {
    for (const acc::BodeSample& s : acc::bodeMagnitude(setting.parameters, frequencies, h))
    {
      csv.row() << setting.name << ',' << s.frequency_rad_s << ',' << s.gain_db << ',' << s.euler_gain_db << '\n';
    }
    const json p = parametersJson(setting);
    summary["settings"].push_back({{"parameters", p}});
    std::printf("  %-14s amplified below %.4f rad/s, peak %.3f dB at %.4f rad/s\n", setting.name.c_str(),
                p["amplified_band_upper_rad_s"].get<double>(), p["peak_gain_db"].get<double>(),
                p["peak_frequency_rad_s"].get<double>());
  }
  csv.close();
  return summary;
}

json sinusoidFigure(const Options& options, const std::string& csv_path, double h)
{
  const auto settings = resolveSettings(options, {"min", "max"});
  const std::size_t vehicles = options.count("vehicles", 10, 1);
  const double w = options.positive("frequency", 0.204);
  const double duration = options.positive("duration", 620.0);
  const double fit_s = options.positive("fit-periods", 5.0) * 2.0 * M_PI / w;
  if (fit_s >= duration - options.number("lead-in", 20.0))
  {
    throw UsageError("--fit-periods covers more than the oscillating part of --duration");
  }
  const auto lead = acc::sinusoidLeadProfile(options.positive("speed", 20.0), options.positive("amplitude", 1.0), w,
                                             options.number("lead-in", 20.0), duration, h);
  const std::size_t fit_from = lead.size() - static_cast<std::size_t>(std::round(fit_s / h));
  std::vector<std::pair<std::string, acc::PlatoonTrajectory>> runs;
  json summary = {{"figure", "sinusoid"}, {"vehicles", vehicles}, {"frequency_rad_s", w},
                  {"fit_from_s", static_cast<double>(fit_from) * h}};
  std::printf("sinusoidal lead at %.4f rad/s, %zu followers, amplitudes fitted over the last %.0f s (paper Fig. 7)\n",
              w, vehicles, fit_s);
  for (const auto& setting : settings)
  {
    runs.emplace_back(setting.name, acc::simulatePlatoon(setting.parameters, lead, h, vehicles));
    const auto r = acc::measureSinusoidResponse(runs.back().second, setting.parameters, w, fit_from);
    summary["settings"].push_back({{"parameters", parametersJson(setting)},
                                   {"amplitude_mps", r.amplitude_mps},
                                   {"last_to_first_follower", r.last_to_first_follower},
                                   {"last_follower_to_lead", r.last_follower_to_lead},
                                   {"model_gain", r.model_gain},
                                   {"model_gain_db", 20.0 * std::log10(r.model_gain)},
                                   {"euler_gain", r.euler_gain},
                                   {"model_gain_to_the_n", r.model_gain_over_platoon},
                                   {"euler_gain_to_the_n", r.euler_gain_over_platoon}});
    std::printf("  %-14s |Gamma| = %.4f (%+.3f dB); follower %zu / lead = %.4f (|Gamma|^%zu = %.4f, Euler %.4f); "
                "follower %zu / follower 1 = %.4f\n",
                setting.name.c_str(), r.model_gain, 20.0 * std::log10(r.model_gain), vehicles, r.last_follower_to_lead,
                vehicles, r.model_gain_over_platoon, r.euler_gain_over_platoon, vehicles, r.last_to_first_follower);
  }
  writePlatoonCsv(csv_path, runs);
  return summary;
}

json leadProfileFigure(const Options& options, const std::string& csv_path, double h)
{
  const auto settings = resolveSettings(options, {"min", "max"});
  const std::string id = options.text("profile", "I");
  if (id.size() != 1 || !acc::isLeadProfileId(id[0]))
  {
    throw UsageError("--profile must be one of " + acc::leadProfileIds());
  }
  acc::LeadProfileSpec spec = acc::leadProfileSpec(id[0]);
  spec.ramp.acceleration_mps2 = options.positive("lead-accel", spec.ramp.acceleration_mps2);
  spec.ramp.deceleration_mps2 = options.positive("lead-decel", spec.ramp.deceleration_mps2);
  const std::size_t vehicles = options.count("vehicles", 60, 1);
  const std::size_t short_platoon = std::min(vehicles, options.count("short-platoon", 15, 1));
  const auto profile = acc::sampleLeadProfile(spec, h);
  const auto lead = acc::withFinalHold(profile, options.number("tail", 600.0), h);
  const std::string description = spec.description + "; " + acc::describeLeadRamp(spec.ramp);
  json summary = {{"figure", "lead-profile"}, {"profile", description}, {"vehicles", vehicles},
                  {"short_platoon", short_platoon}, {"profile_duration_s", static_cast<double>(profile.size() - 1) * h},
                  {"lead_accel_mps2", spec.ramp.acceleration_mps2}, {"lead_decel_mps2", spec.ramp.deceleration_mps2}};
  std::printf("lead profile %s\n  %zu followers (first %zu = the short platoon), record %.0f s (profile %.0f s + hold)\n",
              description.c_str(), vehicles, short_platoon, static_cast<double>(lead.size() - 1) * h,
              static_cast<double>(profile.size() - 1) * h);
  std::vector<std::pair<std::string, acc::PlatoonTrajectory>> runs;
  for (const auto& setting : settings)
  {
    runs.emplace_back(setting.name, acc::simulatePlatoon(setting.parameters, lead, h, vehicles));
    const auto full = acc::measureDisturbanceResponse(runs.back().second);
    const auto shorter = acc::measureDisturbanceResponse(acc::firstFollowers(runs.back().second, short_platoon));
    summary["settings"].push_back(
        {{"parameters", parametersJson(setting)}, {"long", disturbanceJson(full)}, {"short", disturbanceJson(shorter)}});
    const auto& lead_d = full.per_vehicle.front();
    const auto& short_d = shorter.per_vehicle.back();
    const auto& long_d = full.per_vehicle.back();
    std::printf("  %-8s drop below cruise: lead %.2f, follower %zu %.2f, follower %zu %.2f m/s; peak-to-peak: "
                "%.2f, %.2f, %.2f m/s\n",
                setting.name.c_str(), lead_d.drop_below_reference_mps, short_platoon, short_d.drop_below_reference_mps,
                vehicles, long_d.drop_below_reference_mps, lead_d.peak_to_peak_mps, short_d.peak_to_peak_mps,
                long_d.peak_to_peak_mps);
    std::printf("           by drop: %s\n           by peak-to-peak: %s\n", onsetText(full.by_drop).c_str(),
                onsetText(full.by_peak_to_peak).c_str());
    if (full.first_negative_speed_vehicle)
    {
      std::printf("           speeds go negative from follower %zu on: the linear model no longer describes a car\n",
                  *full.first_negative_speed_vehicle);
    }
    if (!full.last_follower_settled)
    {
      std::fprintf(stderr, "warning: %s: the last follower has not settled by the end; lengthen --tail\n",
                   setting.name.c_str());
    }
  }
  writePlatoonCsv(csv_path, runs);
  return summary;
}

/// Every run of every --run file (a file may give several pieces: rejected rows and ACC-off rows
/// split a run). The reader lists each rejected row on stderr.
std::vector<acc::CarFollowingRun> readRunsOrThrow(const Options& options)
{
  std::vector<acc::CarFollowingRun> runs;
  for (const std::string& path : options.texts("run"))
  {
    try
    {
      for (acc::CarFollowingRun& run : acc::readRuns(path))
      {
        runs.push_back(std::move(run));
      }
    }
    catch (const acc::RunReadError& error)
    {
      throw UsageError(error.what());
    }
  }
  if (runs.empty())
  {
    throw UsageError("this figure needs --run RUN.csv");
  }
  return runs;
}

std::vector<acc::AccParameters> parametersOf(const std::vector<acc::NamedSetting>& settings)
{
  std::vector<acc::AccParameters> parameters;
  for (const auto& setting : settings)
  {
    parameters.push_back(setting.parameters);
  }
  return parameters;
}

/// The line's JSON and its printed line (indent and wording as given), or why there is none.
void reportLine(const acc::EquilibriumRegression& regression, json& entry, const char* indent, const char* label)
{
  if (!regression.line)
  {
    std::printf("%sno line fitted: %s\n", indent, regression.no_line_reason.c_str());
    return;
  }
  const acc::GapSpeedLine& line = *regression.line;
  entry["fit"] = {{"eta_m", line.intercept_m}, {"tau_e_s", line.slope_s}, {"rms_residual_m", line.rms_residual_m}};
  std::printf("%s%s: gap = %.3f m + %.4f s * v (rms %.3f m)\n", indent, label, line.intercept_m, line.slope_s,
              line.rms_residual_m);
}

json pooledEquilibrium(const std::vector<acc::CarFollowingRun>& runs, const std::vector<acc::NamedSetting>& settings,
                       double max_dv, double max_accel)
{
  const auto pooled = acc::regressPooledEquilibrium(runs, parametersOf(settings), max_dv, max_accel);
  json entry = {{"steady_samples", pooled.steady.size()}};
  std::printf("  all runs pooled: %zu steady samples\n", pooled.steady.size());
  reportLine(pooled, entry, "    ", "least-squares line");
  for (std::size_t i = 0; i < settings.size(); ++i)
  {
    entry["rms_from_line_m"][settings[i].name] = pooled.rms_from_line_m[i];
    std::printf("    %-14s rms distance of steady samples from eta + tau_e v: %.3f m\n", settings[i].name.c_str(),
                pooled.rms_from_line_m[i]);
  }
  return entry;
}

json equilibriumFigure(const Options& options, const std::string& csv_path)
{
  const auto runs = readRunsOrThrow(options);
  const auto settings = resolveSettings(options, {"min", "max"});
  const double max_dv = options.positive("max-relative-speed", 0.5);
  const double max_accel = options.positive("max-acceleration", 0.1);
  CsvWriter csv(csv_path, "run,time_s,follower_speed_mps,space_gap_m,steady");
  json summary = {{"figure", "equilibrium"}, {"max_relative_speed_mps", max_dv}, {"max_acceleration_mps2", max_accel}};
  std::printf("space gap against speed (paper Fig. 5); steady: |dv| <= %g m/s and |a| <= %g m/s^2\n", max_dv, max_accel);
  for (const auto& run : runs)
  {
    const auto regression = acc::regressEquilibrium(run, parametersOf(settings), max_dv, max_accel);
    std::vector<bool> is_steady(run.size(), false);
    for (std::size_t k : regression.steady)
    {
      is_steady[k] = true;
    }
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      csv.row() << run.name << ',' << run.time_s[k] << ',' << run.follower_speed_mps[k] << ',' << run.space_gap_m[k]
                << ',' << (is_steady[k] ? 1 : 0) << '\n';
    }
    const auto [slowest, fastest] = std::minmax_element(run.follower_speed_mps.begin(), run.follower_speed_mps.end());
    json entry = {{"run", run.name}, {"samples", run.size()}, {"steady_samples", regression.steady.size()},
                  {"speed_range_mps", {*slowest, *fastest}}};
    std::printf("  %s: %zu samples, %zu steady, speeds %.1f to %.1f m/s\n", run.name.c_str(), run.size(),
                regression.steady.size(), *slowest, *fastest);
    reportLine(regression, entry, "    ", "least-squares line through steady samples");
    for (std::size_t i = 0; i < settings.size(); ++i)
    {
      entry["rms_from_line_m"][settings[i].name] = regression.rms_from_line_m[i];
      std::printf("    %-14s eta + tau_e v = %.3f + %.4f v: rms distance of steady samples %.3f m\n",
                  settings[i].name.c_str(), settings[i].parameters.eta_m, settings[i].parameters.tau_e_s,
                  regression.rms_from_line_m[i]);
    }
    summary["runs"].push_back(entry);
  }
  summary["pooled"] = pooledEquilibrium(runs, settings, max_dv, max_accel);
  for (const auto& setting : settings)
  {
    summary["settings"].push_back({{"parameters", parametersJson(setting)}});
  }
  csv.close();
  return summary;
}

json timeseriesFigure(const Options& options, const std::string& csv_path)
{
  const auto runs = readRunsOrThrow(options);
  if (options.texts("run").size() != 1)
  {
    throw UsageError("timeseries takes one --run");
  }
  // A file split into pieces (rejected or ACC-off rows): plot the longest piece, and say so.
  const auto longest = std::max_element(runs.begin(), runs.end(), [](const auto& a, const auto& b) {
    return a.durationS() < b.durationS();
  });
  if (runs.size() > 1)
  {
    std::fprintf(stderr, "note: the run file gave %zu pieces; using the longest, %s (%.1f s)\n", runs.size(),
                 longest->name.c_str(), longest->durationS());
  }
  const acc::CarFollowingRun& run = *longest;
  const std::string problem = acc::describeRunProblem(run);
  if (!problem.empty())
  {
    throw UsageError(run.name + ": " + problem);
  }
  const auto settings = resolveSettings(options, {"min"});
  const double fraction = options.number("train-fraction", 0.5);
  CsvWriter csv(csv_path, "setting,time_s,leader_speed_mps,measured_speed_mps,simulated_speed_mps,"
                          "measured_gap_m,simulated_gap_m,part");
  json summary = {{"figure", "timeseries"}, {"run", run.name}, {"train_fraction", fraction}};
  std::printf("measured against simulated follower (paper Figs. 3 and 4), run %s\n", run.name.c_str());
  for (const auto& setting : settings)
  {
    const auto sim = acc::simulateFollower(setting.parameters, run);
    acc::TrainTestErrors e;
    try
    {
      e = acc::trainTestErrors(run, sim, fraction);
    }
    catch (const std::invalid_argument& error)
    {
      throw UsageError(error.what());
    }
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      csv.row() << setting.name << ',' << run.time_s[k] << ',' << run.leader_speed_mps[k] << ','
                << run.follower_speed_mps[k] << ',' << sim.speed_mps[k] << ',' << run.space_gap_m[k] << ','
                << sim.space_gap_m[k] << ',' << (k < e.split_index ? "train" : "test") << '\n';
    }
    summary["settings"].push_back({{"parameters", parametersJson(setting)},
                                   {"split_time_s", e.split_time_s},
                                   {"train_speed_rmse_mps", e.train_speed_rmse_mps},
                                   {"test_speed_rmse_mps", e.test_speed_rmse_mps},
                                   {"train_gap_rmse_m", e.train_gap_rmse_m},
                                   {"test_gap_rmse_m", e.test_gap_rmse_m},
                                   {"diverged", e.diverged}});
    std::printf("  %-14s speed RMSE train %.3f / test %.3f m/s, gap RMSE train %.3f / test %.3f m (split at %.1f s)%s\n",
                setting.name.c_str(), e.train_speed_rmse_mps, e.test_speed_rmse_mps, e.train_gap_rmse_m,
                e.test_gap_rmse_m, e.split_time_s, e.diverged ? "  DIVERGED" : "");
  }
  csv.close();
  return summary;
}

json runFigure(const std::string& figure, const Options& options, const std::string& csv_path)
{
  const double h = options.positive("time-step", 0.1);
  const std::map<std::string, std::function<json()>> figures{
      {"lambda2-map", [&] { return lambda2MapFigure(options, csv_path); }},
      {"step", [&] { return stepFigure(options, csv_path, h); }},
      {"bode", [&] { return bodeFigure(options, csv_path, h); }},
      {"sinusoid", [&] { return sinusoidFigure(options, csv_path, h); }},
      {"lead-profile", [&] { return leadProfileFigure(options, csv_path, h); }},
      {"equilibrium", [&] { return equilibriumFigure(options, csv_path); }},
      {"timeseries", [&] { return timeseriesFigure(options, csv_path); }}};
  const auto alias = kFigureNumbers.find(figure);
  const auto found = figures.find(alias == kFigureNumbers.end() ? figure : alias->second);
  if (found == figures.end())
  {
    throw UsageError("unknown figure '" + figure + "'");
  }
  return found->second();
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"The numbers and data behind the figures of Gunter et al.: one FIGURE per call, its data as CSV and "
               "a summary as JSON. Parameter sets (repeatable, in order; default min and max of Table II): "
               "--setting NAME, --params CALIBRATE.json, --k1 --k2 --tau-e [--eta] (one custom set)."};
  app.footer(kFigures);
  std::string figure, csv_path, summary_path;
  std::map<std::string, std::vector<std::string>> given;
  app.add_option("FIGURE", figure, "the figure")
      ->required()
      ->check(CLI::IsMember(acceptedFigures()));
  app.add_option("--csv", csv_path, "the figure's data")->required();
  app.add_option("--summary-json", summary_path, "the figure's key numbers");
  for (const std::string& name : kValueOptions)
  {
    // One value per occurrence (a repeated option adds one): never the FIGURE after it.
    app.add_option("--" + name, given[name], "see the figures below")->expected(1)->allow_extra_args(false)->take_all();
  }
  CLI11_PARSE(app, argc, argv);
  try
  {
    const Options options(given);
    json summary = runFigure(figure, options, csv_path);
    summary["csv"] = csv_path;
    if (!summary_path.empty())
    {
      std::ofstream out(summary_path);
      out << summary.dump(2) << '\n';
      if (!out)
      {
        throw std::runtime_error("cannot write " + summary_path);
      }
    }
  }
  catch (const UsageError& error)
  {
    std::cerr << "error: " << error.what() << "\nRun with --help for more information.\n";
    return 2;
  }
  catch (const std::exception& error)
  {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
