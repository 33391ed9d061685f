#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "acc_identification/gnss/nmea_log_timing.h"

namespace acc
{
/// The lines of one receiver and where they go in the bag.
struct SentenceStream
{
  std::string topic;     ///< e.g. "/leader/nmea_sentence"
  std::string frame_id;  ///< e.g. "leader_gnss"
  std::vector<TimedNmeaLine> lines;
};

/// What was written.
struct SentenceBagSummary
{
  std::size_t messages = 0;
  double start_time_s = 0.0;  ///< first and last receive stamps [Unix s]
  double end_time_s = 0.0;
};

/// The two receivers' streams as the drivers subscribe to them: /leader/nmea_sentence (frame
/// leader_gnss) and /follower/nmea_sentence (follower_gnss), without lines yet.
std::vector<SentenceStream> leaderFollowerStreams();

/// Why the streams' topics cannot be subscribed to apart ("" when they can): a name ROS does not
/// take (empty, a space: rosbag wrote it, and no driver could subscribe) or one topic for two
/// receivers.
std::string describeStreamTopicProblem(const std::vector<SentenceStream>& streams);

/// Each log (readTimedNmeaLog with timing) into the lines of its stream, logs[i] into streams[i];
/// lines without a readable time are counted in a warning on log. "" when all were read, else the
/// first error.
std::string loadSentenceStreams(const std::vector<std::string>& logs, const NmeaLineTiming& timing,
                                std::vector<SentenceStream>& streams, std::ostream& log);

/// Writes every line of every stream as an acc_identification/Sentence message, header.stamp and
/// bag time = the line's receive time, in time order across the streams (so `rosbag play
/// --clock` replays the two receivers interleaved as they would arrive), header.seq counting
/// per stream. compression: "lz4", "bz2" or "none". Throws std::runtime_error with the reason
/// when the bag cannot be written, a compression is unknown, or a stamp is not a valid ROS time.
SentenceBagSummary writeSentenceBag(const std::string& path, const std::vector<SentenceStream>& streams,
                                    const std::string& compression);

}  // namespace acc
