#include "acc_identification/reproduction/figure_summary.h"

#include <cmath>
#include <optional>
#include <sstream>

#include "acc_identification/model/string_stability.h"
#include "acc_identification/model/json_number.h"

namespace acc
{
namespace
{
using nlohmann::json;

template <typename T>
json optionalJson(const std::optional<T>& value)
{
  return value ? json(*value) : json(nullptr);
}

json onsetJson(const GrowthOnset& o)
{
  return json{{"decays_at_first", o.decays_at_first},
              {"smallest_at", o.smallest_at},
              {"growth_starts_at", optionalJson(o.growth_starts_at)},
              {"exceeds_lead_at", optionalJson(o.exceeds_lead_at)}};
}
}  // namespace

json settingSummaryJson(const NamedSetting& setting)
{
  const AccParameters& p = setting.parameters;
  const StringStabilityReport report = analyzeStringStability(p);
  return {{"name", setting.name},
          {"source", setting.source},
          {"k1_per_s2", p.k1_per_s2},
          {"k2_per_s", p.k2_per_s},
          {"tau_e_s", p.tau_e_s},
          {"eta_m", p.eta_m},
          {"lambda2", jsonNumberOrInfinity(report.lambda2)},
          {"string_stable", report.string_stable},
          {"amplified_band_upper_rad_s", report.amplified_band_upper_rad_s},
          {"peak_gain_db", jsonNumberOrInfinity(report.peak_gain_db)},
          {"peak_frequency_rad_s", report.peak_frequency_rad_s}};
}

json disturbanceJson(const DisturbanceResponse& response)
{
  json per_vehicle = json::array();
  for (const VehicleDisturbance& d : response.per_vehicle)
  {
    per_vehicle.push_back({{"minimum_speed_mps", d.minimum_speed_mps},
                           {"maximum_speed_mps", d.maximum_speed_mps},
                           {"peak_to_peak_mps", d.peak_to_peak_mps},
                           {"drop_below_reference_mps", d.drop_below_reference_mps},
                           {"rise_above_reference_mps", d.rise_above_reference_mps}});
  }
  return {{"followers", response.per_vehicle.size() - 1},
          {"reference_speed_mps", response.reference_speed_mps},
          {"per_vehicle", per_vehicle},
          {"growth_by_peak_to_peak", onsetJson(response.by_peak_to_peak)},
          {"growth_by_drop", onsetJson(response.by_drop)},
          {"first_negative_speed_vehicle", optionalJson(response.first_negative_speed_vehicle)},
          {"last_follower_settled", response.last_follower_settled}};
}

std::string onsetText(const GrowthOnset& o)
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

}  // namespace acc
