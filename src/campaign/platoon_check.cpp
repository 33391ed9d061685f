#include "acc_identification/campaign/platoon_check.h"

#include "acc_identification/evidence/perturbation_windows.h"
#include "acc_identification/model/number_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "acc_identification/diagnosis/augmented_stability.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/plain_text.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Dips below this are GNSS noise: no ratio is formed with them as the denominator.
constexpr double kMinDipForRatioMps = 0.1;

bool hasSpeed(const OpenAccVehicle* vehicle)
{
  return vehicle != nullptr && vehicle->has_speed && vehicle->speed_values > 0;
}

/// Why car `position` cannot be simulated, "" when it can.
std::string whyNotSimulated(const OpenAccFile& file, int position, const PlatoonCarModel& model)
{
  const std::string label = file.vehicleName(position) + " (" + std::to_string(position) + ")";
  const OpenAccVehicle* car = file.vehicle(position);
  if (car != nullptr && !car->copied_column.empty())
    return label + " has no speed data of its own (a copied column)";
  if (!hasSpeed(car))
    return label + " has no speed data";
  const OpenAccVehicle* ahead = file.vehicle(position - 1);
  if (ahead == nullptr || !ahead->has_gap_to_follower || ahead->gap_values == 0)
    return label + " has no gap data (IVS" + std::to_string(position - 1) + ")";
  if (!model.available)
    return label + " has no model: " + model.source;
  return "";
}

/// The first row in [first, end) where the car's start state and its input are all known.
std::size_t startRow(const OpenAccFile& file, int position, const std::vector<double>& input_mps, std::size_t first,
                     std::size_t end)
{
  const std::vector<double>& speed = file.vehicle(position)->speed_mps;
  const std::vector<double>& gap = file.vehicle(position - 1)->gap_to_follower_m;
  for (std::size_t r = first; r < end; ++r)
  {
    if (std::isfinite(input_mps[r]) && std::isfinite(speed[r]) && std::isfinite(gap[r]))
      return r;
  }
  return end;
}

/// ": its model is not locally stable (...)" when the model's own loop explains a runaway; else
/// that the runaway is large-signal, which a small-signal margin does not cover.
std::string whyDiverged(const PlatoonCarModel& model, const CarFollowingRun& run)
{
  // At the input's median speed, the operating point the diagnosis and the link evidence use too.
  const AugmentedStability loop =
      analyzeAugmentedStability(model.parameters, model.effects, model.settings, finiteMedian(run.leader_speed_mps));
  if (loop.locally_stable)
    return printfText(": its model is locally stable (phase margin %.1f deg at %.3f rad/s), so the runaway is "
                      "large-signal: what its nonlinear terms or its delay do to a large excursion",
                      loop.phase_margin_deg, loop.crossover_rad_s);
  return std::isfinite(loop.phase_margin_deg)
             ? printfText(": its model is not locally stable (phase margin %.1f deg at %.3f rad/s)",
                          loop.phase_margin_deg, loop.crossover_rad_s)
             : ": its model has no feedback";
}

double rmseAgainstMeasured(const std::vector<double>& predicted, const std::vector<double>& measured)
{
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t r = 0; r < predicted.size(); ++r)
  {
    if (std::isfinite(predicted[r]) && std::isfinite(measured[r]))
    {
      sum += (predicted[r] - measured[r]) * (predicted[r] - measured[r]);
      ++n;
    }
  }
  return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : kNaN;
}

/// Simulates one car from row `start` to `end`, driven by input_mps (which the real car at
/// driven_by drives); fills car.predicted_speed_mps.
void predictCar(const OpenAccFile& file, const std::vector<double>& input_mps, int driven_by, std::size_t start,
                std::size_t end, PlatoonCarPrediction& car)
{
  CarFollowingRun run;
  run.name = file.name + " " + car.name;
  run.time_s = sliceRows(file.time_s, start, end);
  run.leader_speed_mps = sliceRows(input_mps, start, end);
  // Only the first gap and speed are read by the simulation (its measured start).
  run.follower_speed_mps.assign(run.size(), file.vehicle(car.position)->speed_mps[start]);
  run.space_gap_m.assign(run.size(), file.vehicle(car.position - 1)->gap_to_follower_m[start]);
  const SimulatedFollower sim = simulateFollower(car.model.parameters, car.model.settings, run);
  const std::size_t valid = sim.diverged ? sim.diverged_at_index : run.size();
  car.predicted_speed_mps.assign(file.rows(), kNaN);
  std::copy(sim.speed_mps.begin(), sim.speed_mps.begin() + valid, car.predicted_speed_mps.begin() + start);
  car.start_row = start;
  car.stopped_at_row = sim.diverged ? start + valid : 0;
  car.driven_by_position = driven_by;
  car.predicted = true;
  // A runaway's growth before the divergence bound would swamp any RMSE: a diverged prediction
  // has none, and its note says why.
  car.rmse_speed_mps = sim.diverged ? kNaN : rmseAgainstMeasured(car.predicted_speed_mps, file.vehicle(car.position)->speed_mps);
  if (sim.diverged)
    car.note = "simulation diverged at t = " + printfText("%.1f s", run.time_s[valid]) + whyDiverged(car.model, run);
  car.breakdown = describeBreakdown(sim, run.time_s);
}


