#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "acc_identification/calibration/calibrate_runs.h"
#include "acc_identification/io/acc_engagement.h"
#include "acc_identification/io/input_account.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/io/openacc_file.h"
#include "acc_identification/io/run_plausibility.h"

namespace acc
{
/// What was read from a bag, with an account of every message not used.
struct BagRuns
{
  std::vector<CarFollowingRun> runs;
  std::size_t messages = 0;
  std::size_t invalid = 0;       ///< valid == false, or non-finite values: split points
  std::size_t implausible = 0;   ///< finite values outside the plausibility bounds: split points, not used
  std::size_t out_of_order = 0;  ///< header stamp not after the previous one: not used
  std::size_t time_holes = 0;    ///< steps longer than the largest time step: split points, no message lost
  std::size_t short_pieces = 0;  ///< pieces between split points too short to simulate
  std::size_t time_resets = 0;   ///< stamps jumping back (a restarted replay): split points
  std::size_t acc_off = 0;            ///< recorded while the ACC reported itself off: split points, not used
  std::size_t acc_state_unknown = 0;  ///< engagement required but not known: split points, not used
  std::size_t engagement_reports = 0; ///< messages of the engagement topic
  std::size_t other_setting = 0;      ///< recorded at another ACC setting than the one asked for: not used
  std::size_t setting_reports = 0;    ///< messages of the setting topic
  std::size_t setting_changes = 0;    ///< reports of a new setting: each ends the runs before it
  /// The ACC setting each run was recorded at, as runs ("": none reported).
  std::vector<std::string> run_settings;
  /// "path: message N (t = T s): why", one per implausible message and per hole, worded as the
  /// CSV reader words the same values (the same checks make both).
  std::vector<std::string> problems;
};

/// What a tool reads from a bag: the samples' topic, and the ACC's engagement reports with the
/// identifier node's rule (io/acc_engagement.h). Topics with or without a leading '/'.
struct BagTopics
{
  std::string relative_state = "relative_state";  ///< acc_identification/RelativeState
  std::string acc_engaged = "acc_engaged";        ///< std_msgs/Bool; a bag without it has no source
  AccEngagementSettings engagement;
  /// std_msgs/String: the ACC's distance setting, as identifier_node reads it; runs end at a change.
  std::string acc_setting = "acc_setting";
  std::string only_setting;  ///< use only the samples recorded at this setting ("": every setting's)
};

/// Reads acc_identification/RelativeState messages of topics.relative_state from a bag recorded
/// from the nodes, timed by their header stamps (GNSS time), and splits them into runs at invalid
/// samples, at samples outside the plausibility bounds (the CSV reader's check), at holes longer
/// than bounds.max_time_step_s, and at samples recorded while the ACC was off (the latest of the
/// bag's topics.acc_engaged reports recorded at or before the sample, as the node judges by
/// arrival; on a tie, one tick of a simulated clock, the report counts as first). Runs end where
/// topics.acc_setting reports a new setting (the latest report at or before each sample is its
/// setting, in the run's name: "#2 (setting max)"); with topics.only_setting, the samples at other
/// settings are not used; runs at several settings without it are said in problems.
/// Segmenting is the identifier's sliding window, so a batch calibration of a bag sees the
/// segments the identifier node sees. Runs are named "<bag name>#<n>". Throws std::runtime_error
/// when the bag cannot be read, has no such topic or a topic of another type,
/// std::invalid_argument when the bounds or the engagement settings are unusable.
BagRuns readRunsFromBag(const std::string& path, const BagTopics& topics, const RunPlausibilityBounds& bounds);

/// readRunsFromBag() with the default plausibility bounds, engagement settings and engagement
/// topic, and holes longer than max_gap_s.
BagRuns readRunsFromBag(const std::string& path, const std::string& topic = "relative_state",
                        double max_gap_s = 0.5);

/// The account of a bag read by readRunsFromBag: messages, samples_used, runs, invalid,
/// implausible, out_of_order, time_holes, time_resets, short_pieces, acc_off,
/// acc_state_unknown, engagement_reports, other_setting, setting_changes.
InputAccount accountOfBag(const std::string& path, const BagRuns& bag);

/// What one RUN argument gave.
struct RunArgument
{
  std::vector<CarFollowingRun> runs;
  /// Its format, the OpenACC pair(s) the runs are of ("BMW_I3 behind SMART_TARGET, positions
  /// 3/2"; none for a canonical CSV and a bag) and the reader's counts.
  InputAccount account;
  /// OpenACC: each run's pair, an index into account.openacc_pairs; empty for other formats.
  std::vector<std::size_t> run_pairs;
};

/// Reads one RUN argument of the command-line tools (calibrate, diagnose): a bag (path ending in
/// .bag, read with readRunsFromBag, with an account of every message not used written to log) or
/// a canonical / OpenACC CSV (readRunFile, its notes and problems written to log). Both are split
/// at holes longer than max_gap_s. selector chooses the pair(s) of an OpenACC file (--follower,
/// --all-pairs); a bag or a canonical CSV holds one pair, so choosing a follower there is an
/// error. Throws std::runtime_error with the reason; RunReadError when the file holds no usable
/// run (a bag as a CSV).
RunArgument readRunArgument(const std::string& path, const BagTopics& topics, double max_gap_s, std::ostream& log,
                            const OpenAccPairSelector& selector);

/// readRunArgument() with the first pair of an OpenACC file; the runs only.
std::vector<CarFollowingRun> readRunArgument(const std::string& path, const std::string& topic,
                                             double max_gap_s, std::ostream& log);

/// Every RUN argument of a tool read with readRunArgument: each run with the argument it came
/// from, and each argument's account. Throws as readRunArgument, and std::runtime_error when a
/// run of one argument repeats a run of an earlier one (io/repeated_recording.h: the same
/// recording given twice, which a calibration would count twice).
struct RunArguments
{
  std::vector<CalibrationInput> runs;
  std::vector<InputAccount> inputs_read;
  std::vector<std::size_t> argument_of_run;  ///< the number of the argument each run came from
};
RunArguments readRunArguments(const std::vector<std::string>& paths, const BagTopics& topics, double max_gap_s,
                              std::ostream& log, const OpenAccPairSelector& selector);

/// Throws std::runtime_error, naming both, when a held-out run repeats a fitted one (diagnose
/// --held-out): a model scored on the recording it was fitted on is not held out.
void refuseHeldOutRepeats(const RunArguments& fitted, const RunArguments& held_out);

/// The selector of the tools' --follower NAME|POSITION and --all-pairs options (mutually
/// exclusive): all pairs, one follower, or by default the first pair.
OpenAccPairSelector pairSelectorFromOptions(const std::string& follower, bool all_pairs);

}  // namespace acc
