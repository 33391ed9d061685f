#include "acc_identification/ros/run_bag_reader.h"
#include "acc_identification/io/run_csv.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <std_msgs/Bool.h>
#include <std_msgs/String.h>

#include "acc_identification/RelativeState.h"
#include "acc_identification/calibration/sliding_window.h"
#include "acc_identification/io/run_csv.h"

namespace acc
{
namespace
{
/// "path: message N (t = T s): why". Fixed notation: GNSS stamps are ~1e9 s and differ in tenths.
std::string describeAtMessage(const std::string& path, std::size_t message_number, double time_s,
                              const std::string& why)
{
  std::ostringstream line;
  line << path << ": message " << message_number << " (t = " << std::fixed << std::setprecision(3) << time_s
       << " s): " << why;
  return line.str();
}

bool hasFiniteValues(const WindowSample& sample)
{
  return std::isfinite(sample.space_gap_m) && std::isfinite(sample.follower_speed_mps) &&
         std::isfinite(sample.leader_speed_mps);
}

/// The same check as the CSV reader's. Non-finite values are left to the window (counted invalid).
std::string describeImplausibleSample(const WindowSample& sample, const RunPlausibilityBounds& bounds)
{
  if (!sample.valid || !hasFiniteValues(sample))
  {
    return "";
  }
  return describeImplausibleValue(sample.space_gap_m, sample.follower_speed_mps, sample.leader_speed_mps, bounds);
}

/// Feeds a bag's samples, in order, to a window longer than any bag, which does the segmenting
/// (at invalid samples and at holes), and accounts in result for every sample it does not use.
class BagSegmenter
{
public:
  BagSegmenter(std::string path, const RunPlausibilityBounds& bounds, const BagTopics& topics, BagRuns& result)
    : path_(std::move(path))
    , bounds_(bounds)
    , engagement_(topics.engagement)
    , only_setting_(topics.only_setting)
    // A batch reader: time resets are handled below, before the window sees them, and a jump
    // ahead is a hole like any other (no confirmation to wait for: nothing leaves this window).
    , window_(std::numeric_limits<double>::infinity(), bounds.max_time_step_s, 2,
              std::numeric_limits<double>::infinity())
    , result_(result)
  {
  }

  /// An engagement report recorded at record_time_s (the bag's clock).
  void reportEngagement(double record_time_s, bool engaged)
  {
    ++result_.engagement_reports;
    engagement_.report(record_time_s, engaged);
  }

  /// A report of the ACC's setting: a new one ends the runs so far, which were another setting's.
  void reportSetting(const std::string& setting)
  {
    ++result_.setting_reports;
    if (setting == setting_)
    {
      return;
    }
    ++result_.setting_changes;
    moveSegments();
    window_.clear();
    segment_open_ = false;
    setting_ = setting;
  }

  /// A sample recorded at record_time_s (the bag's clock), stamped sample.time_s (GNSS time).
  void add(WindowSample sample, double record_time_s)
  {
    ++result_.messages;
    if (!window_.empty() && sample.time_s < window_.endTimeS() - bounds_.max_time_step_s)
    {
      // A time reset inside the bag (a replay restarted): keep what came before as runs of its own.
      moveSegments();
      ++result_.time_resets;
      window_.clear();
      segment_open_ = false;
    }
    const AccEngagement::Judgement engagement = engagement_.judge(record_time_s);
    const std::string implausible = describeImplausibleSample(sample, bounds_);
    if (!implausible.empty() || engagement.use != AccEngagement::Use::kUsed)
    {
      sample.valid = false;  // a split point for the window, never used: as a rejected CSV row
    }
    if (engagement.use != AccEngagement::Use::kUsed)
    {
      noteNotEngaged(sample.time_s, engagement);
      window_.add(sample);  // a split point, whatever else is wrong with it
      return;
    }
    if (!only_setting_.empty() && setting_ != only_setting_)
    {
      ++result_.other_setting;  // not the setting asked for: not used
      sample.valid = false;
      window_.add(sample);
      segment_open_ = false;
      return;
    }
    switch (window_.add(sample))
    {
      case SlidingWindow::AddResult::kInvalid: noteSplitPoint(sample.time_s, implausible); break;
      case SlidingWindow::AddResult::kNonFinite: noteSplitPoint(sample.time_s, ""); break;
      case SlidingWindow::AddResult::kOutOfOrder: ++result_.out_of_order; break;
      case SlidingWindow::AddResult::kRestarted:  // handled above, before the window was cleared
      case SlidingWindow::AddResult::kJumpedAhead:  // never: no forward jump is held here
      case SlidingWindow::AddResult::kHeld:
      case SlidingWindow::AddResult::kAdded: noteAdded(sample.time_s); break;
    }
  }

