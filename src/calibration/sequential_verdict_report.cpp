#include <cmath>
#include <cstdio>
#include <ostream>

#include "acc_identification/calibration/sequential_verdict.h"
#include "acc_identification/model/json_number.h"
#include "acc_identification/model/number_text.h"

namespace acc
{

nlohmann::json toSequenceEntryJson(const SequentialLook& look)
{
  return {{"time_s", look.time_s},
          {"samples", look.samples},
          {"verdict", toString(look.verdict)},
          {"p_value", look.p_value},
          {"e_value_unstable", jsonNumber(look.e_value_unstable)},
          {"e_value_stable", jsonNumber(look.e_value_stable)}};
}

nlohmann::json toJson(const SequentialLook& look)
{
  nlohmann::json json = toSequenceEntryJson(look);
  json["p_value_stable_rejected"] = look.p_value_stable_rejected;
  json["p_value_unstable_rejected"] = look.p_value_unstable_rejected;
  json["alpha"] = look.alpha;
  json["blocks_scored"] = look.blocks_scored;
  json["blocks_skipped"] = look.blocks_skipped;
  json["block_length_s"] = look.block_length_s;
  json["decided_at_s"] = jsonNumber(look.decided_at_s);
  json["reversed"] = look.reversed;
  json["first_verdict"] = toString(look.first_verdict);
  json["reversed_at_s"] = jsonNumber(look.reversed_at_s);
  json["stable_fit_margin"] = jsonNumber(look.stable_fit_margin);
  json["unstable_fit_margin"] = jsonNumber(look.unstable_fit_margin);
  json["reason"] = look.reason;
  json["solve_time_s"] = look.solve_time_s;
  json["evaluations"] = look.evaluations;
  return json;
}

void printVerdictSequence(const std::vector<SequentialLook>& looks, std::ostream& out)
{
  out << "  time [s]  samples  blocks  E_unstable    E_stable  verdict     p (anytime-valid)\n";
  for (const SequentialLook& look : looks)
  {
    out << printfText("%10.1f", look.time_s) << printfText("%9.0f", static_cast<double>(look.samples))
        << printfText("%8.0f", static_cast<double>(look.blocks_scored)) << printfText("%12.4g", look.e_value_unstable)
        << printfText("%12.4g", look.e_value_stable) << "  " << toString(look.verdict)
        << std::string(look.verdict == StabilityVerdict::Undecided ? 2 : 4, ' ') << printfText("%.4g", look.p_value)
        << (look.reversed ? "  REVERSED" : "") << "\n";
  }
}

}  // namespace acc
