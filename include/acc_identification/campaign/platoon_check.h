#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "acc_identification/campaign/campaign_inputs.h"
#include "acc_identification/campaign/perturbation.h"
#include "acc_identification/model/acc_parameters.h"

namespace acc
{
/// The model a platoon check simulates one following car with.
struct PlatoonCarModel
{
  bool available = false;
  AccParameters parameters;
  /// Where it comes from: "leave-one-run-out: 3 other runs", "first half of this run (no other
  /// run of this car and setting)"; or why there is none.
  std::string source;
};

/// One car's measured and predicted dip in one perturbation.
struct DipComparison
{
  int position = 0;  ///< 1 = the platoon's first car (the input: predicted = measured)
  std::string name;
  double measured_dip_mps = 0.0;        ///< NaN without data
  double predicted_dip_mps = 0.0;       ///< NaN where the chain stopped
  double measured_amplification = 0.0;  ///< dip(k) / dip(k-1); NaN for the first car or without data
  double predicted_amplification = 0.0;
};

/// Where the model and the data disagree.
struct PlatoonDisagreement
{
  std::size_t perturbation = 0;  ///< index into PlatoonCheck::perturbations
  int position = 0;
  std::string name;
  std::string what;  ///< "predicted amplification 1.31, measured attenuation 0.84", "dip error +45 %"
};

struct PerturbationCheck
{
  Perturbation perturbation;
  std::vector<DipComparison> positions;  ///< every car of the file, by position
  /// The measured dip of the last car with data exceeds the first car's.
  bool data_show_growth = false;
  std::vector<PlatoonDisagreement> disagreements;
};

/// One car of the chain: its model and the prediction made with it.
struct PlatoonCarPrediction
{
  int position = 0;
  std::string name;
  PlatoonCarModel model;
  bool predicted = false;
  std::size_t start_row = 0;                ///< the prediction starts at its measured gap and speed here
  std::vector<double> predicted_speed_mps;  ///< per row of the file; NaN outside the prediction
  double rmse_speed_mps = 0.0;              ///< predicted against measured speed where both exist; NaN if never
  std::string note;                         ///< why not predicted
};

/// The whole platoon of one run predicted from its real first car.
struct PlatoonCheck
{
  std::string run;      ///< the file's name
  std::string setting;
  std::size_t first_row = 0, end_row = 0;  ///< the rows simulated (the first car's longest stretch with data)
  std::vector<PlatoonCarPrediction> cars;  ///< position 2 onwards
  std::vector<PerturbationCheck> perturbations;
  std::vector<std::string> notes;          ///< chain stops and other caveats
};

struct PlatoonCheckOptions
{
  PerturbationCriteria perturbation;
  /// A dip whose prediction is off by more than this fraction of the measured dip is a disagreement.
  double max_relative_dip_error = 0.3;
  /// Steps longer than this end the first car's stretch (a hole in the data).
  double max_time_step_s = 0.5;
};

/// Predicts every following car of the file: car k is simulated (simulateFollower) with
/// models[k] (index = position; entries 0 and 1 unused) from its measured gap and speed at the
/// first row where it has both, driven by the PREDICTED speed of car k-1 (for k = 2 the measured
/// first car's). The chain stops at the first car with no data, no model, or a diverged
/// simulation, and says so in notes. Then each perturbation of the first car is measured
/// (findPerturbations, dipDepthMps) on the measured and the predicted speeds of every position.
PlatoonCheck checkPlatoon(const CampaignFile& file, const std::vector<PlatoonCarModel>& models,
                          const PlatoonCheckOptions& options = {});

/// The rows [first, end) of the longest stretch where time and the first car's speed are finite
/// and time increases by at most max_time_step_s.
std::pair<std::size_t, std::size_t> longestLeadStretch(const OpenAccFile& file, double max_time_step_s);

}  // namespace acc
