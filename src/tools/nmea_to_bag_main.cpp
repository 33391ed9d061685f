// nmea_to_bag: a leader and a follower NMEA log to a bag of raw acc_identification/Sentence
// messages, stamped with a plausible receive time from each line's GNSS time, so that
// `rosbag play --clock` feeds the two drivers' topics as the receivers would have.
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/io/output_files.h"
#include "acc_identification/ros/sentence_bag_writer.h"
#include "acc_identification/tools/number_checks.h"

int main(int argc, char** argv)
{
  CLI::App app{"Every non-empty line of the two logs becomes one message (valid or not: nothing is dropped), "
               "stamped with its UTC date and time plus --latency and --sentence-spacing per further sentence of "
               "the same epoch. Lines without a time are stamped just after the previous one."};
  acc::NmeaLineTiming timing;
  std::string compression = "lz4";
  std::vector<acc::SentenceStream> streams = acc::leaderFollowerStreams();
  std::string leader_path, follower_path, bag_path;
  app.add_option("--compression", compression, "bag compression")
      ->check(CLI::IsMember({"lz4", "bz2", "none"}))
      ->capture_default_str();
  app.add_option("--latency", timing.first_sentence_latency_s, "receive time after the epoch's GNSS time [s]")
      ->check(acc::nonNegativeNumber())
      ->capture_default_str();
  app.add_option("--sentence-spacing", timing.sentence_spacing_s, "between sentences of one epoch [s]")
      ->check(acc::nonNegativeNumber())
      ->capture_default_str();
  app.add_option("--leader-topic", streams[0].topic)->capture_default_str();
  app.add_option("--follower-topic", streams[1].topic)->capture_default_str();
  app.add_option("--leader-frame", streams[0].frame_id)->capture_default_str();
  app.add_option("--follower-frame", streams[1].frame_id)->capture_default_str();
  app.add_option("LEADER", leader_path, "leader's NMEA log")->required()->check(CLI::ExistingFile);
  app.add_option("FOLLOWER", follower_path, "follower's NMEA log")->required()->check(CLI::ExistingFile);
  app.add_option("OUT", bag_path, "bag to write")->required();
  CLI11_PARSE(app, argc, argv);
  if (!acc::outputsLeaveInputsAlone({leader_path, follower_path}, {bag_path}, std::cerr))
    return 2;
  if (const std::string problem = acc::describeStreamTopicProblem(streams); !problem.empty())
  {
    std::cerr << "error: " << problem << "\n";
    return 2;
  }

  const std::string error = acc::loadSentenceStreams({leader_path, follower_path}, timing, streams, std::cerr);
  if (!error.empty())
  {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  for (const acc::SentenceStream& stream : streams)
    std::cout << "nmea_to_bag: " << (&stream == &streams[0] ? leader_path : follower_path) << ": "
              << stream.lines.size() << " lines -> " << stream.topic << "\n";
  try
  {
    const auto summary = acc::writeSentenceBag(bag_path, streams, compression);
    std::cout << "nmea_to_bag: " << summary.messages << " messages, " << (summary.end_time_s - summary.start_time_s)
              << " s -> " << bag_path << "\n";
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