/// The measured speed of the car at `position` within the rows [first_row, end_row) (NaN
/// elsewhere, and all NaN without speed data): the input of the car behind it.
std::vector<double> measuredInput(const OpenAccFile& data, int position, std::size_t first_row, std::size_t end_row)
{
  std::vector<double> input(data.rows(), kNaN);
  const OpenAccVehicle* vehicle = data.vehicle(position);
  if (!hasSpeed(vehicle))
    return input;
  std::copy(vehicle->speed_mps.begin() + first_row, vehicle->speed_mps.begin() + end_row, input.begin() + first_row);
  return input;
}

/// The chain: each car driven by the prediction of the car ahead. Where a car cannot be predicted
/// (no data, no model, a diverged simulation), the chain restarts behind it from its measured speed,
/// as it starts behind the real first car: a hole in one car's record does not silence every car
/// behind it. Notes on where it stopped and restarted go to check.notes.
std::vector<PlatoonCarPrediction> predictChain(const CampaignFile& file, const std::vector<PlatoonCarModel>& models,
                                               PlatoonCheck& check)
{
  std::vector<PlatoonCarPrediction> cars;
  const OpenAccFile& data = file.contents;
  int driven_by = 1;  // the real car whose measured speed drives the chain
  std::vector<double> input = measuredInput(data, driven_by, check.first_row, check.end_row);
  bool running = true;  // the car ahead was predicted, or is the real car driving the chain
  for (int k = 2; k <= data.lastPosition(); ++k)
  {
    PlatoonCarPrediction car;
    car.position = k;
    car.name = data.vehicleName(k);
    car.model = k < static_cast<int>(models.size()) ? models[k] : PlatoonCarModel{false, {}, "none given"};
    car.predicted_speed_mps.assign(data.rows(), kNaN);
    std::string why = whyNotSimulated(data, k, car.model);
    if (why.empty() && std::none_of(input.begin(), input.end(), [](double v) { return std::isfinite(v); }))
      why = car.name + " (" + std::to_string(k) + "): the car ahead has neither a prediction nor speed data";
    const std::size_t start = why.empty() ? startRow(data, k, input, check.first_row, check.end_row) : 0;
    if (why.empty() && start + 2 > check.end_row)
      why = "no row with its gap, speed and input all known";
    if (!why.empty())
    {
      car.note = why;
      if (running)
        check.notes.push_back("chain stopped at position " + std::to_string(k) + ": " + why);
      running = false;
      driven_by = k;
      input = measuredInput(data, k, check.first_row, check.end_row);
      cars.push_back(car);
      continue;
    }
    if (driven_by != 1 && !running)
      check.notes.push_back("chain restarted at position " + std::to_string(k) + ": driven by the measured speed of " +
                            data.vehicleName(driven_by) + " (" + std::to_string(driven_by) + ")");
    predictCar(data, input, driven_by, start, check.end_row, car);
    if (!car.breakdown.empty())  // the real car neither collides nor reverses: its dips there are the model's
      check.notes.push_back(car.name + " (" + std::to_string(k) + ")'s chain prediction: " + car.breakdown +
                            ", which the real car does not do");
    running = car.note.empty();
    if (!running)
    {
      check.notes.push_back("chain stopped after position " + std::to_string(k) + ": " + car.note);
      driven_by = k;
    }
    if (!car.model.step_mismatch.empty())
      check.notes.push_back(car.name + " (" + std::to_string(k) + "): " + car.model.step_mismatch);
    if (car.model.source.find("first half") != std::string::npos)
      check.notes.push_back(car.name + " (" + std::to_string(k) + "): " + car.model.source);
    input = running ? car.predicted_speed_mps : measuredInput(data, k, check.first_row, check.end_row);
    cars.push_back(std::move(car));
  }
  return cars;
}

