#include "acc_identification/campaign/campaign_sumo_platoon.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "acc_identification/campaign/platoon_check.h"
#include "acc_identification/io/mixed_setting_listing.h"
#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
const SumoAccVType* findVType(const std::vector<SumoAccVType>& vtypes, const std::string& id)
{
  const auto found = std::find_if(vtypes.begin(), vtypes.end(), [&](const SumoAccVType& v) { return v.id == id; });
  return found == vtypes.end() ? nullptr : &*found;
}

/// The car's vType id: its diagnosed one when asked for and there, else its base one.
std::string vtypeIdOf(const std::string& name, const std::string& setting, const std::vector<SumoAccVType>& vtypes,
                      bool diagnosed, std::vector<std::string>& notes)
{
  const std::string base = sumoId(name + "_" + setting);
  if (!diagnosed)
    return base;
  if (findVType(vtypes, base + "_diagnosed") != nullptr)
    return base + "_diagnosed";
  if (findVType(vtypes, base) != nullptr)
    notes.push_back(name + ": no diagnosed vType '" + base + "_diagnosed', its base vType instead");
  return base;
}

/// A car of the chain: its position in the file and its vType.
struct ChainCar
{
  int position = 0;
  const SumoAccVType* vtype = nullptr;
};

/// The cars of the chain from position 2 with data and a vType, in order.
std::vector<ChainCar> chainCars(const CampaignFile& file, const std::vector<SumoAccVType>& vtypes, bool diagnosed,
                                std::vector<std::string>& notes)
{
  std::vector<ChainCar> chain;
  const OpenAccFile& contents = file.contents;
  for (int position = 2;; ++position)
  {
    const OpenAccVehicle* car = contents.vehicle(position);
    const OpenAccVehicle* ahead = contents.vehicle(position - 1);
    if (car == nullptr || !car->has_speed || ahead == nullptr || !ahead->has_gap_to_follower)
    {
      if (position <= static_cast<int>(contents.metadata.vehicle_order.size()))
        notes.push_back("the chain stops at position " + std::to_string(position) + " (" +
                        contents.vehicleName(position) + "): no speed or no gap to the car ahead in the file");
      break;
    }
    const std::string id = vtypeIdOf(car->name, file.settingOf(car->name), vtypes, diagnosed, notes);
    const SumoAccVType* vtype = findVType(vtypes, id);
    if (vtype == nullptr)
    {
      notes.push_back("the chain stops at position " + std::to_string(position) + ": no vType '" + id +
                      "' in the file (campaign --sumo-vtype writes one per fitted car and setting)");
      break;
    }
    chain.push_back({position, vtype});
  }
  return chain;
}

bool chainHasData(const OpenAccFile& file, const std::vector<ChainCar>& chain, std::size_t row)
{
  if (!std::isfinite(file.time_s[row]))
    return false;
  for (const ChainCar& car : chain)
    if (!std::isfinite(file.vehicle(car.position)->speed_mps[row]) ||
        !std::isfinite(file.vehicle(car.position - 1)->gap_to_follower_m[row]))
      return false;
  return true;
}

std::vector<double> rows(const std::vector<double>& column, std::size_t first, std::size_t end)
{
  return std::vector<double>(column.begin() + static_cast<std::ptrdiff_t>(first),
                             column.begin() + static_cast<std::ptrdiff_t>(end));
}
}  // namespace

FilePlatoonForSumo filePlatoonForSumo(const CampaignFile& file, const std::vector<SumoAccVType>& vtypes,
                                      bool diagnosed)
{
  FilePlatoonForSumo out;
  const OpenAccFile& contents = file.contents;
  std::vector<ChainCar> chain = chainCars(file, vtypes, diagnosed, out.notes);
  const auto [first, end] = longestLeadStretch(contents, PlatoonCheckOptions{}.max_time_step_s);
  // The first row where the whole chain has data; a car that never has it with the others ends it.
  std::size_t start = end;
  while (!chain.empty())
  {
    for (start = first; start < end && !chainHasData(contents, chain, start); ++start)
    {
    }
    if (start + 1 < end)
      break;
    out.notes.push_back("the chain stops before position " + std::to_string(chain.back().position) +
                        ": no row where it and every car ahead have speed and gap");
    chain.pop_back();
  }
  out.input.name = file.name;
  if (chain.empty() || start + 1 >= end)
    return out;
  if (start > 0 || end < contents.rows())
  {
    // Rows not replayed are said: a car whose data start late, or a hole in the first car's
    // speeds, once cut the front of the run for every car without a word.
    std::ostringstream note;
    note << "replayed lines " << contents.line[start] << "-" << contents.line[end - 1] << " (t = "
         << significant(contents.time_s[start], 8) << "-" << significant(contents.time_s[end - 1], 8) << " s, "
         << end - start << " of " << contents.rows() << " rows): the first car's longest stretch without a hole"
         << (start > first ? ", from its first row where every car of the chain has speed and gap (line " +
                                 std::to_string(contents.line[first]) + " on lacks one)"
                           : std::string());
    out.notes.push_back(note.str());
  }
  out.input.time_s = rows(contents.time_s, start, end);
  out.input.leader_speed_mps = rows(contents.vehicle(1)->speed_mps, start, end);
  for (const ChainCar& car : chain)
  {
    const std::vector<double>& speed_mps = contents.vehicle(car.position)->speed_mps;
    out.input.vtypes.push_back(*car.vtype);
    out.input.starts.push_back(
        {car.vtype->id, contents.vehicle(car.position - 1)->gap_to_follower_m[start], speed_mps[start]});
    out.input.measured_speed_mps.push_back(rows(speed_mps, start, end));
  }
  return out;
}

FilePlatoonForSumo readFilePlatoonForSumo(const std::string& path, const std::vector<std::string>& listings,
                                          const std::vector<SumoAccVType>& vtypes, bool diagnosed)
{
  std::vector<std::string> paths{path};
  for (const std::string& listing : listings)
  {
    if (!looksLikeMixedSettingListing(listing))
      throw std::invalid_argument(listing + ": not a mixed-setting listing (its first line is not "
                                            "'filename,Long timegap setting' or alike)");
    paths.push_back(listing);
  }
  const CampaignInputs inputs = loadCampaign(paths);
  FilePlatoonForSumo platoon = filePlatoonForSumo(inputs.files.front(), vtypes, diagnosed);
  platoon.notes.insert(platoon.notes.begin(), inputs.notes.begin(), inputs.notes.end());
  return platoon;
}

nlohmann::json replayFilePlatoonInSumo(const std::string& path, const std::vector<std::string>& listings,
                                       const std::string& vtype_file, bool diagnosed,
                                       const SumoReplayOptions& options, std::ostream& out, std::ostream& log)
{
  const FilePlatoonForSumo platoon = readFilePlatoonForSumo(path, listings, readSumoAccVTypes(vtype_file), diagnosed);
  for (const std::string& note : platoon.notes)
    log << "note: " << note << "\n";
  if (platoon.input.vtypes.empty())
    throw std::runtime_error(path + ": no car of the platoon can be replayed (see the notes)");
  const SumoPlatoonReplay replay = replayPlatoonInSumo(platoon.input, vtype_file, options);
  printReplay(replay, out);
  nlohmann::json json{{"mode", "platoon"}, {"file", path}, {"vtype_file", vtype_file}, {"notes", platoon.notes}};
  json["segments"] = nlohmann::json::array({toJson(replay)});
  json["sumo_law"] = "SUMO 1.15 MSCFModel_ACC (docs/SUMO.md)";
  return json;
}

}  // namespace acc
