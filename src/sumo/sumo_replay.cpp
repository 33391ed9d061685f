#include "acc_identification/sumo/sumo_replay.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/io/run_program.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/json_number.h"
#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
/// The scenario folder: the one asked for, or a fresh temporary one removed when done.
class ScenarioFolder
{
public:
  explicit ScenarioFolder(const std::string& requested)
  {
    if (!requested.empty())
    {
      std::filesystem::create_directories(requested);
      path_ = std::filesystem::absolute(requested).string();
      return;
    }
    std::string pattern = (std::filesystem::temp_directory_path() / "acc_sumo_replay.XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr)
      throw std::runtime_error("cannot make a temporary folder for the SUMO scenario");
    path_ = pattern;
    temporary_ = true;
  }
  ~ScenarioFolder()
  {
    std::error_code ignored;
    if (temporary_)
      std::filesystem::remove_all(path_, ignored);
  }
  ScenarioFolder(const ScenarioFolder&) = delete;
  ScenarioFolder& operator=(const ScenarioFolder&) = delete;
  std::string file(const std::string& name) const { return (std::filesystem::path(path_) / name).string(); }

private:
  std::string path_;
  bool temporary_ = false;
};

std::string lastLine(const std::string& path)
{
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty())
      last = line;
  return last;
}

std::vector<std::vector<double>> readTrace(const std::string& path, std::size_t cars)
{
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line))
    throw std::runtime_error("SUMO's trace " + path + " is empty");
  const std::size_t columns = 2 * cars + 2;  // time, leader speed, then speed and gap per follower
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line))
  {
    std::vector<double> row;
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ','))
      row.push_back(std::strtod(field.c_str(), nullptr));
    if (row.size() != columns)
      throw std::runtime_error("SUMO's trace " + path + " has a row of " + std::to_string(row.size()) +
                               " fields, not " + std::to_string(columns));
    rows.push_back(row);
  }
  return rows;
}

double rmse(const std::vector<double>& a, const std::vector<double>& b)
{
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
  {
    if (std::isfinite(a[k]) && std::isfinite(b[k]))
    {
      sum += (a[k] - b[k]) * (a[k] - b[k]);
      ++count;
    }
  }
  return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : std::numeric_limits<double>::quiet_NaN();
}

/// The braking SUMO's safe speed may expect of the leader: what the recorded leader did (1 s
/// differences), at least 1 m/s^2.
double leaderDeceleration(const std::vector<double>& leader_speed_mps, double step_s)
{
  CarFollowingRun as_follower;
  for (std::size_t k = 0; k < leader_speed_mps.size(); ++k)
    as_follower.time_s.push_back(static_cast<double>(k) * step_s);
  as_follower.follower_speed_mps = leader_speed_mps;
  const double observed = observedAccelerationLimits({as_follower}).max_deceleration_mps2;
  return std::max(1.0, std::isfinite(observed) ? observed : 0.0);
}
}  // namespace