double ratio(double dip, double dip_ahead)
{
  if (!std::isfinite(dip) || !std::isfinite(dip_ahead) || dip_ahead < kMinDipForRatioMps)
    return kNaN;
  return dip / dip_ahead;
}

/// Amplification measured against prediction, and the dip error, position by position.
void findDisagreements(PerturbationCheck& check, std::size_t index, double max_relative_dip_error)
{
  for (const DipComparison& row : check.positions)
  {
    if (row.position < 2)
      continue;
    const double measured = row.measured_amplification, predicted = row.chain_amplification;
    if (std::isfinite(measured) && std::isfinite(predicted) && (predicted > 1.0) != (measured > 1.0))
    {
      check.disagreements.push_back({index, row.position, row.name,
                                     std::string(predicted > 1.0 ? "predicted amplification " : "predicted attenuation ") +
                                         printfText("%.2f", predicted) +
                                         (measured > 1.0 ? ", measured amplification " : ", measured attenuation ") +
                                         printfText("%.2f", measured)});
    }
    if (std::isfinite(row.measured.dip_mps) && std::isfinite(row.chain.dip_mps) &&
        row.measured.dip_mps >= kMinDipForRatioMps)
    {
      const double error = (row.chain.dip_mps - row.measured.dip_mps) / row.measured.dip_mps;
      if (std::abs(error) > max_relative_dip_error)
        check.disagreements.push_back({index, row.position, row.name, "dip error " + printfText("%+.0f %%", 100.0 * error)});
    }
  }
}

bool dataShowGrowth(const std::vector<DipComparison>& positions)
{
  const double first = positions.empty() ? kNaN : positions.front().measured.dip_mps;
  double last = kNaN;
  for (std::size_t k = 1; k < positions.size(); ++k)
  {
    if (std::isfinite(positions[k].measured.dip_mps))
      last = positions[k].measured.dip_mps;
  }
  return std::isfinite(first) && std::isfinite(last) && last > first;
}

/// "perturbation 2 (onset 1259.9 s): ", the opening of a note about one perturbation.
std::string perturbationLabel(const PerturbationCheck& perturbation, std::size_t index)
{
  return "perturbation " + std::to_string(index + 1) + " (onset " +
         printfText("%.1f s", perturbation.perturbation.onset_s) + "): ";
}

/// "TESLA_MODELX (3), AUDI_E_TRON (5)": the cars at these positions, for a note.
std::string carsAt(const OpenAccFile& data, const std::vector<int>& positions)
{
  std::vector<std::string> cars;
  for (int position : positions)
    cars.push_back(data.vehicleName(position) + " (" + std::to_string(position) + ")");
  return join(cars, ", ");
}

/// The positions whose model was fitted on a stretch of this run overlapping the perturbation's
/// window (PerturbationCheck::fitted_on_it), and a note naming them.
void markModelsFittedOnIt(const std::vector<PlatoonCarPrediction>& cars, const OpenAccFile& data,
                          const std::vector<double>& time_s, std::size_t index, const PlatoonCheckOptions& options,
                          PerturbationCheck& perturbation, std::vector<std::string>& notes)
{
  const std::optional<std::pair<double, double>> window = perturbationWindowS(time_s, perturbation.perturbation, options);
  if (!window)
    return;
  for (const PlatoonCarPrediction& car : cars)
  {
    const auto& stretches = car.model.fitted_on_this_run_s;
    if (std::any_of(stretches.begin(), stretches.end(), [&](const auto& stretch) {
          return stretch.first <= window->second && window->first <= stretch.second;
        }))
      perturbation.fitted_on_it.push_back(car.position);
  }
  if (!perturbation.fitted_on_it.empty())
    notes.push_back(perturbationLabel(perturbation, index) + "the models of " + carsAt(data, perturbation.fitted_on_it) +
                    " were fitted on this run (no other run of the car at its setting) over a stretch that holds "
                    "this dip: their predictions here, and the chains' behind them, are not out of sample");
}

