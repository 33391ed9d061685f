#include "acc_identification/ros/run_bag_reader.h"

#include <limits>
#include <stdexcept>

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "acc_identification/RelativeState.h"
#include "acc_identification/calibration/sliding_window.h"
#include "acc_identification/io/run_csv.h"

namespace acc_identification
{
BagRuns readRunsFromBag(const std::string& path, const std::string& topic, double max_gap_s)
{
  rosbag::Bag bag;
  try
  {
    bag.open(path, rosbag::bagmode::Read);
  }
  catch (const rosbag::BagException& error)
  {
    throw std::runtime_error("cannot read bag '" + path + "': " + error.what());
  }
  const std::string bare = topic.empty() || topic[0] != '/' ? topic : topic.substr(1);
  rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{bare, "/" + bare}));
  if (view.size() == 0)
  {
    throw std::runtime_error("bag '" + path + "' has no messages on topic '" + topic + "'");
  }
  // A window longer than any bag does the segmenting: split at invalid samples and at holes.
  SlidingWindow all(std::numeric_limits<double>::infinity(), max_gap_s, 2);
  BagRuns result;
  for (const rosbag::MessageInstance& instance : view)
  {
    const auto message = instance.instantiate<RelativeState>();
    if (!message)
    {
      throw std::runtime_error("bag '" + path + "': topic '" + topic + "' is not acc_identification/RelativeState");
    }
    ++result.messages;
    const WindowSample sample{message->header.stamp.toSec(), message->space_gap_m, message->follower_speed_mps,
                              message->leader_speed_mps, static_cast<bool>(message->valid)};
    if (!all.empty() && sample.time_s < all.endTimeS() - max_gap_s)
    {
      // A time reset inside the bag (a replay restarted): keep what came before as runs of its own.
      std::size_t short_pieces = 0;
      for (CarFollowingRun& run : all.segments(&short_pieces))
      {
        result.runs.push_back(std::move(run));
      }
      result.short_pieces += short_pieces;
      ++result.time_resets;
      all.clear();
    }
    switch (all.add(sample))
    {
      case SlidingWindow::AddResult::kInvalid:
      case SlidingWindow::AddResult::kNonFinite: ++result.invalid; break;
      case SlidingWindow::AddResult::kOutOfOrder: ++result.out_of_order; break;
      case SlidingWindow::AddResult::kRestarted:  // handled above, before the window was cleared
      case SlidingWindow::AddResult::kAdded: break;
    }
  }
  std::size_t short_pieces = 0;
  for (CarFollowingRun& run : all.segments(&short_pieces))
  {
    result.runs.push_back(std::move(run));
  }
  result.short_pieces += short_pieces;
  const auto slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  if (name.size() > 4 && name.substr(name.size() - 4) == ".bag")
  {
    name = name.substr(0, name.size() - 4);
  }
  for (std::size_t i = 0; i < result.runs.size(); ++i)
  {
    result.runs[i].name = name + "#" + std::to_string(i + 1);
  }
  return result;
}

std::vector<CarFollowingRun> readRunArgument(const std::string& path, const std::string& topic,
                                             double max_gap_s, std::ostream& log)
{
  const std::string bag_suffix = ".bag";
  const bool is_bag = path.size() >= bag_suffix.size() &&
                      path.compare(path.size() - bag_suffix.size(), bag_suffix.size(), bag_suffix) == 0;
  if (!is_bag)
  {
    return readRuns(path);
  }
  BagRuns bag = readRunsFromBag(path, topic, max_gap_s);
  log << path << ": " << bag.messages << " messages, " << bag.invalid << " invalid, " << bag.out_of_order
      << " out of order, " << bag.time_resets << " time resets, " << bag.short_pieces
      << " pieces too short -> " << bag.runs.size() << " runs\n";
  return std::move(bag.runs);
}

}  // namespace acc_identification