SumoRun runSumo(const std::vector<double>& leader_speed_mps, double step_s, const std::vector<SumoCarStart>& cars,
                const std::string& vtype_file, const SumoReplayOptions& options)
{
  if (options.driver_script.empty())
    throw std::runtime_error("no SUMO driver script given (sumo_traci_replay.py)");
  const ScenarioFolder folder(options.work_dir);
  nlohmann::json job{{"sumo", options.sumo},
                     {"step_length_s", step_s},
                     {"vtype_file", std::filesystem::absolute(vtype_file).string()},
                     {"work_dir", folder.file("")},
                     {"leader",
                      {{"length_m", options.leader_length_m},
                       {"decel_mps2", leaderDeceleration(leader_speed_mps, step_s)},
                       {"speeds_mps", leader_speed_mps}}},
                     {"output", folder.file("trace.csv")}};
  job["followers"] = nlohmann::json::array();
  for (const SumoCarStart& car : cars)
    job["followers"].push_back({{"vtype", car.vtype_id}, {"gap_m", car.gap_m}, {"speed_mps", car.speed_mps}});
  std::ofstream(folder.file("job.json")) << job.dump() << "\n";
  const std::string log = folder.file("driver.log");
  const int status = runProgram({options.python, options.driver_script, folder.file("job.json")}, log);
  if (status != 0)
  {
    const std::string reason = lastLine(log);
    throw std::runtime_error("SUMO replay failed" + (reason.empty() ? std::string(" (") + options.python +
                                                                          " could not run the driver)"
                                                                    : ": " + reason));
  }
  const std::vector<std::vector<double>> rows = readTrace(folder.file("trace.csv"), cars.size());
  if (rows.size() != leader_speed_mps.size())
    throw std::runtime_error("SUMO returned " + std::to_string(rows.size()) + " steps for " +
                             std::to_string(leader_speed_mps.size()) + " samples");
  SumoRun result;
  result.speed_mps.assign(cars.size() + 1, {});
  result.gap_m.assign(cars.size() + 1, {});
  for (const std::vector<double>& row : rows)
  {
    result.speed_mps[0].push_back(row[1]);
    for (std::size_t car = 1; car <= cars.size(); ++car)
    {
      result.speed_mps[car].push_back(row[2 * car]);
      result.gap_m[car].push_back(row[2 * car + 1]);
    }
  }
  return result;
}

namespace
{
/// The run's mean step [s] (its span over its steps): the one step a uniform run has.
double meanStepS(const CarFollowingRun& run)
{
  return (run.time_s.back() - run.time_s.front()) / static_cast<double>(run.size() - 1);
}
}  // namespace

std::string nonUniformStepReason(const CarFollowingRun& run)
{
  if (run.size() < 2)
    return "run '" + run.name + "' has fewer than two samples";
  const double step_s = meanStepS(run);
  for (std::size_t k = 1; k < run.size(); ++k)
  {
    const double h = run.time_s[k] - run.time_s[k - 1];
    if (std::abs(h - step_s) > 0.01 * step_s)
      return "run '" + run.name + "' is not sampled uniformly (a step of " + std::to_string(h) + " s at " +
             std::to_string(run.time_s[k - 1]) + " s against " + std::to_string(step_s) +
             " s): SUMO steps uniformly; a --max-gap below that step splits the run there, or resample it";
  }
  return "";
}

double uniformStepS(const CarFollowingRun& run)
{
  const std::string reason = nonUniformStepReason(run);
  if (!reason.empty())
    throw std::runtime_error(reason);
  return meanStepS(run);
}

namespace
{
/// Whether SUMO's gap-control gains are the model's k1 and k2 in every mode (asymmetric models:
/// collision avoidance's space gain k1 r_s), and the model has nothing SUMO lacks. eta and tau_e
/// count as the same within SUMO's shortest vehicle length and headway (below them they cannot be
/// exported exactly: a desired gap at most 0.1 m + 1 ms of travel longer).
bool gainsAreTheModels(const SumoAccVType& vtype, const PackageModel& model)
{
  const EffectSettings settings = model.settings();
  const SumoAccGains& g = vtype.gains;
  const double k1 = model.parameters.k1_per_s2, k2 = model.parameters.k2_per_s;
  const auto same = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); };
  bool same_effects = settings.closing_gain_ratio == 1.0;
  for (EffectKind kind : model.effects)
    same_effects = same_effects && (kind == EffectKind::acceleration_limits || kind == EffectKind::asymmetric_response);
  return same_effects && same(g.gap_closing_gain_space_per_s2, k1) && same(g.gap_control_gain_space_per_s2, k1) &&
         same(g.gap_closing_gain_speed_per_s, k2) && same(g.gap_control_gain_speed_per_s, k2) &&
         same(g.collision_avoidance_gain_speed_per_s, k2) &&
         same(g.collision_avoidance_gain_space_per_s2, k1 * settings.short_gap_gain_ratio) &&
         std::abs(vtype.tau_s - model.parameters.tau_e_s) <= kShortestSumoTauS &&
         std::abs(vtype.min_gap_m + vtype.length_m - model.parameters.eta_m) <= kShortestSumoLengthM + 1e-9;
}