/// The cars of one perturbation not compared because they were driven by hand, in one note.
void noteDrivenByHand(const OpenAccFile& data, const PerturbationCheck& perturbation, std::size_t index,
                      std::vector<std::string>& notes)
{
  if (perturbation.driven_by_hand.empty())
    return;
  notes.push_back(perturbationLabel(perturbation, index) + carsAt(data, perturbation.driven_by_hand) +
                  " not on ACC (Driver column) between the stretch's start and the window's end: " +
                  "their predictions, and the chains' behind them, are not compared");
}

PerturbationCheck comparePerturbation(const PlatoonCheck& check, const OpenAccFile& data,
                                      const std::vector<double>& time_s, const Perturbation& perturbation,
                                      std::size_t index, const PlatoonCheckOptions& options)
{
  PerturbationCheck result;
  result.perturbation = perturbation;
  // Every measure of one speed series, from one copy of the check's rows.
  auto measure = [&](const std::vector<double>& speed) {
    const std::vector<double> rows = sliceRows(speed, check.first_row, check.end_row);
    return DipMeasures{dipDepthMps(time_s, rows, perturbation, options.perturbation),
                       distanceLostM(time_s, rows, perturbation, options.perturbation),
                       dipShape(time_s, rows, perturbation, options.perturbation)};
  };
  auto predicted = [&](const std::vector<PlatoonCarPrediction>& cars, std::size_t i) {
    if (i >= cars.size() || !cars[i].predicted)
      return DipMeasures{};
    // A prediction that stopped inside the window would measure part of it (and a runaway's growth).
    if (cars[i].stopped_at_row > 0 && cars[i].stopped_at_row < check.first_row + perturbation.window_end)
      return DipMeasures{};
    return measure(cars[i].predicted_speed_mps);
  };
  auto drivenBy = [](const std::vector<PlatoonCarPrediction>& cars, std::size_t i) {
    return i < cars.size() && cars[i].predicted ? cars[i].driven_by_position : 0;
  };
  for (const PlatoonCarPrediction& car : check.cars)
  {
    if (!onAccThroughout(data, car.position, check.first_row, check.first_row + perturbation.window_end))
      result.driven_by_hand.push_back(car.position);
  }
  // A prediction passes through the cars from the real car driving it to its own position.
  auto throughHand = [&result](int driven_by, int position) {
    return std::any_of(result.driven_by_hand.begin(), result.driven_by_hand.end(),
                       [&](int hand) { return driven_by < hand && hand <= position; });
  };
  DipComparison lead;
  lead.position = 1;
  lead.name = data.vehicleName(1);
  lead.measured = lead.chain = measure(data.vehicle(1)->speed_mps);
  lead.chain_driven_by = 1;
  if (!check.cars_diagnosed.empty())
  {
    lead.chain_diagnosed = lead.measured;
    lead.chain_diagnosed_driven_by = 1;
  }
  result.positions.push_back(lead);
  for (std::size_t i = 0; i < check.cars.size(); ++i)
  {
    const PlatoonCarPrediction& car = check.cars[i];
    DipComparison row;
    row.position = car.position;
    row.name = car.name;
    if (hasSpeed(data.vehicle(car.position)))
      row.measured = measure(data.vehicle(car.position)->speed_mps);
    row.chain = predicted(check.cars, i);
    row.chain_diagnosed = predicted(check.cars_diagnosed, i);
    row.pair = predicted(check.pairs, i);
    row.pair_diagnosed = predicted(check.pairs_diagnosed, i);
    row.chain_driven_by = drivenBy(check.cars, i);
    row.chain_diagnosed_driven_by = drivenBy(check.cars_diagnosed, i);
    if (throughHand(row.chain_driven_by, row.position))
      row.chain = DipMeasures{};
    if (throughHand(row.chain_diagnosed_driven_by, row.position))
      row.chain_diagnosed = DipMeasures{};
    if (throughHand(row.position - 1, row.position))
      row.pair = row.pair_diagnosed = DipMeasures{};
    if (perturbation.cutOffAt(row.position))
      row.measured = row.chain = row.chain_diagnosed = row.pair = row.pair_diagnosed = DipMeasures{};
    const DipComparison& ahead = result.positions.back();
    // Behind the real car driving a chain, the car ahead's dip is its measured one (as the first car's).
    auto chainDipAhead = [&ahead](const DipMeasures& chain, int driven_by) {
      return driven_by == ahead.position ? ahead.measured.dip_mps : chain.dip_mps;
    };
    row.measured_amplification = ratio(row.measured.dip_mps, ahead.measured.dip_mps);
    row.chain_amplification = ratio(row.chain.dip_mps, chainDipAhead(ahead.chain, row.chain_driven_by));
    row.chain_amplification_diagnosed =
        ratio(row.chain_diagnosed.dip_mps, chainDipAhead(ahead.chain_diagnosed, row.chain_diagnosed_driven_by));
    result.positions.push_back(row);
  }
  result.data_show_growth = dataShowGrowth(result.positions);
  findDisagreements(result, index, options.max_relative_dip_error);
  return result;
}
}  // namespace

