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

nlohmann::json toJson(const PairDipEvidence& evidence)
{
  nlohmann::json dips = nlohmann::json::array();
  for (const PairDip& dip : evidence.dips)
  {
    dips.push_back({{"run", dip.run},
                    {"onset_s", dip.onset_s},
                    {"leader_dip_mps", jsonNumber(dip.leader_dip_mps)},
                    {"follower_dip_mps", jsonNumber(dip.follower_dip_mps)}});
  }
  return {{"dips", dips}, {"dip_ratio", toJson(evidence.ratio)}};
}

}  // namespace acc
