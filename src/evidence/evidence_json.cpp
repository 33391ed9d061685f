#include "acc_identification/evidence/evidence_json.h"
#include "acc_identification/model/json_number.h"

#include <cmath>

namespace acc
{
nlohmann::json toJson(const DipRatioEstimate& d)
{
  return {{"perturbations", d.count},
          {"skipped", d.skipped},
          {"ratio_of_means", jsonNumber(d.ratio_of_means)},
          {"median_ratio", jsonNumber(d.median_ratio)},
          {"smallest_ratio", jsonNumber(d.smallest_ratio)},
          {"largest_ratio", jsonNumber(d.largest_ratio)},
          {"lower", jsonNumber(d.lower)},
          {"upper", jsonNumber(d.upper)},
          {"confidence", d.confidence},
          {"verdict", toString(d.amplifies)},
          {"reason", d.reason}};
}

nlohmann::json toJson(const ClusteredRatio& r)
{
  return {{"ratio", jsonNumber(r.ratio)},
          {"lower", jsonNumber(r.lower)},
          {"upper", jsonNumber(r.upper)},
          {"confidence", r.confidence},
          {"clusters", r.clusters},
          {"observations", r.observations}};
}

nlohmann::json toJson(const DipShapeTransfer& t)
{
  return {{"braking", toJson(t.braking)},
          {"recovery", toJson(t.recovery)},
          {"median_widening_s", jsonNumber(t.median_widening_s)},
          {"widenings", t.widenings}};
}

nlohmann::json toJson(const PairDipEvidence& evidence)
{
  nlohmann::json dips = nlohmann::json::array();
  for (const PairDip& dip : evidence.dips)
  {
    dips.push_back({{"run", dip.run},
                    {"onset_s", dip.onset_s},
                    {"incomplete", dip.perturbation.incomplete},
                    {"leader_dip_mps", jsonNumber(dip.leader_dip_mps)},
                    {"follower_dip_mps", jsonNumber(dip.follower_dip_mps)},
                    {"leader_peak_braking_mps2", jsonNumber(dip.leader_shape.braking_mps2)},
                    {"follower_peak_braking_mps2", jsonNumber(dip.follower_shape.braking_mps2)},
                    {"leader_peak_recovery_mps2", jsonNumber(dip.leader_shape.recovery_mps2)},
                    {"follower_peak_recovery_mps2", jsonNumber(dip.follower_shape.recovery_mps2)},
                    {"leader_dip_width_s", jsonNumber(dip.leader_shape.width_s)},
                    {"follower_dip_width_s", jsonNumber(dip.follower_shape.width_s)}});
  }
  return {{"dips", dips}, {"dip_ratio", toJson(evidence.ratio)}, {"shape_passed_on", toJson(evidence.shape)}};
}

}  // namespace acc