std::string describeStepMismatch(const std::vector<CarFollowingRun>& training, double run_step_s)
{
  // The training segments' median steps as printed, in numeric order (as strings, 10 came before 2).
  std::map<double, std::string> steps;
  bool mismatch = false;
  for (const CarFollowingRun& segment : training)
  {
    const double step_s = medianStepS({segment});
    if (!(step_s > 0.0) || !(run_step_s > 0.0))
      continue;
    const std::string printed = printfText("%.3g", step_s);
    steps.emplace(std::stod(printed), printed);
    mismatch = mismatch || std::abs(run_step_s / step_s - 1.0) > kStepMismatchShare;
  }
  if (!mismatch)
    return "";
  std::string listed;
  std::size_t written = 0;
  for (const auto& [value_s, printed] : steps)
    listed += (written++ == 0 ? "" : written == steps.size() ? " and " : ", ") + printed;
  return printfText("fitted on runs at %s s steps, this run is at %.3g s: the fit's parameters are those of the "
                    "model's Euler map at its data's step (the paper's calibration), so this prediction, stepped at "
                    "the run's, carries the difference (calibrate's euler_step_bias says how far the step moves a fit)",
                    listed.c_str(), run_step_s);
}

bool onAccThroughout(const OpenAccFile& file, int position, std::size_t from_row, std::size_t to_row)
{
  const OpenAccVehicle* car = file.vehicle(position);
  for (std::size_t row = from_row; car != nullptr && row < std::min(to_row, file.rows()); ++row)
  {
    if (!isOnAccAt(file, *car, row))
      return false;
  }
  return true;
}

std::string describeRowsLeftOut(const OpenAccFile& file, std::size_t first_row, std::size_t end_row)
{
  const std::size_t left_out = file.rows() - (end_row - first_row);
  return "only the first car's longest unbroken stretch is checked: lines " + std::to_string(file.line[first_row]) +
         "-" + std::to_string(file.line[end_row - 1]) + " (" + std::to_string(end_row - first_row) + " of " +
         std::to_string(file.rows()) + " rows); the " + std::to_string(left_out) + (left_out == 1 ? " row" : " rows") +
         " outside it (where its time or speed is missing, time does not increase, or a step is longer than "
         "the maximum) " + (left_out == 1 ? "is" : "are") + " not";
}

std::pair<std::size_t, std::size_t> longestLeadStretch(const OpenAccFile& file, double max_time_step_s)
{
  const OpenAccVehicle* lead = file.vehicle(1);
  std::pair<std::size_t, std::size_t> best{0, 0};
  if (lead == nullptr)
    return best;
  auto close = [&best](std::size_t first, std::size_t end) {
    if (end - first > best.second - best.first)
      best = {first, end};
  };
  bool open = false;
  std::size_t first = 0;
  for (std::size_t r = 0; r < file.rows(); ++r)
  {
    if (!(std::isfinite(file.time_s[r]) && std::isfinite(lead->speed_mps[r])))
    {
      if (open)
        close(first, r);
      open = false;
      continue;
    }
    const double step_s = open ? file.time_s[r] - file.time_s[r - 1] : 0.0;
    if (open && !(step_s > 0.0 && step_s <= max_time_step_s))
    {
      close(first, r);
      open = false;
    }
    if (!open)
    {
      first = r;
      open = true;
    }
  }
  if (open)
    close(first, file.rows());
  return best;
}

