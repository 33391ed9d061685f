#include "acc_identification/calibration/stability_test.h"

#include <cmath>

namespace acc
{
namespace
{
nlohmann::json number(double value)
{
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

nlohmann::json parametersJson(const AccParameters& p)
{
  return {{"k1", number(p.k1_per_s2)}, {"k2", number(p.k2_per_s)}, {"tau_e", number(p.tau_e_s)},
          {"eta", number(p.eta_m)}};
}

nlohmann::json sideJson(const SideFit& side)
{
  if (!side.found)
  {
    return nlohmann::json();
  }
  return {{"parameters", parametersJson(side.parameters)},
          {"margin", number(side.margin)},
          {"train_rmse_speed", number(side.train_rmse_speed_mps)},
          {"test_rmse_speed", number(side.test_rmse_speed_mps)},
          {"unconstrained_optimum", side.unconstrained_optimum},
          {"status", side.status}};
}
}  // namespace

nlohmann::json toJson(const StabilityTestResult& result)
{
  nlohmann::json json;
  json["verdict"] = toString(result.verdict);
  json["p_value"] = number(result.p_value);
  // Which null hypothesis p_value tests ("stable": a small p says unstable); null when not tested.
  json["p_value_hypothesis"] = result.tested ? nlohmann::json(pValueHypothesis(result)) : nlohmann::json();
  json["p_value_stable_rejected"] = number(result.p_value_stable_rejected);
  json["p_value_unstable_rejected"] = number(result.p_value_unstable_rejected);
  json["alpha"] = number(result.alpha);
  json["tested"] = result.tested;
  json["mean_squared_error_difference"] = number(result.mean_squared_error_difference);
  json["best_stable"] = sideJson(result.best_stable);
  json["best_unstable"] = sideJson(result.best_unstable);
  json["margin_interval"] = nlohmann::json::array({number(result.margin_low), number(result.margin_high)});
  json["margin_interval_note"] = result.margin_interval_note;
  nlohmann::json profile = nlohmann::json::array();
  for (const MarginProfilePoint& point : result.margin_profile)
  {
    profile.push_back({{"margin", number(point.margin)},
                       {"fitted", point.fitted},
                       {"train_rmse_speed", number(point.train_rmse_speed_mps)},
                       {"test_rmse_speed", number(point.test_rmse_speed_mps)},
                       {"p_value", number(point.p_value)},
                       {"allowed", point.allowed}});
  }
  json["margin_profile"] = profile;
  json["bootstrap"] = {{"replicates", result.bootstrap_replicates},
                       {"block_length_s", number(result.block_length_s)},
                       {"seed", result.seed}};
  json["training_samples"] = result.training_samples;
  json["held_out_samples"] = result.held_out_samples;
  json["held_out_segments"] = result.held_out_segments;
  json["reason"] = result.reason;
  json["solve_time_s"] = number(result.solve_time_s);
  if (result.quantities)
  {
    json["identifiable_quantities"] = toJson(*result.quantities);
  }
  return json;
}

}  // namespace acc
