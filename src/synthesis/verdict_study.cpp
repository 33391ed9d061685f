#include "acc_identification/synthesis/verdict_study.h"

#include <algorithm>
#include <cmath>

#include "acc_identification/calibration/sequential_verdict.h"
#include "acc_identification/model/json_number.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/synthesis/synthetic_runs.h"

namespace acc
{
namespace
{
/// One drive's looks into its class's tallies.
void tallyDrive(const std::vector<SequentialLook>& looks, double drive_start_s, StabilityVerdict right,
                const VerdictStudyOptions& options, VerdictStudyClass& r)
{
  ++r.drives;
  bool wrong = false, withdrawn = false;
  StabilityVerdict taken = StabilityVerdict::Undecided;
  for (const SequentialLook& look : looks)
  {
    wrong = wrong || (look.verdict != StabilityVerdict::Undecided && look.verdict != right);
    withdrawn = withdrawn || (taken != StabilityVerdict::Undecided && look.verdict != taken);
    taken = look.verdict;
  }
  for (std::size_t c = 0; c < options.checkpoints_s.size(); ++c)
  {
    // The look the node would show at that drive length: the last at or before it.
    const SequentialLook* at = nullptr;
    for (const SequentialLook& look : looks)
      if (look.time_s - drive_start_s <= options.checkpoints_s[c] + 1e-9)
        at = &look;
    r.right_by_length[c] += at != nullptr && at->verdict == right;
  }
  r.wrong += wrong;
  r.withdrawn += withdrawn;
  r.reversed += !looks.empty() && looks.back().reversed;
  if (!looks.empty() && looks.back().verdict == right && !looks.back().reversed)
  {
    ++r.decided_right;
    r.decided_at_sum_s += looks.back().decided_at_s - drive_start_s;
  }
}
}  // namespace

std::string fitCheckpointsToDuration(VerdictStudyOptions* options, bool checkpoints_given)
{
  std::vector<double>& lengths_s = options->checkpoints_s;
  if (!checkpoints_given)
  {
    lengths_s.erase(std::remove_if(lengths_s.begin(), lengths_s.end(),
                                   [&](double s) { return s >= options->duration_s; }),
                    lengths_s.end());
    lengths_s.push_back(options->duration_s);
  }
  for (const double length_s : lengths_s)
    if (length_s > options->duration_s)
      return "--checkpoints " + significant(length_s) + " s is longer than each drive (--duration " +
             significant(options->duration_s) + " s)";
  return "";
}

std::vector<VerdictStudyClass> runVerdictStudy(const VerdictStudyOptions& options, std::FILE* progress)
{
  SequentialVerdictOptions verdict_options;
  verdict_options.alpha = options.alpha;
  verdict_options.look_period_s = options.look_every_s;
  std::vector<VerdictStudyClass> classes;
  for (double margin : options.margins)
  {
    VerdictStudyClass r;
    r.margin = margin;
    r.right_by_length.assign(options.checkpoints_s.size(), 0);
    const StabilityVerdict right = margin >= 0 ? StabilityVerdict::Stable : StabilityVerdict::Unstable;
    for (int i = 0; i < options.drives; ++i)
    {
      const std::uint32_t seed = options.first_seed + static_cast<std::uint32_t>(i);
      const double cruise_mps = options.cruise_speeds_mps[static_cast<std::size_t>(i) % options.cruise_speeds_mps.size()];
      const CarFollowingRun run = synthesizeRun(truthWithMargin(margin), options.duration_s, 0.1, cruise_mps, seed);
      const std::vector<SequentialLook> looks = replaySequentialVerdict({run}, verdict_options);
      tallyDrive(looks, run.time_s.front(), right, options, r);
      if (progress != nullptr)
        std::fprintf(progress, "m = %g, drive %d/%d: %s\n", margin, i + 1, options.drives,
                     looks.empty() ? "no look" : toString(looks.back().verdict).c_str());
    }
    classes.push_back(r);
  }
  return classes;
}

std::string verdictStudyTable(const std::vector<VerdictStudyClass>& classes, const VerdictStudyOptions& options)
{
  std::string table = printfText("Sequential verdict on %d seeded synthetic drive(s) per class, %.0f s each, a look "
                                 "every %.0f s, alpha %.2f\n",
                                 options.drives, options.duration_s, options.look_every_s, options.alpha);
  table += printfText("%8s %7s %7s %10s %9s", "margin", "drives", "wrong", "withdrawn", "reversed");
  for (double c : options.checkpoints_s)
    table += printfText("  right@%4.0fs", c);
  table += "  mean decided at [s]\n";
  for (const VerdictStudyClass& r : classes)
  {
    table += printfText("%8.2f %7d %7d %10d %9d", r.margin, r.drives, r.wrong, r.withdrawn, r.reversed);
    for (int right : r.right_by_length)
      table += printfText("  %11.2f", static_cast<double>(right) / r.drives);
    const double decided_at_s = r.meanDecidedAtS();
    table += std::isfinite(decided_at_s) ? printfText("  %8.0f\n", decided_at_s) : printfText("  %8s\n", "-");
  }
  return table;
}

nlohmann::json verdictStudyJson(const std::vector<VerdictStudyClass>& classes, const VerdictStudyOptions& options)
{
  nlohmann::json json = nlohmann::json::array();
  for (const VerdictStudyClass& r : classes)
  {
    nlohmann::json power = nlohmann::json::array();
    for (std::size_t c = 0; c < options.checkpoints_s.size(); ++c)
      power.push_back({{"drive_length_s", options.checkpoints_s[c]},
                       {"decided_right", static_cast<double>(r.right_by_length[c]) / r.drives}});
    json.push_back({{"margin", r.margin},
                    {"drives", r.drives},
                    {"wrong_decisions", r.wrong},
                    {"withdrawn", r.withdrawn},
                    {"reversed", r.reversed},
                    {"power_by_length", power},
                    {"mean_decided_at_s", jsonNumber(r.meanDecidedAtS())}});
  }
  return {{"drives_per_class", options.drives},
          {"duration_s", options.duration_s},
          {"look_every_s", options.look_every_s},
          {"alpha", options.alpha},
          {"classes", json}};
}

}  // namespace acc