PlatoonCarPrediction predictPair(const OpenAccFile& file, int position, const PlatoonCarModel& model,
                                 std::size_t first_row, std::size_t end_row)
{
  PlatoonCarPrediction car;
  car.position = position;
  car.name = file.vehicleName(position);
  car.model = model;
  car.predicted_speed_mps.assign(file.rows(), kNaN);
  car.note = whyNotSimulated(file, position, model);
  const OpenAccVehicle* ahead = file.vehicle(position - 1);
  if (car.note.empty() && !hasSpeed(ahead))
    car.note = car.name + ": the car ahead has no speed data";
  if (!car.note.empty())
    return car;
  const std::vector<double> input = measuredInput(file, position - 1, first_row, end_row);
  const std::size_t start = startRow(file, position, input, first_row, end_row);
  if (start + 2 > end_row)
  {
    car.note = "no row with its gap, speed and input all known";
    return car;
  }
  // A hole in the leader's record makes the simulation non-finite there: it stops and says so.
  predictCar(file, input, position - 1, start, end_row, car);
  return car;
}

std::vector<Perturbation> leadPerturbations(const OpenAccFile& file, const PlatoonCheckOptions& options,
                                            std::size_t* first_row, std::size_t* end_row)
{
  std::tie(*first_row, *end_row) = longestLeadStretch(file, options.max_time_step_s);
  if (*end_row < *first_row + 2)
    return {};
  const std::vector<double> time_s = sliceRows(file.time_s, *first_row, *end_row);
  std::vector<Perturbation> found =
      findPerturbations(time_s, sliceRows(file.vehicle(1)->speed_mps, *first_row, *end_row), options.perturbation);
  // A window the data's end cuts is judged on the cars behind, in platoon order (judgeCutWindows).
  std::vector<std::vector<double>> speeds;
  speeds.reserve(static_cast<std::size_t>(std::max(0, file.lastPosition())));  // cars point into it
  std::vector<MeasuredSpeed> cars;
  for (int position = 2; position <= file.lastPosition(); ++position)
    if (const OpenAccVehicle* car = file.vehicle(position))
    {
      speeds.push_back(sliceRows(car->speed_mps, *first_row, *end_row));
      cars.push_back({file.vehicleName(position) + " (" + std::to_string(position) + ")", &speeds.back(), position});
    }
  judgeCutWindows(found, time_s, cars, options.perturbation);
  return found;
}

namespace
{
/// Everything of checkPlatoon but the perturbations: the chain and the pair-level predictions with
/// one chain's models, and their notes.
PlatoonCheck predictPlatoon(const CampaignFile& file, const PlatoonChainModels& chain, const PlatoonCheckOptions& options)
{
  PlatoonCheck check;
  check.run = file.name;
  check.setting = file.setting;
  check.car_settings = file.car_settings;
  const OpenAccFile& data = file.contents;
  std::tie(check.first_row, check.end_row) = longestLeadStretch(data, options.max_time_step_s);
  if (check.end_row < check.first_row + 2)
  {
    check.notes.push_back("the first car (" + data.vehicleName(1) + ") has no stretch of speed data: nothing predicted");
    return check;
  }
  check.cars = predictChain(file, chain.models, check);
  for (const PlatoonCarPrediction& car : check.cars)
    check.pairs.push_back(predictPair(data, car.position, car.model, check.first_row, check.end_row));
  if (!chain.diagnosed.empty())
  {
    PlatoonCheck diagnosed_notes;  // the same rows; its notes are filtered below
    diagnosed_notes.first_row = check.first_row;
    diagnosed_notes.end_row = check.end_row;
    check.cars_diagnosed = predictChain(file, chain.diagnosed, diagnosed_notes);
    for (const std::string& note : diagnosed_notes.notes)
    {
      if (note.rfind("chain st", 0) == 0 || note.rfind("chain restarted", 0) == 0)
        check.notes.push_back("diagnosed models: " + note);
    }
    for (const PlatoonCarPrediction& car : check.cars_diagnosed)
      check.pairs_diagnosed.push_back(predictPair(data, car.position, car.model, check.first_row, check.end_row));
  }
  if (check.end_row - check.first_row < data.rows())
    check.notes.push_back(describeRowsLeftOut(data, check.first_row, check.end_row));
  return check;
}

/// The cars whose models in `chain` differ from the first chain's (by source: each fit says what it
/// was fitted on).
std::vector<PerturbationCarModels> modelsThatDiffer(const PlatoonCheck& first, const PlatoonCheck& chain)
{
  std::vector<PerturbationCarModels> differing;
  for (std::size_t i = 0; i < chain.cars.size() && i < first.cars.size(); ++i)
  {
    const PlatoonCarModel& model = chain.cars[i].model;
    const PlatoonCarModel* diagnosed = i < chain.cars_diagnosed.size() ? &chain.cars_diagnosed[i].model : nullptr;
    const bool same_diagnosed = diagnosed == nullptr || i >= first.cars_diagnosed.size() ||
                                diagnosed->source == first.cars_diagnosed[i].model.source;
    if (model.source != first.cars[i].model.source || !same_diagnosed)
      differing.push_back({chain.cars[i].position, chain.cars[i].name, model,
                           diagnosed != nullptr ? *diagnosed : PlatoonCarModel{}});
  }
  return differing;
}

/// The notes of the other chains that the first chain's do not hold (a chain stopped at another car).
void addNotesOfOtherChains(const std::vector<PlatoonCheck>& chains, PlatoonCheck& check)
{
  for (std::size_t c = 1; c < chains.size(); ++c)
  {
    for (const std::string& note : chains[c].notes)
    {
      if (std::find(check.notes.begin(), check.notes.end(), note) == check.notes.end())
        check.notes.push_back("perturbation " + std::to_string(c + 1) + "'s chain: " + note);
    }
  }
}
}  // namespace