/// Classifies SUMO's own steps with the law at SUMO's state.
SumoStepCounts countSteps(const SumoAccVType& vtype, bool same_gains, const std::vector<double>& leader_mps,
                          const std::vector<double>& speed_mps, const std::vector<double>& gap_m, double step_s,
                          const SumoReplayOptions& options)
{
  SumoStepCounts counts;
  SumoAccMode mode = SumoAccMode::speed_control;
  const std::size_t every = sumoActionEvery(vtype, step_s);
  double held_acceleration_mps2 = 0.0;
  for (std::size_t k = 0; k + 1 < speed_mps.size(); ++k)
  {
    // Between action steps SUMO holds the acceleration it decided at SUMO's own last action step.
    const bool acting = k % every == 0;
    const SumoAccStep step =
        acting ? sumoAccStep(vtype, gap_m[k], speed_mps[k], leader_mps[k], mode, step_s, options.lane_speed_limit_mps)
               : heldStep(speed_mps[k], held_acceleration_mps2, mode, step_s);
    if (acting)
      held_acceleration_mps2 = (speed_mps[k + 1] - speed_mps[k]) / step_s;
    counts.held += !acting;
    mode = step.mode;
    ++counts.steps;
    counts.speed_control += step.mode == SumoAccMode::speed_control;
    counts.gap_control += step.mode == SumoAccMode::gap_control;
    counts.gap_closing += step.mode == SumoAccMode::gap_closing;
    counts.collision_avoidance += step.mode == SumoAccMode::collision_avoidance;
    const bool slow = speed_mps[k] <= 15.0 && sumoAccGapMargin(speed_mps[k]) > 0.0;
    counts.below_15_mps += slow;
    counts.speed_bound_active += step.speed_bound_active;
    const bool departed = std::abs(speed_mps[k + 1] - step.next_speed_mps) > options.departure_tolerance_mps;
    counts.safe_speed_override += departed;
    counts.law_coincides +=
        same_gains && !slow && !step.speed_bound_active && !departed && step.mode != SumoAccMode::speed_control;
  }
  return counts;
}

std::string share(std::size_t part, std::size_t whole)
{
  std::ostringstream out;
  out.precision(3);
  out << (whole > 0 ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0) << " %";
  return out.str();
}

std::vector<std::string> explain(const SumoPairReplay& r, bool same_gains)
{
  std::vector<std::string> lines;
  const SumoStepCounts& c = r.counts;
  if (std::isfinite(r.model_diverged_at_s))
    lines.push_back("the package's model runs away at " + significant(r.model_diverged_at_s) +
                    " s (its speed or gap beyond any road vehicle's): every error against it is over the samples "
                    "before, and no comparison after");
  if (c.law_coincides == c.steps)
    lines.push_back("SUMO's law and the model coincide at every step: what differs is the position update (SUMO "
                    "moves by the new speed, the package's Euler step by the old one)");
  if (!same_gains && r.model_from_vtype_params)
    lines.push_back("SUMO's law lacks part of the model the vType was exported from (an effect SUMO's ACC cannot "
                    "carry; the file's notes name it): that part is the difference at every step");
  else if (!same_gains)
    lines.push_back("the vType's gap-control modes have different gains (a vType made elsewhere): the model "
                    "compared is the nearest one, with SUMO's gap-closing gains");
  if (c.below_15_mps > 0)
    lines.push_back(share(c.below_15_mps, c.steps) +
                    " of steps at or below 15 m/s, where SUMO 1.15's desired gap adds the margin d0 (up to 2 m)");
  if (c.speed_control > 0)
    lines.push_back(share(c.speed_control, c.steps) + " of steps in speed control (gap beyond 120 m)");
  if (c.speed_bound_active > 0)
    lines.push_back(share(c.speed_bound_active, c.steps) +
                    " of steps cut by accel, emergencyDecel or the desired speed (the data's limits)");
  if (c.safe_speed_override > 0)
    lines.push_back(share(c.safe_speed_override, c.steps) +
                    " of steps overridden by SUMO's safe speed (collisionAvoidanceOverride)");
  if (c.held > 0)
    lines.push_back(share(c.held, c.steps) +
                    " of steps between SUMO's action steps, where it holds its last decision (actionStepLength: "
                    "the export's stand-in for a reaction delay)");
  return lines;
}
}  // namespace

