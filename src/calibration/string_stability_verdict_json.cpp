#include "acc_identification/calibration/string_stability_verdict.h"
#include "acc_identification/model/json_number.h"

#include <cmath>

namespace acc
{
namespace
{
nlohmann::json parametersJson(const AccParameters& p)
{
  return {{"k1", jsonNumber(p.k1_per_s2)}, {"k2", jsonNumber(p.k2_per_s)}, {"tau_e", jsonNumber(p.tau_e_s)},
          {"eta", jsonNumber(p.eta_m)}};
}

nlohmann::json sideJson(const SideFit& side)
{
  if (!side.found)
  {
    return nlohmann::json();
  }
  return {{"parameters", parametersJson(side.parameters)},
          {"margin", jsonNumber(side.margin)},
          {"train_rmse_speed", jsonNumber(side.train_rmse_speed_mps)},
          {"test_rmse_speed", jsonNumber(side.test_rmse_speed_mps)},
          {"unconstrained_optimum", side.unconstrained_optimum},
          {"status", side.status}};
}
}  // namespace

nlohmann::json marginPiecesJson(const StabilityTestResult& result)
{
  nlohmann::json pieces = nlohmann::json::array();
  for (const auto& [low, high] : result.margin_allowed_pieces)
    pieces.push_back({jsonNumber(low), jsonNumber(high)});
  return pieces;
}

nlohmann::json toJson(const StabilityTestResult& result)
{
  nlohmann::json json;
  json["verdict"] = toString(result.verdict);
  json["p_value"] = jsonNumber(result.p_value);
  // Which null hypothesis p_value tests ("stable": a small p says unstable); null when not tested.
  json["p_value_hypothesis"] = result.tested ? nlohmann::json(pValueHypothesis(result)) : nlohmann::json();
  json["p_value_stable_rejected"] = jsonNumber(result.p_value_stable_rejected);
  json["p_value_unstable_rejected"] = jsonNumber(result.p_value_unstable_rejected);
  json["alpha"] = jsonNumber(result.alpha);
  json["tested"] = result.tested;
  json["mean_squared_error_difference"] = jsonNumber(result.mean_squared_error_difference);
  json["best_stable"] = sideJson(result.best_stable);
  json["best_unstable"] = sideJson(result.best_unstable);
  json["margin_interval"] = nlohmann::json::array({jsonNumber(result.margin_low), jsonNumber(result.margin_high)});
  json["margin_allowed_pieces"] = marginPiecesJson(result);
  json["margin_interval_note"] = result.margin_interval_note;
  nlohmann::json profile = nlohmann::json::array();
  for (const MarginProfilePoint& point : result.margin_profile)
  {
    profile.push_back({{"margin", jsonNumber(point.margin)},
                       {"fitted", point.fitted},
                       {"train_rmse_speed", jsonNumber(point.train_rmse_speed_mps)},
                       {"test_rmse_speed", jsonNumber(point.test_rmse_speed_mps)},
                       {"p_value", jsonNumber(point.p_value)},
                       {"allowed", point.allowed}});
  }
  json["margin_profile"] = profile;
  json["bootstrap"] = {{"replicates", result.bootstrap_replicates},
                       {"block_length_s", jsonNumber(result.block_length_s)},
                       {"seed", result.seed}};
  json["training_samples"] = result.training_samples;
  json["held_out_samples"] = result.held_out_samples;
  json["held_out_segments"] = result.held_out_segments;
  json["reason"] = result.reason;
  json["solve_time_s"] = jsonNumber(result.solve_time_s);
  if (result.quantities)
  {
    json["identifiable_quantities"] = toJson(*result.quantities);
  }
  return json;
}

}  // namespace acc
