#pragma once

#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/ros/run_bag_reader.h"

namespace acc
{
/// The run inputs calibrate and diagnose take alike: RUN files (canonical CSV, OpenACC CSV, bags
/// of RelativeState), the bags' topics and engagement rule, the hole that splits a run, and which
/// OpenACC pair(s) to read.
/// One declaration, so that the tools' options and their help cannot drift apart.
struct RunInputOptions
{
  std::vector<std::string> paths;
  BagTopics bag;  ///< what is read from a bag: the options bind its fields
  double max_gap_s = 0.5;
  std::string follower;
  bool all_pairs = false;

  /// Declares RUN..., --topic, --acc-engaged-topic, --require-acc-engaged, --acc-engaged-timeout,
  /// --acc-setting-topic, --acc-setting, --max-gap, --follower and --all-pairs (mutually exclusive);
  /// all_pairs_means says what reading every pair does in this tool. required: RUN must be given.
  void declare(CLI::App& app, const std::string& all_pairs_means, bool required);

  /// readRunArguments of the options; the readers' notes on log. Throws as it does.
  RunArguments read(std::ostream& log) const;
  /// Other files read with the same options.
  RunArguments readPaths(const std::vector<std::string>& other_paths, std::ostream& log) const;
  /// read(), and the files kept aside (diagnose --held-out) read with the same options; throws as
  /// they do, and as refuseHeldOutRepeats when a held-out run repeats a fitted one.
  std::pair<RunArguments, RunArguments> readWithHeldOut(const std::vector<std::string>& held_out_paths,
                                                        std::ostream& log) const;
};

}  // namespace acc