SumoPairReplay replayPairInSumo(const CarFollowingRun& run, const SumoAccVType& vtype, const std::string& vtype_file,
                                const SumoReplayOptions& options)
{
  SumoPairReplay r;
  r.run = run.name;
  r.vtype_id = vtype.id;
  r.samples = run.size();
  r.step_s = uniformStepS(run);
  r.model = packageModelOf(vtype);
  r.model_from_vtype_params = vtype.has_source_model;
  const SumoRun sumo = runSumo(run.leader_speed_mps, r.step_s,
                               {{vtype.id, run.space_gap_m.front(), run.follower_speed_mps.front()}}, vtype_file, options);
  // A model that diverges is scored up to its divergence only (rmse skips NaN), and says so.
  const SimulatedFollower simulated = simulateFollower(r.model.parameters, r.model.settings(), run);
  if (simulated.diverged)
    r.model_diverged_at_s = run.time_s[std::min(simulated.diverged_at_index, run.size() - 1)];
  const SimulatedFollower model = scorable(simulated);
  const SumoAccTrace replica = simulateSumoAcc(vtype, run.leader_speed_mps, r.step_s, run.space_gap_m.front(),
                                               run.follower_speed_mps.front(), options.lane_speed_limit_mps);
  r.rmse_speed_sumo_vs_model_mps = rmse(sumo.speed_mps[1], model.speed_mps);
  r.rmse_speed_sumo_vs_measured_mps = rmse(sumo.speed_mps[1], run.follower_speed_mps);
  r.rmse_speed_model_vs_measured_mps = rmse(model.speed_mps, run.follower_speed_mps);
  r.rmse_gap_sumo_vs_model_m = rmse(sumo.gap_m[1], model.space_gap_m);
  r.rmse_gap_sumo_vs_measured_m = rmse(sumo.gap_m[1], run.space_gap_m);
  r.rmse_gap_model_vs_measured_m = rmse(model.space_gap_m, run.space_gap_m);
  r.rmse_speed_sumo_vs_replica_mps = rmse(sumo.speed_mps[1], replica.speed_mps);
  const bool same_gains = gainsAreTheModels(vtype, r.model);
  r.counts = countSteps(vtype, same_gains, run.leader_speed_mps, sumo.speed_mps[1], sumo.gap_m[1], r.step_s, options);
  r.explanation = explain(r, same_gains);
  return r;
}

namespace
{
/// The package's chain: each car driven by the simulated car ahead, from its start.
std::vector<std::vector<double>> simulateChain(const SumoPlatoonInput& input, const std::vector<PackageModel>& models)
{
  std::vector<std::vector<double>> chain;
  std::vector<double> ahead_mps = input.leader_speed_mps;
  const std::size_t n = input.time_s.size();
  for (std::size_t i = 0; i < models.size(); ++i)
  {
    CarFollowingRun link{input.name, input.time_s, std::vector<double>(n, input.starts[i].gap_m),
                         std::vector<double>(n, input.starts[i].speed_mps), ahead_mps};
    chain.push_back(scorable(simulateFollower(models[i].parameters, models[i].settings(), link)).speed_mps);
    ahead_mps = chain.back();
  }
  return chain;
}

/// The same chain with SUMO's law (sumo_acc_simulation.h).
std::vector<std::vector<double>> simulateSumoChain(const SumoPlatoonInput& input, double step_s,
                                                   const SumoReplayOptions& options)
{
  std::vector<std::vector<double>> chain;
  std::vector<double> ahead_mps = input.leader_speed_mps;
  for (std::size_t i = 0; i < input.vtypes.size(); ++i)
  {
    chain.push_back(simulateSumoAcc(input.vtypes[i], ahead_mps, step_s, input.starts[i].gap_m,
                                    input.starts[i].speed_mps, options.lane_speed_limit_mps)
                        .speed_mps);
    ahead_mps = chain.back();
  }
  return chain;
}

double measuredDip(const SumoPlatoonInput& input, std::size_t car, const Perturbation& perturbation)
{
  if (car >= input.measured_speed_mps.size() || input.measured_speed_mps[car].empty())
    return std::numeric_limits<double>::quiet_NaN();
  return dipDepthMps(input.time_s, input.measured_speed_mps[car], perturbation);
}
}  // namespace

