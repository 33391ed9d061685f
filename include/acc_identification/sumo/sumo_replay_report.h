#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/model/car_following_run.h"
#include "acc_identification/sumo/sumo_replay.h"

namespace acc
{
/// What sumo_replay does with the runs (segments) of one RUN argument: the vTypes named by ids
/// (none: the file's first ACC vType) read from vtype_file; one id: each segment replayed as a
/// pair, the RMSEs pooled over segments (by samples) at the top of the JSON; several: each
/// segment's leader replayed with the platoon behind it. A segment SUMO cannot step through
/// (nonUniformStepReason) is skipped, printed and listed in the JSON's skipped_segments. Prints
/// the text to out, returns the JSON. Throws std::runtime_error (an id not in the file, no ACC
/// vType, no segment SUMO can replay, SUMO failing).
nlohmann::json replayRunInSumo(const std::vector<CarFollowingRun>& runs, const std::string& vtype_file,
                               const std::vector<std::string>& ids, const SumoReplayOptions& options,
                               std::ostream& out);

}  // namespace acc
