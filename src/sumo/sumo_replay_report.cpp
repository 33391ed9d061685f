#include "acc_identification/sumo/sumo_replay_report.h"

#include <filesystem>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "acc_identification/model/json_number.h"

namespace acc
{
namespace
{
std::vector<SumoAccVType> chosenVTypes(const std::string& vtype_file, const std::vector<std::string>& ids,
                                       std::ostream& out)
{
  const std::vector<SumoAccVType> all = readSumoAccVTypes(vtype_file);
  if (all.empty())
    throw std::runtime_error(vtype_file + " holds no vType with carFollowModel=\"ACC\"");
  if (ids.empty())
  {
    out << "vType: " << all.front().id << " (the first ACC vType of " << vtype_file << ")\n";
    return {all.front()};
  }
  std::vector<SumoAccVType> chosen;
  for (const std::string& id : ids)
  {
    auto found = std::find_if(all.begin(), all.end(), [&](const SumoAccVType& v) { return v.id == id; });
    if (found == all.end())
    {
      std::string known;
      for (const SumoAccVType& v : all)
        known += (known.empty() ? "" : ", ") + v.id;
      throw std::runtime_error("no ACC vType '" + id + "' in " + vtype_file + " (it has: " + known + ")");
    }
    chosen.push_back(*found);
  }
  return chosen;
}

/// sqrt of the sample-weighted mean of squares: the RMSE over all segments' samples.
double pooledRmse(const std::vector<SumoPairReplay>& replays, double SumoPairReplay::*field)
{
  double sum = 0.0, count = 0.0;
  for (const SumoPairReplay& r : replays)
  {
    const double value = r.*field;
    if (std::isfinite(value))
    {
      sum += value * value * static_cast<double>(r.samples);
      count += static_cast<double>(r.samples);
    }
  }
  return count > 0.0 ? std::sqrt(sum / count) : std::numeric_limits<double>::quiet_NaN();
}

nlohmann::json pairsJson(const std::vector<SumoPairReplay>& replays)
{
  nlohmann::json json{
      {"mode", "pair"},
      {"vtype", replays.front().vtype_id},
      {"rmse_speed_sumo_vs_model_mps", jsonNumber(pooledRmse(replays, &SumoPairReplay::rmse_speed_sumo_vs_model_mps))},
      {"rmse_speed_sumo_vs_measured_mps",
       jsonNumber(pooledRmse(replays, &SumoPairReplay::rmse_speed_sumo_vs_measured_mps))},
      {"rmse_speed_model_vs_measured_mps",
       jsonNumber(pooledRmse(replays, &SumoPairReplay::rmse_speed_model_vs_measured_mps))},
      {"rmse_speed_sumo_vs_sumo_law_replica_mps",
       jsonNumber(pooledRmse(replays, &SumoPairReplay::rmse_speed_sumo_vs_replica_mps))}};
  json["segments"] = nlohmann::json::array();
  for (const SumoPairReplay& r : replays)
    json["segments"].push_back(toJson(r));
  return json;
}

/// The replayable runs in SUMO: one vType, each run as a pair; several, each run as a platoon.
nlohmann::json replayRunsInSumo(const std::vector<CarFollowingRun>& runs, const std::vector<SumoAccVType>& vtypes,
                                const std::string& vtype_file, const SumoReplayOptions& options, std::ostream& out)
{
  // --keep DIR with several segments: each its own DIR/segment_k (one folder held only the last).
  const auto optionsOf = [&](std::size_t k) {
    SumoReplayOptions segment = options;
    if (!options.work_dir.empty() && runs.size() > 1)
      segment.work_dir = (std::filesystem::path(options.work_dir) / ("segment_" + std::to_string(k + 1))).string();
    return segment;
  };
  nlohmann::json json;
  if (vtypes.size() == 1)
  {
    std::vector<SumoPairReplay> replays;
    for (std::size_t k = 0; k < runs.size(); ++k)
    {
      replays.push_back(replayPairInSumo(runs[k], vtypes.front(), vtype_file, optionsOf(k)));
      printReplay(replays.back(), out);
    }
    return pairsJson(replays);
  }
  json = {{"mode", "platoon"}, {"segments", nlohmann::json::array()}};
  for (std::size_t k = 0; k < runs.size(); ++k)
  {
    const SumoPlatoonReplay replay = replayPlatoonInSumo(equilibriumPlatoon(runs[k], vtypes), vtype_file, optionsOf(k));
    printReplay(replay, out);
    json["segments"].push_back(toJson(replay));
  }
  return json;
}
}  // namespace

nlohmann::json replayRunInSumo(const std::vector<CarFollowingRun>& runs, const std::string& vtype_file,
                               const std::vector<std::string>& ids, const SumoReplayOptions& options,
                               std::ostream& out)
{
  if (runs.empty())
    throw std::runtime_error("no run to replay");
  const std::vector<SumoAccVType> vtypes = chosenVTypes(vtype_file, ids, out);
  // A segment SUMO cannot step through (one dropped row below --max-gap) is skipped and said, not
  // the end of the segments already replayed.
  std::vector<CarFollowingRun> replayable;
  nlohmann::json skipped = nlohmann::json::array();
  for (const CarFollowingRun& run : runs)
  {
    const std::string reason = nonUniformStepReason(run);
    if (reason.empty())
      replayable.push_back(run);
    else
    {
      out << "skipped: " << reason << "\n";
      skipped.push_back({{"run", run.name}, {"reason", reason}});
    }
  }
  if (replayable.empty())
    throw std::runtime_error("no segment SUMO can replay: " + skipped.front()["reason"].get<std::string>());
  nlohmann::json json = replayRunsInSumo(replayable, vtypes, vtype_file, options, out);
  json["skipped_segments"] = skipped;
  json["vtype_file"] = vtype_file;
  json["sumo_law"] = "SUMO 1.15 MSCFModel_ACC (docs/SUMO.md)";
  return json;
}

}  // namespace acc