  /// Moves the segments still in the window to result; call once, after the last sample.
  void finish() { moveSegments(); }

private:
  /// Counted by kind; said once for each stretch of samples the ACC did not drive.
  void noteNotEngaged(double time_s, const AccEngagement::Judgement& engagement)
  {
    segment_open_ = false;
    ++(engagement.use == AccEngagement::Use::kAccOff ? result_.acc_off : result_.acc_state_unknown);
    if (engagement.starts_stretch)
    {
      report(time_s, engagement_.describe(engagement.use) + "; messages not used from here until the ACC is "
                                                            "reported engaged, run split");
    }
  }

  void noteSplitPoint(double time_s, const std::string& implausible)
  {
    segment_open_ = false;
    if (implausible.empty())
    {
      ++result_.invalid;
      return;
    }
    ++result_.implausible;
    report(time_s, implausible + "; message not used, run split here");
  }

  /// The window splits at a hole by itself (the same step against the same bound); this accounts
  /// for it with the CSV reader's check and words.
  void noteAdded(double time_s)
  {
    const std::string hole = segment_open_ ? describeTimeHole(segment_end_s_, time_s, bounds_) : "";
    if (!hole.empty())
    {
      ++result_.time_holes;
      report(time_s, hole + "; run split");
    }
    segment_open_ = true;
    segment_end_s_ = time_s;
  }

  void report(double time_s, const std::string& why)
  {
    result_.problems.push_back(describeAtMessage(path_, result_.messages, time_s, why));
  }

  void moveSegments()
  {
    std::size_t short_pieces = 0;
    for (CarFollowingRun& run : window_.segments(&short_pieces))
    {
      result_.runs.push_back(std::move(run));
      result_.run_settings.push_back(setting_);
    }
    result_.short_pieces += short_pieces;
  }