SumoPlatoonInput equilibriumPlatoon(const CarFollowingRun& run, const std::vector<SumoAccVType>& vtypes)
{
  SumoPlatoonInput input{run.name, run.time_s, run.leader_speed_mps, vtypes, {}, {}};
  const double u0 = run.leader_speed_mps.front();
  for (const SumoAccVType& vtype : vtypes)
  {
    const AccParameters p = packageModelOf(vtype).parameters;
    input.starts.push_back({vtype.id, p.eta_m + p.tau_e_s * u0, u0});
  }
  return input;
}

SumoPlatoonReplay replayPlatoonInSumo(const SumoPlatoonInput& input, const std::string& vtype_file,
                                      const SumoReplayOptions& options)
{
  SumoPlatoonReplay r;
  r.run = input.name;
  r.samples = input.time_s.size();
  r.step_s = uniformStepS({input.name, input.time_s, input.leader_speed_mps, input.leader_speed_mps,
                           input.leader_speed_mps});
  std::vector<PackageModel> models;
  for (const SumoAccVType& vtype : input.vtypes)
  {
    r.vtype_ids.push_back(vtype.id);
    models.push_back(packageModelOf(vtype));
  }
  const SumoRun sumo = runSumo(input.leader_speed_mps, r.step_s, input.starts, vtype_file, options);
  const std::vector<std::vector<double>> chain = simulateChain(input, models);
  const std::vector<std::vector<double>> replica = simulateSumoChain(input, r.step_s, options);
  for (std::size_t i = 0; i < input.vtypes.size(); ++i)
  {
    r.rmse_speed_sumo_vs_model_mps.push_back(rmse(sumo.speed_mps[i + 1], chain[i]));
    r.rmse_speed_sumo_vs_replica_mps.push_back(rmse(sumo.speed_mps[i + 1], replica[i]));
    // SUMO's steps classified at SUMO's own states, driven by SUMO's car ahead.
    r.steps.push_back(countSteps(input.vtypes[i], gainsAreTheModels(input.vtypes[i], models[i]), sumo.speed_mps[i],
                                 sumo.speed_mps[i + 1], sumo.gap_m[i + 1], r.step_s, options));
  }
  std::vector<Perturbation> perturbations = findPerturbations(input.time_s, input.leader_speed_mps);
  std::vector<MeasuredSpeed> measured;
  for (std::size_t i = 0; i < input.measured_speed_mps.size(); ++i)
    if (!input.measured_speed_mps[i].empty())
      measured.push_back({input.vtypes.size() > i ? input.vtypes[i].id : "car " + std::to_string(i + 2),
                          &input.measured_speed_mps[i], static_cast<int>(i) + 2});
  judgeCutWindows(perturbations, input.time_s, measured);
  for (const Perturbation& perturbation : perturbations)
  {
    SumoPlatoonPerturbation entry;
    entry.onset_s = perturbation.onset_s;
    entry.leader_dip_mps = dipDepthMps(input.time_s, input.leader_speed_mps, perturbation);
    entry.not_measured = perturbation.incomplete.empty() ? perturbation.cut_note : perturbation.incomplete;
    for (std::size_t i = 0; i < input.vtypes.size(); ++i)
    {
      if (perturbation.cutOffAt(static_cast<int>(i) + 2))
      {
        entry.positions.push_back({input.vtypes[i].id, std::nan(""), std::nan(""), std::nan(""), std::nan("")});
        continue;
      }
      entry.positions.push_back({input.vtypes[i].id, dipDepthMps(input.time_s, sumo.speed_mps[i + 1], perturbation),
                                 dipDepthMps(input.time_s, chain[i], perturbation),
                                 dipDepthMps(input.time_s, replica[i], perturbation),
                                 measuredDip(input, i, perturbation)});
    }
    r.perturbations.push_back(entry);
  }
  return r;
}

