#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/io/input_account.h"

namespace acc
{
/// THE verdict of a diagnosis (statedVerdict) as JSON: {model, verdict, p_value_stable_rejected,
/// p_value_unstable_rejected, model_adequate, why}; diagnosisToJson's "verdict".
nlohmann::json verdictJson(const DiagnosisResult& r);

/// The diagnosis as JSON: dominant_effect, plausible_effects, selected_effects (the forward
/// selection's chain, in order: [{effect, model_effects, train_rmse_speed, test_rmse_speed,
/// test_rmse_gap, improvement over the previous step {mean_mse_reduction, relative (to the base
/// model's held-out MSE), lower_bound, upper_bound}, parameters, effect_parameters,
/// standard_errors, stability, stability_test {verdict, p_value, reason}}]), forward_selection
/// {stop_reason, rounds [{on_top_of, added, candidates [{effect, improvement, significant}]}]},
/// baseline {parameters,
/// train_rmse_speed, test_rmse_speed, test_rmse_gap, stability}, effects [{name, parameters,
/// standard_errors, train_rmse_speed, test_rmse_speed, test_rmse_gap, improvement, significant,
/// stability}], selection {rule, ...}, where {regimes, speed_bands, segments, frequency_bands},
/// runs, notes. Non-finite numbers are written as null (JSON has no NaN).
nlohmann::json diagnosisToJson(const DiagnosisResult& result);

/// diagnose --json (and Python's diagnose): diagnosisToJson with what was read: inputs (the RUN
/// paths), held_out_inputs (--held-out; none when empty), openacc_pairs and inputs_read (each
/// file's account).
nlohmann::json diagnosisToJson(const DiagnosisResult& result, const std::vector<std::string>& inputs,
                               const std::vector<std::string>& held_out_inputs,
                               const std::vector<InputAccount>& inputs_read);

/// Writes the tables the report's figures are drawn from into dir (which must exist):
///   residuals.csv  run,time_s,regime,speed_mps,gap_m,base_speed_mps,base_gap_m,effect_speed_mps,effect_gap_m
///   spectrum.csv   run,frequency_hz,power_before,power_after
///   gain.csv       frequency_rad_s,base_db,<effect>_db...
///   train_fit.csv  run,time_s,speed_mps,base_speed_mps,effect_speed_mps (first parts)
/// Throws std::runtime_error when a file cannot be written.
void writeDiagnosisTables(const DiagnosisResult& result, const std::string& dir);

/// diagnose --sumo-vtype PATH: the final model as a SUMO vType (docs/SUMO.md), its effects where
/// SUMO has an equivalent and the others named in the file, its adequacy as a caveat when it does
/// not describe the data (runs: those diagnosed). False after saying on log why not.
bool saveFinalModelVType(const DiagnosisResult& result, const std::vector<CarFollowingRun>& runs,
                         const std::string& path, const std::string& id, bool from_openacc, std::ostream& log);

/// diagnose --report DIR (which must exist): the tables, diagnosis.json (json) and, unless
/// no_plots, the figures and report.md drawn by plot_script (plot_diagnosis.py). False after
/// saying on log what failed.
bool writeDiagnosisReport(const DiagnosisResult& result, const nlohmann::json& json, const std::string& dir,
                          const std::string& plot_script, bool no_plots, std::ostream& log);

}  // namespace acc
