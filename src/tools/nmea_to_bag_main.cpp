// nmea_to_bag: a leader and a follower NMEA log to a bag of raw acc_identification/Sentence
// messages, stamped with a plausible receive time from each line's GNSS time, so that
// `rosbag play --clock` feeds the two drivers' topics as the receivers would have.
#include <iostream>
#include <string>

#include "acc_identification/command_line.h"
#include "acc_identification/ros/sentence_bag_writer.h"


namespace
{
const char* kUsage =
    "usage: nmea_to_bag [--compression lz4|bz2|none] [--latency S] [--sentence-spacing S]\n"
    "                   [--leader-topic /leader/nmea_sentence] [--follower-topic /follower/nmea_sentence]\n"
    "                   [--leader-frame leader_gnss] [--follower-frame follower_gnss]\n"
    "                   LEADER.nmea FOLLOWER.nmea OUT.bag\n"
    "  Every non-empty line becomes one message (valid or not: nothing is dropped), stamped with\n"
    "  its UTC date and time plus --latency (0.04 s) and --sentence-spacing (0.02 s) per further\n"
    "  sentence of the same epoch. Lines without a time are stamped just after the previous one.\n";
}  // namespace

int main(int argc, char** argv)
{
  acc::CommandLine cli({"compression", "latency", "sentence-spacing", "leader-topic", "follower-topic", "leader-frame",
                        "follower-frame"},
                       {"help"});
  if (!cli.parse(argc, argv) || cli.has("help") || cli.positional().size() != 3)
  {
    std::cerr << (cli.error().empty() ? "" : "error: " + cli.error() + "\n") << kUsage;
    return cli.has("help") ? 0 : 2;
  }
  acc::NmeaLineTiming timing;
  timing.first_sentence_latency_s = cli.number("latency").value_or(timing.first_sentence_latency_s);
  timing.sentence_spacing_s = cli.number("sentence-spacing").value_or(timing.sentence_spacing_s);
  if (!cli.error().empty() || timing.first_sentence_latency_s < 0.0 || timing.sentence_spacing_s < 0.0)
  {
    std::cerr << "error: " << (cli.error().empty() ? "latency and spacing must not be negative" : cli.error()) << "\n"
              << kUsage;
    return 2;
  }
  const auto& files = cli.positional();
  std::vector<acc::SentenceStream> streams{
      {cli.value("leader-topic").value_or("/leader/nmea_sentence"), cli.value("leader-frame").value_or("leader_gnss"), {}},
      {cli.value("follower-topic").value_or("/follower/nmea_sentence"),
       cli.value("follower-frame").value_or("follower_gnss"),
       {}}};
  for (int i = 0; i < 2; ++i)
  {
    acc::TimedNmeaLog log = acc::readTimedNmeaLog(files[i], timing);
    if (!log.error.empty())
    {
      std::cerr << "error: " << log.error << "\n";
      return 1;
    }
    if (log.untimed_lines > 0)
      std::cerr << "warning: " << files[i] << ": " << log.untimed_lines
                << " line(s) without a readable time, stamped after the previous line\n";
    std::cout << "nmea_to_bag: " << files[i] << ": " << log.lines.size() << " lines -> " << streams[i].topic << "\n";
    streams[i].lines = std::move(log.lines);
  }
  try
  {
    const auto summary = acc::writeSentenceBag(files[2], streams, cli.value("compression").value_or("lz4"));
    std::cout << "nmea_to_bag: " << summary.messages << " messages, " << (summary.end_time_s - summary.start_time_s)
              << " s -> " << files[2] << "\n";
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