namespace
{
nlohmann::json countsJson(const SumoStepCounts& c)
{
  return {{"total", c.steps},
          {"speed_control", c.speed_control},
          {"gap_control", c.gap_control},
          {"gap_closing", c.gap_closing},
          {"collision_avoidance", c.collision_avoidance},
          {"at_or_below_15_mps", c.below_15_mps},
          {"speed_bound_active", c.speed_bound_active},
          {"safe_speed_override", c.safe_speed_override},
          {"held_between_action_steps", c.held},
          {"law_coincides", c.law_coincides}};
}

nlohmann::json modelJson(const PackageModel& model, bool from_params)
{
  return {{"source", from_params ? "the vType's acc_identification params (the model it was exported from)"
                                 : "the model SUMO's law equals above 15 m/s (the vType carries no source model)"},
          {"k1_per_s2", model.parameters.k1_per_s2},
          {"k2_per_s", model.parameters.k2_per_s},
          {"tau_e_s", model.parameters.tau_e_s},
          {"eta_m", model.parameters.eta_m},
          {"effects", effectNames(model.effects)},
          {"effect_values", model.effect_values}};
}
}  // namespace

nlohmann::json toJson(const SumoPairReplay& r)
{
  return {{"run", r.run},
          {"vtype", r.vtype_id},
          {"samples", r.samples},
          {"step_s", r.step_s},
          {"rmse_speed_sumo_vs_model_mps", jsonNumber(r.rmse_speed_sumo_vs_model_mps)},
          {"rmse_speed_sumo_vs_measured_mps", jsonNumber(r.rmse_speed_sumo_vs_measured_mps)},
          {"rmse_speed_model_vs_measured_mps", jsonNumber(r.rmse_speed_model_vs_measured_mps)},
          {"rmse_gap_sumo_vs_model_m", jsonNumber(r.rmse_gap_sumo_vs_model_m)},
          {"rmse_gap_sumo_vs_measured_m", jsonNumber(r.rmse_gap_sumo_vs_measured_m)},
          {"rmse_gap_model_vs_measured_m", jsonNumber(r.rmse_gap_model_vs_measured_m)},
          {"rmse_speed_sumo_vs_sumo_law_replica_mps", jsonNumber(r.rmse_speed_sumo_vs_replica_mps)},
          {"steps", countsJson(r.counts)},
          {"law_coincides_share", r.counts.steps > 0 ? static_cast<double>(r.counts.law_coincides) /
                                                           static_cast<double>(r.counts.steps)
                                                     : 0.0},
          {"model", modelJson(r.model, r.model_from_vtype_params)},
          {"model_diverged_at_s", jsonNumber(r.model_diverged_at_s)},
          {"explanation", r.explanation}};
}

nlohmann::json toJson(const SumoPlatoonReplay& r)
{
  nlohmann::json perturbations = nlohmann::json::array();
  for (const SumoPlatoonPerturbation& p : r.perturbations)
  {
    nlohmann::json positions = nlohmann::json::array();
    for (std::size_t i = 0; i < p.positions.size(); ++i)
      positions.push_back({{"position", i + 2},
                           {"vtype", p.positions[i].vtype_id},
                           {"sumo_dip_mps", jsonNumber(p.positions[i].sumo_dip_mps)},
                           {"model_dip_mps", jsonNumber(p.positions[i].model_dip_mps)},
                           {"sumo_law_replica_dip_mps", jsonNumber(p.positions[i].replica_dip_mps)},
                           {"measured_dip_mps", jsonNumber(p.positions[i].measured_dip_mps)}});
    perturbations.push_back(
        {{"onset_s", p.onset_s}, {"leader_dip_mps", jsonNumber(p.leader_dip_mps)}, {"not_measured", p.not_measured},
         {"positions", positions}});
  }
  nlohmann::json rmse = nlohmann::json::array(), rmse_replica = nlohmann::json::array(),
                 steps = nlohmann::json::array();
  for (const SumoStepCounts& counts : r.steps)
    steps.push_back(countsJson(counts));
  for (double value : r.rmse_speed_sumo_vs_model_mps)
    rmse.push_back(jsonNumber(value));
  for (double value : r.rmse_speed_sumo_vs_replica_mps)
    rmse_replica.push_back(jsonNumber(value));
  return {{"run", r.run},         {"samples", r.samples},
          {"step_s", r.step_s},   {"vtypes", r.vtype_ids},
          {"rmse_speed_sumo_vs_model_mps", rmse}, {"rmse_speed_sumo_vs_sumo_law_replica_mps", rmse_replica},
          {"steps", steps},
          {"perturbations", perturbations}};
}

