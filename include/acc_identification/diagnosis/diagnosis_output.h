#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/diagnosis/diagnosis.h"

namespace acc
{
/// The diagnosis as JSON: dominant_effect, plausible_effects, baseline {parameters,
/// train_rmse_speed, test_rmse_speed, test_rmse_gap, stability}, effects [{name, parameters,
/// standard_errors, train_rmse_speed, test_rmse_speed, test_rmse_gap, improvement, significant,
/// stability}], selection {rule, ...}, where {regimes, speed_bands, segments, frequency_bands},
/// runs, notes. Non-finite numbers are written as null (JSON has no NaN).
nlohmann::json diagnosisToJson(const DiagnosisResult& result);

/// Writes the tables the report's figures are drawn from into dir (which must exist):
///   residuals.csv  run,time_s,regime,speed_mps,gap_m,base_speed_mps,base_gap_m,effect_speed_mps,effect_gap_m
///   spectrum.csv   run,frequency_hz,power_before,power_after
///   gain.csv       frequency_rad_s,base_db,<effect>_db...
///   train_fit.csv  run,time_s,speed_mps,base_speed_mps,effect_speed_mps (first parts)
/// Throws std::runtime_error when a file cannot be written.
void writeDiagnosisTables(const DiagnosisResult& result, const std::string& dir);

}  // namespace acc
