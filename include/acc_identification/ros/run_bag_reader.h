#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "acc_identification/car_following_run.h"

namespace acc_identification
{
/// What was read from a bag, with an account of every message not used.
struct BagRuns
{
  std::vector<CarFollowingRun> runs;
  std::size_t messages = 0;
  std::size_t invalid = 0;       ///< valid == false, or non-finite values: split points
  std::size_t out_of_order = 0;  ///< header stamp not after the previous one: not used
  std::size_t short_pieces = 0;  ///< pieces between split points too short to simulate
  std::size_t time_resets = 0;   ///< stamps jumping back (a restarted replay): split points
};

/// Reads acc_identification/RelativeState messages of topic (with or without a leading '/')
/// from a bag recorded from the nodes, timed by their header stamps (GNSS time), and splits them
/// into runs at invalid samples and at holes longer than max_gap_s. Runs are named
/// "<bag name>#<n>". Throws std::runtime_error when the bag cannot be read or has no such topic.
BagRuns readRunsFromBag(const std::string& path, const std::string& topic = "relative_state",
                        double max_gap_s = 0.5);

/// Reads one RUN argument of the command-line tools (calibrate, diagnose): a bag (path ending in
/// .bag, read with readRunsFromBag, with an account of every message not used written to log) or
/// a canonical / OpenACC CSV (readRuns). Throws std::runtime_error with the reason.
std::vector<CarFollowingRun> readRunArgument(const std::string& path, const std::string& topic,
                                             double max_gap_s, std::ostream& log);

}  // namespace acc_identification
