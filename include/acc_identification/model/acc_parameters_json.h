#pragma once

#include <nlohmann/json.hpp>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/json_number.h"

namespace acc
{
/// {k1_per_s2, k2_per_s, tau_e_s, eta_m}, null where a value is not finite: the parameters as
/// calibrate's and campaign's JSON write them.
inline nlohmann::json parametersJson(const AccParameters& p)
{
  return {{"k1_per_s2", jsonNumber(p.k1_per_s2)},
          {"k2_per_s", jsonNumber(p.k2_per_s)},
          {"tau_e_s", jsonNumber(p.tau_e_s)},
          {"eta_m", jsonNumber(p.eta_m)}};
}

}  // namespace acc