std::optional<std::pair<double, double>> perturbationWindowS(const std::vector<double>& time_s,
                                                             const Perturbation& perturbation,
                                                             const PlatoonCheckOptions& options)
{
  const WindowRows rows = perturbationWindowRows(time_s, perturbation, options.perturbation);
  if (rows.end <= rows.first)
    return std::nullopt;
  return std::make_pair(time_s[rows.first], time_s[rows.end - 1]);
}

PlatoonCheck checkPlatoon(const CampaignFile& file, const std::vector<PlatoonCarModel>& models,
                          const PlatoonCheckOptions& options, const std::vector<PlatoonCarModel>* diagnosed)
{
  PlatoonChainModels chain{models, diagnosed != nullptr ? *diagnosed : std::vector<PlatoonCarModel>{}};
  return checkPlatoonByPerturbation(file, {chain}, options);
}

PlatoonCheck checkPlatoonByPerturbation(const CampaignFile& file, const std::vector<PlatoonChainModels>& chains,
                                        const PlatoonCheckOptions& options)
{
  const OpenAccFile& data = file.contents;
  std::size_t first_row = 0, end_row = 0;
  const std::vector<Perturbation> found = leadPerturbations(data, options, &first_row, &end_row);
  if (chains.empty() || (chains.size() > 1 && chains.size() != found.size()))
    throw std::invalid_argument("checkPlatoonByPerturbation: " + std::to_string(chains.size()) + " chains for " +
                                std::to_string(found.size()) + " perturbations of " + file.name);
  std::vector<PlatoonCheck> predicted;
  for (const PlatoonChainModels& chain : chains)
    predicted.push_back(predictPlatoon(file, chain, options));
  PlatoonCheck check = predicted.front();
  if (check.end_row < check.first_row + 2)
    return check;
  addNotesOfOtherChains(predicted, check);
  if (chains.size() > 1)
    check.notes.push_back("each perturbation is predicted by its own chain, whose models of the cars with no other run "
                          "at their setting were fitted on this run outside that perturbation's window; the cars' "
                          "traces and models shown are perturbation 1's chain's (each perturbation's own in "
                          "own_chain_models)");
  const std::vector<double> time_s = sliceRows(data.time_s, check.first_row, check.end_row);
  if (found.empty())
    check.notes.push_back("no perturbation: in the stretch checked, the first car's speed never drops more than " +
                          printfText("%.1f m/s", options.perturbation.drop_below_median_mps) + " below its median");
  for (std::size_t i = 0; i < found.size(); ++i)
  {
    const PlatoonCheck& chain = predicted[chains.size() == 1 ? 0 : i];
    check.perturbations.push_back(comparePerturbation(chain, data, time_s, found[i], i, options));
    if (chains.size() > 1)
      check.perturbations.back().own_chain_models = modelsThatDiffer(predicted.front(), chain);
    if (!found[i].incomplete.empty())
      check.notes.push_back(perturbationLabel(check.perturbations.back(), i) + found[i].incomplete +
                            "; no car's dip there is measured or scored");
    else if (!found[i].cut_note.empty())
      check.notes.push_back(perturbationLabel(check.perturbations.back(), i) + found[i].cut_note +
                            "; those dips are not measured or scored");
    noteDrivenByHand(data, check.perturbations.back(), i, check.notes);
    markModelsFittedOnIt(chain.cars, data, time_s, i, options, check.perturbations.back(), check.notes);
  }
  return check;
}

}  // namespace acc
