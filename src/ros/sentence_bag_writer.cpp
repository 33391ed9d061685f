#include "acc_identification/ros/sentence_bag_writer.h"

#include <rosbag/bag.h>
#include <ros/names.h>
#include <ros/time.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "acc_identification/Sentence.h"
#include "acc_identification/ros/ros_time.h"

namespace acc
{
namespace
{
rosbag::compression::CompressionType compressionType(const std::string& name)
{
  if (name == "lz4")
    return rosbag::compression::LZ4;
  if (name == "bz2")
    return rosbag::compression::BZ2;
  if (name == "none")
    return rosbag::compression::Uncompressed;
  throw std::runtime_error("unknown bag compression '" + name + "' (lz4, bz2 or none)");
}

struct Entry
{
  double stamp_s;
  ros::Time stamp;
  std::size_t stream;
  std::size_t line;
};
}  // namespace

SentenceBagSummary writeSentenceBag(const std::string& path, const std::vector<SentenceStream>& streams,
                                    const std::string& compression)
{
  const auto type = compressionType(compression);
  std::vector<Entry> entries;
  for (std::size_t s = 0; s < streams.size(); ++s)
    for (std::size_t i = 0; i < streams[s].lines.size(); ++i)
    {
      const double stamp_s = streams[s].lines[i].receive_time_s;
      // The package's one conversion (ros/ros_time.h); 0 would be "unset", so it is no stamp either.
      ros::Time stamp;
      if (!toRosTime(stamp_s, stamp) || stamp.isZero())
        throw std::runtime_error(streams[s].topic + ": line " + std::to_string(i + 1) + " has no valid time stamp");
      entries.push_back({stamp_s, stamp, s, i});
    }
  // Stable: lines of one stream with equal stamps keep their file order.
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.stamp_s < b.stamp_s; });

  rosbag::Bag bag;
  try
  {
    bag.open(path, rosbag::bagmode::Write);
    bag.setCompression(type);
    std::vector<std::uint32_t> seq(streams.size(), 0);
    for (const Entry& entry : entries)
    {
      const SentenceStream& stream = streams[entry.stream];
      acc_identification::Sentence message;
      message.header.seq = seq[entry.stream]++;
      message.header.stamp = entry.stamp;
      message.header.frame_id = stream.frame_id;
      message.sentence = stream.lines[entry.line].line;
      bag.write(stream.topic, message.header.stamp, message);
    }
    bag.close();
  }
  catch (const rosbag::BagException& e)
  {
    throw std::runtime_error("cannot write bag " + path + ": " + e.what());
  }
  SentenceBagSummary summary;
  summary.messages = entries.size();
  if (!entries.empty())
  {
    summary.start_time_s = entries.front().stamp_s;
    summary.end_time_s = entries.back().stamp_s;
  }
  return summary;
}

std::string describeStreamTopicProblem(const std::vector<SentenceStream>& streams)
{
  for (std::size_t i = 0; i < streams.size(); ++i)
  {
    std::string why;
    if (streams[i].topic.empty())
      return "a receiver's topic is empty: rosbag would write a topic no driver can subscribe to";
    if (!ros::names::validate(streams[i].topic, why))
      return "topic '" + streams[i].topic + "': " + why;
    for (std::size_t j = 0; j < i; ++j)
      if (ros::names::resolve("/", streams[j].topic, false) == ros::names::resolve("/", streams[i].topic, false))
        return "topic '" + streams[i].topic + "' given for two receivers: their sentences would be one stream";
  }
  return "";
}

std::vector<SentenceStream> leaderFollowerStreams()
{
  return {{"/leader/nmea_sentence", "leader_gnss", {}}, {"/follower/nmea_sentence", "follower_gnss", {}}};
}

std::string loadSentenceStreams(const std::vector<std::string>& logs, const NmeaLineTiming& timing,
                                std::vector<SentenceStream>& streams, std::ostream& log)
{
  for (std::size_t i = 0; i < logs.size() && i < streams.size(); ++i)
  {
    TimedNmeaLog timed = readTimedNmeaLog(logs[i], timing);
    if (!timed.error.empty())
      return timed.error;
    if (timed.untimed_lines > 0)
      log << "warning: " << logs[i] << ": " << timed.untimed_lines
          << " line(s) without a readable time, stamped after the previous line\n";
    streams[i].lines = std::move(timed.lines);
  }
  return "";
}

}  // namespace acc