  std::string path_;
  RunPlausibilityBounds bounds_;
  AccEngagement engagement_;
  std::string only_setting_;  ///< the setting whose samples are used ("": every setting's)
  std::string setting_;       ///< the latest reported setting ("": none yet)
  SlidingWindow window_;
  BagRuns& result_;
  bool segment_open_ = false;   ///< whether the window's newest segment has a valid sample
  double segment_end_s_ = 0.0;  ///< its newest sample: what a hole is measured from
};

std::string bagName(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  if (name.size() > 4 && name.substr(name.size() - 4) == ".bag")
  {
    name = name.substr(0, name.size() - 4);
  }
  return name;
}

/// Every topic of the bag with its type and message count, for a message that helps choose one:
/// "/relative_state (acc_identification/RelativeState, 57 messages), ...", or "none (empty bag)".
std::string describeBagTopics(const rosbag::Bag& bag)
{
  std::map<std::string, std::string> types;
  rosbag::View everything(bag);
  for (const rosbag::ConnectionInfo* connection : everything.getConnections())
  {
    types.emplace(connection->topic, connection->datatype);
  }
  std::string listed;
  for (const auto& [topic, type] : types)
  {
    rosbag::View on_topic(bag, rosbag::TopicQuery(topic));  // size() is not const
    listed += (listed.empty() ? "" : ", ") + topic + " (" + type + ", " + std::to_string(on_topic.size()) +
              " message" + (on_topic.size() == 1 ? "" : "s") + ")";
  }
  return listed.empty() ? "none (empty bag)" : listed;
}

/// How to get samples from a bag without them on the topic asked: another topic of the type, or,
/// for a drive's raw sentences or fixes only (drive.launch records those), the chain to make them.
std::string whatToDoWithoutRelativeState(const rosbag::Bag& bag)
{
  rosbag::View everything(bag);
  for (const rosbag::ConnectionInfo* connection : everything.getConnections())
    if (connection->datatype == "acc_identification/RelativeState")
      return " (choose the one of type acc_identification/RelativeState with --topic)";
  return ". It holds no acc_identification/RelativeState at all: replay it through the chain and record "
         "the samples (roslaunch acc_identification replay.launch bag:=BAG antenna_offset_m:=M, with "
         "rosbag record /relative_state), or pair the receivers' logs with nmea_to_csv";
}

/// The topic's names as a bag may hold them: as given and with a leading '/' (or without it).
std::vector<std::string> topicSpellings(const std::string& topic)
{
  const std::string bare = topic.empty() || topic[0] != '/' ? topic : topic.substr(1);
  return {bare, "/" + bare};
}

/// A report of topic recorded at record_time_s (the bag's clock).
template <typename Value>
struct BagReport
{
  double record_time_s = 0.0;
  Value value{};
};

/// The reports of the bag on topic (none when topic is empty or absent), by record time; a topic
/// of another type than Message is an error that names the option choosing it.
template <typename Message, typename Value = decltype(Message::data)>
std::vector<BagReport<Value>> readReports(rosbag::Bag& bag, const std::string& path, const std::string& topic,
                                       const std::string& type_name, const std::string& option)
{
  std::vector<BagReport<Value>> reports;
  if (topic.empty())
  {
    return reports;
  }
  for (const rosbag::MessageInstance& instance : rosbag::View(bag, rosbag::TopicQuery(topicSpellings(topic))))
  {
    const auto report = instance.instantiate<Message>();
    if (!report)
    {
      throw std::runtime_error("bag '" + path + "': topic '" + topic + "' is " + instance.getDataType() + ", not " +
                               type_name + " (choose the topic with " + option + ", or none with " + option + " '')");
    }
    reports.push_back({instance.getTime().toSec(), report->data});
  }
  std::stable_sort(reports.begin(), reports.end(),
                   [](const BagReport<Value>& a, const BagReport<Value>& b) { return a.record_time_s < b.record_time_s; });
  return reports;
}

/// The reports the bag holds, applied to a segmenter in record order up to a time.
class ReportsInOrder
{
public:
  ReportsInOrder(rosbag::Bag& bag, const std::string& path, const BagTopics& topics)
    : engagement_(readReports<std_msgs::Bool>(bag, path, topics.acc_engaged, "std_msgs/Bool", "--acc-engaged-topic"))
    , setting_(readReports<std_msgs::String>(bag, path, topics.acc_setting, "std_msgs/String", "--acc-setting-topic"))
  {
  }

