// Raw sentences into bags: receive stamps from the GNSS times, every line kept, both receivers
// interleaved in time; and the bundled bags in bags/ hold what bags/README.md says.
#include <gtest/gtest.h>

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <string>

#include "acc_identification/Sentence.h"
#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/gnss/nmea_writer.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/synthesis/synthesis.h"
#include "acc_identification/synthesis/synthesis_output.h"
#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/ros/sentence_bag_writer.h"
#include "acc_identification/gnss/nmea_log_timing.h"

namespace acc
{
namespace
{
std::string writeLog(const std::string& name, const std::string& content)
{
  const std::string path = testing::TempDir() + "synthesis_bag_" + name;
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

// Two epochs just before midnight of 2026-05-11 (day 20584) and one after; GGA first, without a
// date; one broken line and one line without time.
const char* kLog =
    "$GNGGA,235959.80,4507.80000,N,00827.00000,E,1,12,0.8,120.0,M,,M,,*6E\r\n"
    "$GNRMC,235959.80,A,4507.80000,N,00827.00000,E,40.000,57.30,110526,,,A*7E\r\n"
    "$GNGGA,235959.90,4507.80010,N,00827.00010,E,1,12,0.8,120.0,M,,M,,*6F\r\n"
    "garbage without time\r\n"
    "$GNRMC,235959.90,A,4507.80010,N,00827.00010,E,40.000,57.30,110526,,,A*7F\r\n"
    "$GNGGA,000000.00,4507.80020,N,00827.00020,E,1,12,0.8,120.0,M,,M,,*67\r\n";

TEST(NmeaLogTiming, StampsFromGnssTimeAcrossMidnightKeepingEveryLine)
{
  const TimedNmeaLog log = readTimedNmeaLog(writeLog("timing.nmea", kLog));
  ASSERT_EQ(log.error, "");
  ASSERT_EQ(log.lines.size(), 6u);
  EXPECT_EQ(log.untimed_lines, 1u);
  const double midnight = 20585.0 * 86400.0;  // 2026-05-12 00:00:00
  EXPECT_NEAR(log.lines[0].receive_time_s, midnight - 0.2 + 0.04, 1e-6);  // GGA before the first date
  EXPECT_NEAR(log.lines[1].receive_time_s, midnight - 0.2 + 0.06, 1e-6);  // second sentence of the epoch
  EXPECT_NEAR(log.lines[2].receive_time_s, midnight - 0.1 + 0.04, 1e-6);
  EXPECT_NEAR(log.lines[3].receive_time_s, log.lines[2].receive_time_s + 0.02, 1e-6);  // untimed
  EXPECT_EQ(log.lines[3].line, "garbage without time");
  EXPECT_NEAR(log.lines[5].receive_time_s, midnight + 0.04, 1e-6);  // the day rolled over
}

TEST(NmeaLogTiming, ALogWithoutDateIsAnErrorNotAGuess)
{
  const TimedNmeaLog log = readTimedNmeaLog(writeLog("nodate.nmea", "$GNGGA,235959.80,4507.80000,N,00827.00000,E,1,12,0.8,120.0,M,,M,,*6E\r\n"));
  EXPECT_NE(log.error.find("date"), std::string::npos);
  EXPECT_NE(readTimedNmeaLog("/nonexistent/x.nmea").error, "");
}

TEST(SentenceBag, BothReceiversInterleavedInTimeOrder)
{
  const TimedNmeaLog log = readTimedNmeaLog(writeLog("bag.nmea", kLog));
  std::vector<SentenceStream> streams{{"/leader/nmea_sentence", "leader_gnss", log.lines},
                                      {"/follower/nmea_sentence", "follower_gnss", log.lines}};
  for (TimedNmeaLine& line : streams[1].lines)
    line.receive_time_s += 0.01;
  const std::string path = testing::TempDir() + "synthesis_bag_out.bag";
  const SentenceBagSummary summary = writeSentenceBag(path, streams, "lz4");
  EXPECT_EQ(summary.messages, 12u);

  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  double previous = 0.0;
  std::map<std::string, std::vector<std::string>> lines;
  for (const rosbag::MessageInstance& instance : view)
  {
    const auto message = instance.instantiate<acc_identification::Sentence>();
    ASSERT_TRUE(message);
    EXPECT_GE(instance.getTime().toSec(), previous);
    EXPECT_EQ(instance.getTime(), message->header.stamp);
    previous = instance.getTime().toSec();
    EXPECT_EQ(message->header.frame_id, instance.getTopic() == "/leader/nmea_sentence" ? "leader_gnss" : "follower_gnss");
    EXPECT_EQ(message->header.seq, lines[instance.getTopic()].size());
    lines[instance.getTopic()].push_back(message->sentence);
  }
  ASSERT_EQ(lines["/leader/nmea_sentence"].size(), 6u);
  EXPECT_EQ(lines["/leader/nmea_sentence"][3], "garbage without time");
  EXPECT_EQ(lines["/follower/nmea_sentence"], lines["/leader/nmea_sentence"]);
  EXPECT_THROW(writeSentenceBag(path, streams, "zip"), std::runtime_error);
}

/// Every bundled bag: both topics, 10 Hz GGA + RMC that all parse, stamps in order.
// Topics a driver can subscribe to, one per receiver: nmea_to_bag wrote a topic with an empty
// name, one with a space, and both receivers on one topic, each with exit status 0.
TEST(SentenceBag, TopicsNoDriverCanTellApartAreRefused)
{
  std::vector<SentenceStream> streams = leaderFollowerStreams();
  EXPECT_EQ(describeStreamTopicProblem(streams), "");
  streams[1].topic = "follower/nmea";  // relative: fine
  EXPECT_EQ(describeStreamTopicProblem(streams), "");
  for (const char* bad : {"", "bad topic!", "/leader/nmea_sentence", "leader/nmea_sentence"})
  {
    streams[1].topic = bad;
    EXPECT_NE(describeStreamTopicProblem(streams), "") << "'" << bad << "'";
  }
}

TEST(BundledBags, HoldBothReceiversAtTenHertzWithValidSentences)
{
  for (const char* name : {"casale_part3_sentences.bag", "casale_part4_sentences.bag", "casale_part5_sentences.bag",
                           "synthetic_min_F.bag", "synthetic_max_F.bag", "zalazone_toyota_rav4_s_sentences.bag"})
  {
    SCOPED_TRACE(name);
    rosbag::Bag bag(std::string(ACC_SYNTHESIS_BAGS_DIR) + "/" + name, rosbag::bagmode::Read);
    rosbag::View view(bag);
    std::map<std::string, std::size_t> ok, bad;
    for (const rosbag::MessageInstance& instance : view)
    {
      const auto message = instance.instantiate<acc_identification::Sentence>();
      ASSERT_TRUE(message);
      NmeaSentence sentence;
      (parseNmeaSentence(message->sentence, sentence) == NmeaParseOutcome::kOk ? ok : bad)[instance.getTopic()]++;
    }
    // The ZalaZone session lays four runs 20 s apart: the holes hold no epochs.
    const double holes_s = std::string(name).rfind("zalazone", 0) == 0 ? 3 * 20.0 : 0.0;
    const double duration_s = (view.getEndTime() - view.getBeginTime()).toSec() - holes_s;
    EXPECT_GT(duration_s, 60.0);
    for (const char* topic : {"/leader/nmea_sentence", "/follower/nmea_sentence"})
    {
      EXPECT_EQ(bad[topic], 0u) << topic;
      // Two sentences per epoch at 10 Hz over the whole bag (OpenACC has a few missing rows).
      EXPECT_NEAR(static_cast<double>(ok[topic]) / duration_s, 20.0, 1.0) << topic;
    }
  }
}

std::map<std::string, std::vector<std::string>> bagLines(const std::string& path)
{
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  std::map<std::string, std::vector<std::string>> lines;
  for (const rosbag::MessageInstance& instance : view)
    lines[instance.getTopic()].push_back(instance.instantiate<acc_identification::Sentence>()->sentence);
  return lines;
}

std::vector<std::string> nmeaLines(const std::vector<GnssFix>& fixes)
{
  std::vector<std::string> lines;
  for (const GnssFix& fix : fixes)
  {
    lines.push_back(formatGga(fix, "GN"));
    lines.push_back(formatRmc(fix, "GN"));
  }
  return lines;
}

std::string readFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The synthetic bags and truth files are what the code makes today from the options in
/// bags/README.md (so a change of the synthesis without `scripts/make_bags.sh` fails here).
TEST(BundledBags, SyntheticBagsAreWhatTheSynthesisMakes)
{
  for (const char* setting : {"min", "max"})
  {
    SCOPED_TRACE(setting);
    SynthesisOptions options;
    options.profile = 'F';
    options.parameters = findNamedSetting(setting)->parameters;
    options.seed = 1;
    const SynthesizedDrive drive = synthesizeDrive(options);
    const std::string stem = std::string(ACC_SYNTHESIS_BAGS_DIR) + "/synthetic_" + setting + "_F";
    auto lines = bagLines(stem + ".bag");
    EXPECT_TRUE(lines["/leader/nmea_sentence"] == nmeaLines(drive.leader_fixes));
    EXPECT_TRUE(lines["/follower/nmea_sentence"] == nmeaLines(drive.follower_fixes));
    const std::string truth_path = testing::TempDir() + "synthesis_bag_truth.csv";
    std::string error;
    ASSERT_TRUE(writeTruthCsv(truth_path, drive.truth.run, &error)) << error;
    EXPECT_TRUE(readFile(truth_path) == readFile(stem + "_truth.csv"));
    EXPECT_TRUE(synthesisJson(options, setting) == readFile(stem + "_parameters.json"));
  }
}

/// The Casale bags hold exactly the conversion of the OpenACC files.
TEST(BundledBags, CasaleBagsAreTheConversionOfOpenAcc)
{
  for (const char* run : {"part3", "part4", "part5"})
  {
    SCOPED_TRACE(run);
    const OpenAccPairTrack file = readOpenAccPairTrack(std::string(ACC_OPENACC_DATA_DIR) + "/" + run + ".csv");
    ASSERT_EQ(file.error, "");
    auto lines = bagLines(std::string(ACC_SYNTHESIS_BAGS_DIR) + "/casale_" + run + "_sentences.bag");
    EXPECT_TRUE(lines["/leader/nmea_sentence"] == nmeaLines(openAccFixes(file, 1)));
    EXPECT_TRUE(lines["/follower/nmea_sentence"] == nmeaLines(openAccFixes(file, 2)));
  }
}

/// The ZalaZone bag holds exactly the conversion of the four excerpts, laid end to end 20 s apart
/// in this order (scripts/make_bags.sh).
TEST(BundledBags, ZalaZoneBagIsTheConversionOfTheExcerptRunsEndToEnd)
{
  std::vector<std::string> leader, follower;
  double next_start_s = std::numeric_limits<double>::quiet_NaN();
  for (const char* run : {"dynamic_part5", "dynamic_part6", "dynamic_part12", "dynamic_part14"})
  {
    SCOPED_TRACE(run);
    OpenAccPairTrack file = readOpenAccPairTrack(std::string(ACC_ZALAZONE_DATA_DIR) + "/" + run + ".csv",
                                                 OpenAccPairSelector::byFollower("TOYOTA_RAV4"));
    ASSERT_EQ(file.error, "");
    ASSERT_EQ(file.pair.leader_name, "AUDI_E_TRON");
    const double first_s = file.rows.front().time_of_day_s;
    // The script rounds the shift to the millisecond, as here.
    const double shift_s = std::isnan(next_start_s) ? 0.0 : std::round((next_start_s - first_s) * 1000.0) / 1000.0;
    for (OpenAccRow& row : file.rows)
      row.time_of_day_s += shift_s;
    next_start_s = std::round((file.rows.back().time_of_day_s + 20.0) * 1000.0) / 1000.0;
    for (const std::string& line : nmeaLines(openAccFixes(file, 1)))
      leader.push_back(line);
    for (const std::string& line : nmeaLines(openAccFixes(file, 2)))
      follower.push_back(line);
  }
  auto lines = bagLines(std::string(ACC_SYNTHESIS_BAGS_DIR) + "/zalazone_toyota_rav4_s_sentences.bag");
  EXPECT_EQ(lines["/leader/nmea_sentence"].size(), leader.size());
  EXPECT_TRUE(lines["/leader/nmea_sentence"] == leader);
  EXPECT_TRUE(lines["/follower/nmea_sentence"] == follower);
}

}  // namespace
}  // namespace acc