void printReplay(const SumoPairReplay& r, std::ostream& out)
{
  out << r.run << " with vType " << r.vtype_id << " (" << r.samples << " samples, step " << r.step_s << " s)\n"
      << "  speed RMSE  SUMO vs model " << r.rmse_speed_sumo_vs_model_mps << " m/s, SUMO vs measured "
      << r.rmse_speed_sumo_vs_measured_mps << " m/s, model vs measured " << r.rmse_speed_model_vs_measured_mps
      << " m/s\n"
      << "  gap RMSE    SUMO vs model " << r.rmse_gap_sumo_vs_model_m << " m, SUMO vs measured "
      << r.rmse_gap_sumo_vs_measured_m << " m, model vs measured " << r.rmse_gap_model_vs_measured_m << " m\n"
      << "  SUMO vs the package's replica of SUMO's law: " << r.rmse_speed_sumo_vs_replica_mps << " m/s\n"
      << "  law and model coincide at " << share(r.counts.law_coincides, r.counts.steps) << " of steps\n";
  for (const std::string& line : r.explanation)
    out << "  - " << line << "\n";
}

namespace
{
bool hasMeasured(const SumoPlatoonPerturbation& p)
{
  return std::any_of(p.positions.begin(), p.positions.end(),
                     [](const SumoPlatoonDip& d) { return std::isfinite(d.measured_dip_mps); });
}
}  // namespace

void printReplay(const SumoPlatoonReplay& r, std::ostream& out)
{
  out << r.run << ": platoon of " << r.vtype_ids.size() << " in SUMO behind the run's leader\n";
  for (std::size_t i = 0; i < r.vtype_ids.size(); ++i)
  {
    out << "  position " << i + 2 << " (" << r.vtype_ids[i] << "): speed RMSE SUMO vs the package's chain "
        << r.rmse_speed_sumo_vs_model_mps[i] << " m/s, vs the replica of SUMO's law "
        << r.rmse_speed_sumo_vs_replica_mps[i] << " m/s";
    const SumoStepCounts& c = r.steps[i];
    if (c.below_15_mps > 0)
      out << "; at or below 15 m/s (margin d0) " << share(c.below_15_mps, c.steps);
    if (c.safe_speed_override > 0)
      out << "; SUMO's safe speed overrode the law in " << c.safe_speed_override << " steps";
    out << "\n";
  }
  for (const SumoPlatoonPerturbation& p : r.perturbations)
  {
    out << "  perturbation at " << p.onset_s << " s, leader dip " << p.leader_dip_mps
        << " m/s; dips by position, SUMO / package model" << (hasMeasured(p) ? " / measured" : "") << " [m/s]:";
    for (const SumoPlatoonDip& d : p.positions)
    {
      out << "  " << d.sumo_dip_mps << " / " << d.model_dip_mps;
      if (hasMeasured(p))
        out << " / " << d.measured_dip_mps;
    }
    out << "\n";
    if (!p.not_measured.empty())
      out << "    (" << p.not_measured << ")\n";
  }
  if (r.perturbations.empty())
    out << "  the leader has no perturbation (a drop of more than 1 m/s below its median)\n";
}

}  // namespace acc