  /// Applies every report recorded at or before record_time_s not applied yet.
  void applyUntil(double record_time_s, BagSegmenter& segmenter)
  {
    for (; next_engagement_ < engagement_.size() && engagement_[next_engagement_].record_time_s <= record_time_s;
         ++next_engagement_)
    {
      segmenter.reportEngagement(engagement_[next_engagement_].record_time_s, engagement_[next_engagement_].value);
    }
    for (; next_setting_ < setting_.size() && setting_[next_setting_].record_time_s <= record_time_s; ++next_setting_)
    {
      segmenter.reportSetting(setting_[next_setting_].value);
    }
  }

private:
  std::vector<BagReport<std::uint8_t>> engagement_;
  std::vector<BagReport<std::string>> setting_;
  std::size_t next_engagement_ = 0;
  std::size_t next_setting_ = 0;
};
}  // namespace

BagRuns readRunsFromBag(const std::string& path, const BagTopics& topics, const RunPlausibilityBounds& bounds)
{
  const std::string bounds_problem = describeBoundsProblem(bounds);
  if (!bounds_problem.empty())
  {
    throw std::invalid_argument("readRunsFromBag: unusable plausibility bounds: " + bounds_problem);
  }
  rosbag::Bag bag;
  try
  {
    bag.open(path, rosbag::bagmode::Read);
  }
  catch (const rosbag::BagException& error)
  {
    throw std::runtime_error("cannot read bag '" + path + "': " + error.what());
  }
  const std::vector<std::string> samples_topic = topicSpellings(topics.relative_state);
  if (rosbag::View(bag, rosbag::TopicQuery(samples_topic)).size() == 0)
  {
    throw std::runtime_error("bag '" + path + "' has no messages on topic '" + topics.relative_state +
                             "'; its topics: " + describeBagTopics(bag) + whatToDoWithoutRelativeState(bag));
  }
  BagRuns result;
  BagSegmenter segmenter(path, bounds, topics, result);
  ReportsInOrder reports(bag, path, topics);
  for (const rosbag::MessageInstance& instance : rosbag::View(bag, rosbag::TopicQuery(samples_topic)))
  {
    const auto message = instance.instantiate<acc_identification::RelativeState>();
    if (!message)
    {
      throw std::runtime_error("bag '" + path + "': topic '" + topics.relative_state +
                               "' is not acc_identification/RelativeState");
    }
    // The latest report recorded at or before the sample: as the node received them, and on a
    // tie (one tick of a simulated clock) the report first, whichever the bag lists first.
    const double record_time_s = instance.getTime().toSec();
    reports.applyUntil(record_time_s, segmenter);
    segmenter.add({message->header.stamp.toSec(), message->space_gap_m, message->follower_speed_mps,
                   message->leader_speed_mps, static_cast<bool>(message->valid)},
                  record_time_s);
  }
  reports.applyUntil(std::numeric_limits<double>::infinity(), segmenter);  // counted
  segmenter.finish();
  const std::string name = bagName(path);
  std::set<std::string> settings;
  for (std::size_t i = 0; i < result.runs.size(); ++i)
  {
    const std::string& setting = result.run_settings[i];
    result.runs[i].name = name + "#" + std::to_string(i + 1) + (setting.empty() ? "" : " (setting " + setting + ")");
    settings.insert(setting.empty() ? "not reported" : setting);
  }
  if (settings.size() > 1)
  {
    std::string listed;
    for (const std::string& setting : settings)
      listed += (listed.empty() ? "" : ", ") + setting;
    result.problems.push_back(path + ": runs at " + std::to_string(settings.size()) + " ACC settings (" + listed +
                              "): one model fitted across them mixes them; choose one with --acc-setting");
  }
  return result;
}

BagRuns readRunsFromBag(const std::string& path, const std::string& topic, double max_gap_s)
{
  RunPlausibilityBounds bounds;
  bounds.max_time_step_s = max_gap_s;
  BagTopics topics;
  topics.relative_state = topic;
  return readRunsFromBag(path, topics, bounds);
}

InputAccount accountOfBag(const std::string& path, const BagRuns& bag)
{
  InputAccount account;
  account.path = path;
  account.format = "bag";
  account.counts = {{"messages", bag.messages},       {"samples_used", sampleCount(bag.runs)},
                    {"runs", bag.runs.size()},        {"invalid", bag.invalid},
                    {"implausible", bag.implausible}, {"out_of_order", bag.out_of_order},
                    {"time_holes", bag.time_holes},   {"time_resets", bag.time_resets},
                    {"short_pieces", bag.short_pieces}, {"acc_off", bag.acc_off},
                    {"acc_state_unknown", bag.acc_state_unknown}, {"engagement_reports", bag.engagement_reports},
                    {"other_setting", bag.other_setting}, {"setting_changes", bag.setting_changes}};
  return account;
}

namespace
{
/// ", N recorded with the ACC off, M with its state unknown (K engagement reports)" where the bag
/// has an engagement source or a sample was not used for want of one; "" otherwise.
std::string describeEngagementCounts(const BagRuns& bag)
{
  if (bag.engagement_reports == 0 && bag.acc_state_unknown == 0)
  {
    return "";
  }
  return ", " + std::to_string(bag.acc_off) + " recorded with the ACC off, " + std::to_string(bag.acc_state_unknown) +
         " with its state unknown (" + std::to_string(bag.engagement_reports) + " engagement reports)";
}

/// ", N at another ACC setting (K setting changes)" where the bag reports its settings; "" otherwise.
std::string describeSettingCounts(const BagRuns& bag)
{
  if (bag.setting_reports == 0)
  {
    return "";
  }
  return ", " + std::to_string(bag.other_setting) + " at another ACC setting (" + std::to_string(bag.setting_changes) +
         " setting changes)";
}
}  // namespace

RunArgument readRunArgument(const std::string& path, const BagTopics& topics, double max_gap_s, std::ostream& log,
                            const OpenAccPairSelector& selector)
{
  const std::string bag_suffix = ".bag";
  const bool is_bag = path.size() >= bag_suffix.size() &&
                      path.compare(path.size() - bag_suffix.size(), bag_suffix.size(), bag_suffix) == 0;
  RunArgument argument;
  if (!is_bag && !topics.only_setting.empty())
    throw std::runtime_error(path + ": --acc-setting chooses among the settings a bag's setting topic reports; a CSV "
                                    "is read whole (an OpenACC file holds one setting, its Distance_setting line): "
                                    "give --acc-setting with bags only");
  if (!is_bag)
  {
    RunPlausibilityBounds bounds;
    bounds.max_time_step_s = max_gap_s;
    RunFileContents contents = readRunFile(path, bounds, selector);
    argument.account = accountOfRunFile(path, contents);
    if (!contents.pairs.empty())
      argument.run_pairs = contents.run_pairs;
    argument.runs = reportAndTakeRuns(path, contents, log);
    return argument;
  }
  if (selector.kind == OpenAccPairSelector::Kind::kFollower)
  {
    throw std::runtime_error(path + ": " + selector.describe() + " chosen, but a bag of RelativeState holds one pair");
  }
  RunPlausibilityBounds bounds;
  bounds.max_time_step_s = max_gap_s;
  BagRuns bag = readRunsFromBag(path, topics, bounds);
  for (const std::string& problem : bag.problems)
  {
    log << "warning: " << problem << "\n";
  }
  log << path << ": " << bag.messages << " messages, " << bag.invalid << " invalid, " << bag.implausible
      << " outside the plausibility bounds, " << bag.out_of_order << " out of order, " << bag.time_holes
      << " holes in time, " << bag.time_resets << " time resets, " << bag.short_pieces << " pieces too short"
      << describeEngagementCounts(bag) << describeSettingCounts(bag) << " -> " << bag.runs.size() << " runs"
      << describeCoarseSteps(bag.time_holes, bag.messages > 0 ? bag.messages - 1 : 0) << "\n";
  // As a CSV with no usable row: bad input, not valid data that cannot be fitted.
  if (bag.runs.empty())
    throw RunReadError(path + ": no usable run (" + std::to_string(bag.messages) + " messages; each one not used is " +
                       "named above)");
  argument.account = accountOfBag(path, bag);
  argument.runs = std::move(bag.runs);
  return argument;
}

std::vector<CarFollowingRun> readRunArgument(const std::string& path, const std::string& topic, double max_gap_s,
                                             std::ostream& log)
{
  BagTopics topics;
  topics.relative_state = topic;
  return readRunArgument(path, topics, max_gap_s, log, OpenAccPairSelector::first()).runs;
}

namespace
{
/// describeRepeatedInput over these runs: by their arguments, or with `held_out` given, the fitted
/// runs as one input and the held-out ones as another.
std::string describeRepeat(const RunArguments& runs, const RunArguments* held_out = nullptr)
{
  if (held_out == nullptr)
    return describeRepeatedInput(runs.runs, runs.argument_of_run);
  std::vector<CalibrationInput> all = runs.runs;
  all.insert(all.end(), held_out->runs.begin(), held_out->runs.end());
  std::vector<std::size_t> input_of(runs.runs.size(), 0);
  input_of.resize(all.size(), 1);
  return describeRepeatedInput(all, input_of);
}
}  // namespace

RunArguments readRunArguments(const std::vector<std::string>& paths, const BagTopics& topics, double max_gap_s,
                              std::ostream& log, const OpenAccPairSelector& selector)
{
  RunArguments arguments;
  for (std::size_t number = 0; number < paths.size(); ++number)
  {
    RunArgument argument = readRunArgument(paths[number], topics, max_gap_s, log, selector);
    arguments.inputs_read.push_back(argument.account);
    for (CarFollowingRun& run : argument.runs)
    {
      arguments.runs.push_back({std::move(run), paths[number]});
      arguments.argument_of_run.push_back(number);
    }
  }
  if (const std::string repeat = describeRepeat(arguments); !repeat.empty())
    throw std::runtime_error(repeat + ": give each recording once (a fit would count it twice)");
  return arguments;
}

void refuseHeldOutRepeats(const RunArguments& fitted, const RunArguments& held_out)
{
  if (const std::string repeat = describeRepeat(fitted, &held_out); !repeat.empty())
    throw std::runtime_error("a held-out run repeats a fitted one: " + repeat +
                             ": a model scored on the recording it was fitted on is not held out");
}

OpenAccPairSelector pairSelectorFromOptions(const std::string& follower, bool all_pairs)
{
  if (all_pairs)
  {
    return OpenAccPairSelector::all();
  }
  return follower.empty() ? OpenAccPairSelector::first() : OpenAccPairSelector::byFollower(follower);
}

}  // namespace acc
