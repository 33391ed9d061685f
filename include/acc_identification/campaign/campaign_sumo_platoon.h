#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "acc_identification/campaign/campaign_inputs.h"
#include "acc_identification/sumo/sumo_replay.h"

namespace acc
{
/// An OpenACC platoon file as SUMO replays it (sumo_replay --platoon): the first car's longest
/// stretch with data (longestLeadStretch) from the first row where every car of the chain has its
/// speed and gap, the chain of cars from position 2 whose vType ("<VEHICLE>_<setting>", as
/// campaign --sumo-vtype names them) is in vtypes, each started from its measured gap and speed,
/// and every car's measured speeds for the dips. notes say where the chain stops and why.
struct FilePlatoonForSumo
{
  SumoPlatoonInput input;
  std::vector<std::string> notes;
};

/// diagnosed: each car's "<VEHICLE>_<setting>_diagnosed" vType where the file has one (the platoon
/// diagnosis's model, campaign_sumo_export.h), its base vType otherwise (said in the notes).
FilePlatoonForSumo filePlatoonForSumo(const CampaignFile& file, const std::vector<SumoAccVType>& vtypes,
                                      bool diagnosed = false);

/// The OpenACC file at path read as the campaign reads it, and its platoon laid out as above.
/// listings: the database's mixed-setting listings (io/mixed_setting_listing.h), so that each car
/// of a listed mixed run is looked up at its own setting; a path that is no listing throws
/// std::invalid_argument. The notes hold the reading's notes first, then the chain's.
FilePlatoonForSumo readFilePlatoonForSumo(const std::string& path, const std::vector<std::string>& listings,
                                          const std::vector<SumoAccVType>& vtypes, bool diagnosed);

/// sumo_replay --platoon: the OpenACC file's platoon (readFilePlatoonForSumo) replayed in SUMO
/// with the vTypes of vtype_file, SUMO's dips by position beside the package's chain of the same
/// models and the real cars'. Prints to out (notes to log), returns the JSON. Throws
/// std::runtime_error with the reason.
nlohmann::json replayFilePlatoonInSumo(const std::string& path, const std::vector<std::string>& listings,
                                       const std::string& vtype_file, bool diagnosed,
                                       const SumoReplayOptions& options, std::ostream& out, std::ostream& log);

}  // namespace acc
