// Epoch assembly and dates: sentences in, one fix per epoch out; the whole decoder on a log.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "acc_identification/gnss/gnss_velocity.h"
#include "acc_identification/gnss/nmea_decoder.h"
#include "acc_identification/gnss/nmea_log.h"
#include "acc_identification/gnss/nmea_writer.h"
#include "acc_identification/gnss/utc_date.h"

using acc::GnssFix;

namespace
{
constexpr double kPi = 3.14159265358979323846;

struct Decoded
{
  std::vector<GnssFix> fixes;
  std::vector<acc::NmeaParseOutcome> outcomes;
  acc::NmeaStatistics statistics;
};

/// Feeds every chunk, then ends the stream.
Decoded decode(const std::vector<std::string>& chunks)
{
  Decoded out;
  acc::NmeaDecoder decoder([&](std::string_view, acc::NmeaParseOutcome o) { out.outcomes.push_back(o); },
                           [&](const GnssFix& fix) { out.fixes.push_back(fix); });
  double t = 100.0;
  for (const auto& chunk : chunks)
    decoder.feed(chunk.data(), chunk.size(), t += 0.01);
  decoder.finish(t);
  out.statistics = decoder.statistics();
  return out;
}

std::string joinLines(const std::vector<std::string>& lines)
{
  std::string text;
  for (const auto& line : lines)
    text += line + "\r\n";
  return text;
}

double at(int year, unsigned month, unsigned day, double time_of_day_s)
{
  return acc::daysFromCivil(year, month, day) * acc::kSecondsPerDay + time_of_day_s;
}
}  // namespace

TEST(GnssEpoch, OneFixPerEpochCombiningSentences)
{
  const auto d = decode({joinLines({
      "$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,A*57",
      "$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*06",
      "$GPGGA,083559.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*52",
      "$GPGST,083559.00,1.8,,,,1.7,1.3,2.2*76",
      "$GPZDA,083559.00,09,12,2002,00,00*6E",
  })});
  ASSERT_EQ(d.fixes.size(), 1u);
  const GnssFix& fix = d.fixes[0];
  EXPECT_TRUE(fix.has_date);
  EXPECT_NEAR(fix.gnss_time_s, at(2002, 12, 9, 8 * 3600 + 35 * 60 + 59.0), 1e-6);
  EXPECT_NEAR(fix.latitude_deg, 47 + 17.11399 / 60, 1e-12);  // GGA wins over RMC
  EXPECT_DOUBLE_EQ(fix.altitude_m, 499.6);
  EXPECT_NEAR(fix.speed_over_ground_mps, 0.004 * 1852 / 3600, 1e-12);  // RMC came first
  EXPECT_NEAR(fix.course_rad, 77.52 * kPi / 180, 1e-12);
  EXPECT_EQ(fix.fix_quality, 1);
  EXPECT_EQ(fix.satellites_used, 8);
  EXPECT_DOUBLE_EQ(fix.latitude_sigma_m, 1.7);
  EXPECT_DOUBLE_EQ(fix.geoid_separation_m, 48.0);
  EXPECT_EQ(fix.valid_fields, 255u);
  EXPECT_DOUBLE_EQ(fix.receive_time_s, 100.01);
}

// A second sentence of one type and talker in one epoch is counted, not silently dropped: a log
// with every line twice, or a second GGA whose position differs (the first is kept, as the ranks
// keep the first of equal sources). Another talker's GGA is no repeat.
TEST(GnssEpoch, ARepeatedSentenceInAnEpochIsCountedAndTheFirstKept)
{
  const std::string gga = "$GPGGA,083559.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*52";
  const std::string moved = "$GPGGA,083559.00,4717.12399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*51";
  const std::string rmc = "$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,A*57";
  const auto twice = decode({joinLines({rmc, rmc, gga, gga})});
  ASSERT_EQ(twice.fixes.size(), 1u);
  EXPECT_EQ(twice.statistics.repeated_sentences, 2u);
  EXPECT_NE(twice.statistics.summary().find("2 repeated sentences"), std::string::npos) << twice.statistics.summary();
  const auto conflicting = decode({joinLines({rmc, gga, moved})});
  ASSERT_EQ(conflicting.fixes.size(), 1u);
  EXPECT_EQ(conflicting.statistics.repeated_sentences, 1u);
  EXPECT_NEAR(conflicting.fixes[0].latitude_deg, 47 + 17.11399 / 60, 1e-12);
  const auto clean = decode({joinLines({rmc, gga})});
  EXPECT_EQ(clean.statistics.repeated_sentences, 0u);
  EXPECT_EQ(clean.statistics.summary().find("repeated"), std::string::npos);
}

TEST(GnssEpoch, TwoSentencesInOneReadAndOneSplitAcrossReads)
{
  const std::string a = "$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B\r\n";
  const std::string b = "$GPGGA,092725.10,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5A\r\n";
  const std::string c = "$GPGGA,092725.20,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*59\r\n";
  const auto d = decode({a + b.substr(0, 20), b.substr(20) + c});
  ASSERT_EQ(d.fixes.size(), 3u);
  EXPECT_NEAR(d.fixes[1].gnss_time_s - d.fixes[0].gnss_time_s, 0.1, 1e-9);
  EXPECT_FALSE(d.fixes[0].has_date);
  EXPECT_EQ(d.statistics.sentences_ok, 3u);
}

TEST(GnssEpoch, BadSentencesAreCountedByReasonNeverFatal)
{
  const auto d = decode({joinLines({
      "$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5C",  // bad checksum
      "$GPGGA,092725.00,4717.11399,N,00833.9",                                       // truncated
      "$GPGSV,1,1,00*79",                                                            // unsupported
      "$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B",
  }) + "\x01\x02garbage"});
  EXPECT_EQ(d.statistics.lines, 4u);
  EXPECT_EQ(d.statistics.bad_checksum, 1u);
  EXPECT_EQ(d.statistics.malformed, 1u);
  EXPECT_EQ(d.statistics.unsupported, 1u);
  EXPECT_EQ(d.statistics.sentences_ok, 1u);
  EXPECT_EQ(d.statistics.stray_bytes, 9u);
  EXPECT_EQ(d.fixes.size(), 1u);
  EXPECT_EQ(d.outcomes.size(), 4u);
}

TEST(GnssEpoch, TimeWithoutDateAtStartUpThenDate)
{
  const auto d = decode({joinLines({
      "$GNGGA,235959.80,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*47",
      "$GNRMC,235959.80,A,4717.11399,N,00833.91590,E,10.000,90.00,,,,A,V*01",
      "$GNRMC,235959.90,A,4717.11399,N,00833.91590,E,10.000,90.00,311220,,,A,V*03",
      "$GNGGA,000000.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4E",  // GGA before RMC
      "$GNRMC,000000.00,A,4717.11399,N,00833.91590,E,10.000,90.00,010121,,,A,V*0B",
      "$GNGGA,000000.10,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4F",  // no RMC at all
  })});
  ASSERT_EQ(d.fixes.size(), 4u);
  EXPECT_FALSE(d.fixes[0].has_date);
  EXPECT_FALSE(d.fixes[0].has(GnssFix::kValidDate));
  EXPECT_NEAR(d.fixes[0].gnss_time_s, 86399.8, 1e-6);  // time of day only
  EXPECT_TRUE(d.fixes[1].has_date);
  EXPECT_NEAR(d.fixes[1].gnss_time_s, at(2020, 12, 31, 86399.9), 1e-6);
  EXPECT_NEAR(d.fixes[2].gnss_time_s, at(2021, 1, 1, 0.0), 1e-6);
  EXPECT_NEAR(d.fixes[3].gnss_time_s, at(2021, 1, 1, 0.1), 1e-6);
}

TEST(GnssEpoch, MidnightRolloverWithoutDateSentence)
{
  // Only GGA after a single dated RMC: the day must advance at the wrap of the time of day.
  const auto d = decode({joinLines({
      "$GNRMC,235959.90,A,4717.11399,N,00833.91590,E,10.000,90.00,311220,,,A,V*03",
      "$GNGGA,000000.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4E",
      "$GNGGA,000000.10,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4F",
  })});
  ASSERT_EQ(d.fixes.size(), 3u);
  EXPECT_NEAR(d.fixes[1].gnss_time_s - d.fixes[0].gnss_time_s, 0.1, 1e-6);
  EXPECT_NEAR(d.fixes[2].gnss_time_s, at(2021, 1, 1, 0.1), 1e-6);
}

// A log that never carries a date (GGA and VTG only) across midnight: its times go on above a day
// instead of jumping back 86,400 s, which the pairing took for a receiver reset (leaving the
// epoch before midnight unpaired and the run split there). Undated, still: has_date false.
TEST(GnssEpoch, MidnightWithoutAnyDateKeepsTimeIncreasing)
{
  const auto d = decode({joinLines({
      "$GNGGA,235959.80,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*47",
      "$GNGGA,235959.90,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*46",
      "$GNGGA,000000.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4E",
      "$GNGGA,000000.10,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4F",
  })});
  ASSERT_EQ(d.fixes.size(), 4u);
  EXPECT_NEAR(d.fixes[0].gnss_time_s, 86399.8, 1e-6);
  EXPECT_NEAR(d.fixes[2].gnss_time_s, 86400.0, 1e-6);
  EXPECT_NEAR(d.fixes[3].gnss_time_s, 86400.1, 1e-6);
  EXPECT_FALSE(d.fixes[3].has_date);
  // A late sentence of the day before, after midnight, keeps its own day.
  acc::UtcDateTracker tracker;
  EXPECT_DOUBLE_EQ(tracker.undatedTimeS(86399.9), 86399.9);
  EXPECT_DOUBLE_EQ(tracker.undatedTimeS(0.1), 86400.1);
  EXPECT_DOUBLE_EQ(tracker.undatedTimeS(86399.95), 86399.95);
}

TEST(GnssEpoch, DateLaggingTheRolloverIsCorrected)
{
  // The RMC of 00:00:00.00 still says 31 Dec (a receiver's date one sentence late).
  const auto d = decode({joinLines({
      "$GNRMC,235959.90,A,4717.11399,N,00833.91590,E,10.000,90.00,311220,,,A,V*03",
      "$GNRMC,000000.00,A,4717.11399,N,00833.91590,E,10.000,90.00,311220,,,A,V*0B",
      "$GNRMC,000000.10,A,4717.11399,N,00833.91590,E,10.000,90.00,010121,,,A,V*0A",
  })});
  ASSERT_EQ(d.fixes.size(), 3u);
  EXPECT_NEAR(d.fixes[1].gnss_time_s, at(2021, 1, 1, 0.0), 1e-6);
  EXPECT_NEAR(d.fixes[2].gnss_time_s, at(2021, 1, 1, 0.1), 1e-6);
  EXPECT_EQ(d.statistics.date_lag_corrections, 1u);
}

TEST(GnssEpoch, UntimedSentencesAloneAreCountedNotSilentlyDropped)
{
  const auto d = decode({joinLines({"$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*06"})});
  EXPECT_TRUE(d.fixes.empty());
  EXPECT_EQ(d.statistics.epochs_without_time, 1u);
}

TEST(GnssEpoch, IdleFlushCompletesTheEpochWithoutWaitingForTheNext)
{
  std::vector<GnssFix> fixes;
  acc::NmeaDecoder decoder(nullptr, [&](const GnssFix& fix) { fixes.push_back(fix); });
  const std::string gga = "$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B\r\n";
  decoder.feed(gga.data(), gga.size(), 10.0);
  decoder.flushIfIdle(10.01, 0.05);
  EXPECT_TRUE(fixes.empty());
  decoder.flushIfIdle(10.06, 0.05);
  EXPECT_EQ(fixes.size(), 1u);
}

TEST(GnssEpoch, EnuVelocityFromCourse)
{
  GnssFix fix;
  fix.speed_over_ground_mps = 10.0;
  fix.course_rad = kPi / 2;  // due east
  fix.valid_fields = GnssFix::kValidSpeed | GnssFix::kValidCourse;
  acc::EnuVelocity v;
  ASSERT_TRUE(acc::enuVelocity(fix, v));
  EXPECT_NEAR(v.east_mps, 10.0, 1e-12);
  EXPECT_NEAR(v.north_mps, 0.0, 1e-12);
  fix.course_rad = kPi;  // due south
  ASSERT_TRUE(acc::enuVelocity(fix, v));
  EXPECT_NEAR(v.north_mps, -10.0, 1e-12);
  fix.valid_fields = GnssFix::kValidSpeed;  // moving without a course: unknown direction
  EXPECT_FALSE(acc::enuVelocity(fix, v));
}

TEST(NmeaLog, DriveFixture)
{
  const auto log = acc::readNmeaLog(std::string(ACC_GNSS_TEST_DATA) + "/drive_10s.nmea");
  ASSERT_TRUE(log.error.empty()) << log.error;
  ASSERT_EQ(log.fixes.size(), 100u);
  EXPECT_EQ(log.statistics.lines, 600u);
  EXPECT_EQ(log.statistics.unsupported, 99u);  // GSA
  EXPECT_EQ(log.statistics.bad_checksum, 1u);
  EXPECT_EQ(log.statistics.stray_bytes, 2u);
  int dated = 0;
  for (const auto& fix : log.fixes)
    dated += fix.has_date;
  EXPECT_EQ(dated, 97);
  const GnssFix& last = log.fixes.back();
  EXPECT_NEAR(last.gnss_time_s, at(2020, 10, 27, 10 * 3600 + 15 * 60 + 39.9), 1e-6);
  EXPECT_NEAR(last.speed_over_ground_mps, 10.0 + 0.5 * 9.9, 0.001 / 3.6);
  EXPECT_NEAR(last.course_rad, kPi / 4, 1e-9);
  EXPECT_DOUBLE_EQ(last.altitude_m, 159.9);
  // 10 m/s * 9.9 s + 0.25 m/s^2 * 9.9^2 along 45 deg: north component in degrees of latitude.
  const double north_m = (99.0 + 0.25 * 9.9 * 9.9) / std::sqrt(2.0);
  EXPECT_NEAR((last.latitude_deg - 45.13) * kPi / 180 * 6378137.0, north_m, 0.02);
  EXPECT_EQ(last.valid_fields, 255u);
}

TEST(NmeaLog, MissingFileIsAnError)
{
  const auto log = acc::readNmeaLog("/nonexistent/x.nmea");
  EXPECT_FALSE(log.error.empty());
  EXPECT_TRUE(log.fixes.empty());
}

// ---- Receivers of other makes: epochs quoted from gpsd's regression logs (BSD-2-Clause, see
// test/data/nmea_captures/ATTRIBUTION.md).

TEST(GnssEpochReceivers, PositionFromGnsAndGllWhenThereIsNoGga)
{
  // Ericsson GRU 04: ZDA, GNS, VTG, GLL and proprietary sentences; GGA only once a minute.
  const auto d = decode({joinLines({
      "$GNZDA,213712.000,12,02,2026,,*4B",
      "$GNGNS,213712.000,4111.59903,N,11156.54809,W,AANN,13,0.93,01482.5,-016.5,,*52",
      "$GNVTG,000.0,T,348.3,M,000.0,N,000.1,K,A*30",
      "$GNGLL,4111.59903,N,11156.54809,W,213712.000,A,A*50",
      "$PTNLRBA,1,0*56",
      "$GNZDA,213713.000,12,02,2026,,*4A",
  })});
  ASSERT_EQ(d.fixes.size(), 2u);
  const GnssFix& fix = d.fixes[0];
  EXPECT_TRUE(fix.has(GnssFix::kValidPosition | GnssFix::kValidAltitude | GnssFix::kValidDate |
                      GnssFix::kValidSatellites | GnssFix::kValidHdop | GnssFix::kValidSpeed));
  EXPECT_NEAR(fix.gnss_time_s, at(2026, 2, 12, 21 * 3600 + 37 * 60 + 12.0), 1e-6);
  EXPECT_NEAR(fix.latitude_deg, 41 + 11.59903 / 60, 1e-12);
  EXPECT_DOUBLE_EQ(fix.altitude_m, 1482.5);
  EXPECT_EQ(fix.satellites_used, 13);
  EXPECT_EQ(fix.fix_quality, 1);
  EXPECT_NEAR(fix.speed_over_ground_mps, 0.1 / 3.6, 1e-12);  // VTG's km/h (gpsd reads its knots: 0)
}

TEST(GnssEpochReceivers, CombinedTalkerCountsAllSatellites)
{
  // Telit PLS83-W: one GGA, VTG and RMC per constellation (GP, GA) and a combined GNGNS. Each
  // GGA counts only its constellation's satellites; the epoch used 14.
  const auto d = decode({joinLines({
      "$GPGGA,043539.00,4333.190206,N,00127.618380,E,1,05,1.3,250.8,M,50.0,M,,*62",
      "$GAGGA,043539.00,4333.190206,N,00127.618380,E,1,01,1.3,250.8,M,50.0,M,,*77",
      "$GNGNS,043539.00,4333.190206,N,00127.618380,E,AAAAN,14,1.3,250.8,50.0,,,V*62",
      "$GPVTG,,T,1.7,M,0.0,N,0.0,K,A*0B",
      "$GAVTG,,T,1.7,M,0.0,N,0.0,K,A*1A",
      "$GPRMC,043539.00,A,4333.190206,N,00127.618380,E,0.0,,040925,1.7,W,A,V*7C",
      "$GARMC,043539.00,A,4333.190206,N,00127.618380,E,0.0,,040925,1.7,W,A,V*6D",
  })});
  ASSERT_EQ(d.fixes.size(), 1u);
  const GnssFix& fix = d.fixes[0];
  EXPECT_EQ(fix.satellites_used, 14);
  EXPECT_NEAR(fix.latitude_deg, 43 + 33.190206 / 60, 1e-12);
  EXPECT_DOUBLE_EQ(fix.altitude_m, 250.8);
  EXPECT_DOUBLE_EQ(fix.geoid_separation_m, 50.0);
  EXPECT_NEAR(fix.gnss_time_s, at(2025, 9, 4, 4 * 3600 + 35 * 60 + 39.0), 1e-6);
  EXPECT_DOUBLE_EQ(fix.speed_over_ground_mps, 0.0);
  EXPECT_FALSE(fix.has(GnssFix::kValidCourse));  // empty at standstill
}

TEST(GnssEpochReceivers, SimulatorModeGivesNoPosition)
{
  // Garmin GPSmap 76S in simulator mode: RMC V (mode S), GGA quality 8.
  const auto d = decode({joinLines({
      "$GPRMC,125106,V,3854.5087,N,07726.4523,W,0.0,0.0,241011,10.5,W,S*28",
      "$GPGGA,125106,3854.5087,N,07726.4523,W,8,10,2.0,268.8,M,-33.9,M,,*7F",
      "$GPGLL,3854.5087,N,07726.4523,W,125106,V,S*55",
  })});
  ASSERT_EQ(d.fixes.size(), 1u);
  EXPECT_FALSE(d.fixes[0].has(GnssFix::kValidPosition));
  EXPECT_FALSE(d.fixes[0].has(GnssFix::kValidAltitude));
  EXPECT_EQ(d.fixes[0].fix_quality, 8);
  // Written: an RMC that says A (no mode field) does not bring the simulated position back.
  const auto e = decode({joinLines({
      "$GPRMC,125106,A,3854.5087,N,07726.4523,W,0.0,0.0,241011,10.5,W*40",
      "$GPGGA,125106,3854.5087,N,07726.4523,W,8,10,2.0,268.8,M,-33.9,M,,*7F",
  })});
  ASSERT_EQ(e.fixes.size(), 1u);
  EXPECT_FALSE(e.fixes[0].has(GnssFix::kValidPosition));
  EXPECT_EQ(e.fixes[0].fix_quality, 8);
}

TEST(GnssEpochReceivers, EveryLineOfAMixedStreamIsAccountedFor)
{
  // "$$" starts (ST Teseo), AIS lines (Saab R4), a line's tail at the start, a short GGA.
  const std::string input = "4.4343,N,01025.5386,E,200002,A,D*48\r\n"
                            "$$GNRMC,135806.000,A,4723.00484,N,00045.88150,E,0.5,120.9,210325,,,A,C*11\r\n"
                            "!AIVDM,1,1,,B,13aGhtw0R<OJf=6LgQ?Ad1FF05`L,0*24\n"
                            "$GPGGA,130711,5012.790800,N,00806.879600,W,2,,,,,,,*6A\n";
  const auto d = decode({input});
  EXPECT_EQ(d.statistics.lines, 3u);
  EXPECT_EQ(d.statistics.sentences_ok, 2u);
  EXPECT_EQ(d.statistics.unsupported, 1u);
  EXPECT_EQ(d.statistics.malformed, 0u);
  EXPECT_EQ(d.statistics.stray_lines, 1u);
  EXPECT_EQ(d.statistics.inputLines(), 4u);
  EXPECT_EQ(d.fixes.size(), 2u);
}

namespace
{
/// GGA and RMC of epoch k (10 Hz) of a receiver moving at 10 + k m/s: each fix's speed says its
/// epoch, so a speed with the wrong position shows.
struct EpochLines
{
  std::string gga, rmc;
};

EpochLines epochLines(int k)
{
  GnssFix fix;
  fix.gnss_time_s = at(2024, 5, 12, 36000.0 + 0.1 * k);
  fix.has_date = true;
  fix.latitude_deg = 47.0 + 1e-5 * k;
  fix.longitude_deg = 8.0;
  fix.altitude_m = 400.0;
  fix.fix_quality = 1;
  fix.satellites_used = 12;
  fix.hdop = 0.8;
  fix.speed_over_ground_mps = 10.0 + k;
  fix.course_rad = 1.0;
  fix.valid_fields = GnssFix::kValidPosition | GnssFix::kValidAltitude | GnssFix::kValidSatellites |
                     GnssFix::kValidHdop | GnssFix::kValidSpeed | GnssFix::kValidCourse | GnssFix::kValidDate;
  return {acc::formatGga(fix) + "\r\n", acc::formatRmc(fix) + "\r\n"};
}

/// A decoder with the given reorder wait whose fixes go to fixes.
struct ReorderingLink
{
  std::vector<GnssFix> fixes;
  acc::NmeaDecoder decoder{nullptr, [this](const GnssFix& fix) { fixes.push_back(fix); }};
  explicit ReorderingLink(double wait_s) { decoder.setReorderWait(wait_s); }
  void send(const std::string& line, double t) { decoder.feed(line.data(), line.size(), t); }
};

void expectWhole(const std::vector<GnssFix>& fixes, int first_epoch)
{
  for (std::size_t i = 0; i < fixes.size(); ++i)
  {
    const int k = first_epoch + static_cast<int>(i);
    EXPECT_NEAR(fixes[i].gnss_time_s, at(2024, 5, 12, 36000.0 + 0.1 * k), 1e-6) << "fix " << i;
    EXPECT_TRUE(fixes[i].valid_fields & GnssFix::kValidPosition) << "fix " << i;
    EXPECT_TRUE(fixes[i].valid_fields & GnssFix::kValidSpeed) << "epoch " << k << " lost its RMC";
    EXPECT_NEAR(fixes[i].speed_over_ground_mps, 10.0 + k, 1e-3) << "epoch " << k;
  }
}
}  // namespace

// Over a radio link with jitter an epoch's RMC can come after the next epoch's GGA. Without a
// reorder wait each such epoch is one fix without speed (the pairing's leader speed is missing)
// and its late RMC is counted, never a second fix of its time; with one, every epoch is one
// whole fix, in order.
TEST(GnssEpochReorder, AnRmcAfterTheNextEpochsGgaJoinsItsOwnEpoch)
{
  for (double wait_s : {0.0, 0.5})
  {
    ReorderingLink link(wait_s);
    double t = 0.0;
    for (int k = 0; k < 5; ++k)  // in order: the stream's epochs carry position and speed
    {
      link.send(epochLines(k).gga, t += 0.01);
      link.send(epochLines(k).rmc, t += 0.01);
    }
    for (int k = 5; k < 15; ++k)  // from epoch 5 on each RMC comes after the next epoch's GGA
    {
      link.send(epochLines(k).gga, t += 0.05);
      if (k > 5)
        link.send(epochLines(k - 1).rmc, t += 0.05);
    }
    link.send(epochLines(14).rmc, t += 0.05);
    link.decoder.finish(t);
    const acc::NmeaStatistics s = link.decoder.statistics();
    if (wait_s == 0.0)
    {
      ASSERT_EQ(link.fixes.size(), 15u);
      for (std::size_t k = 0; k < link.fixes.size(); ++k)
      {
        EXPECT_EQ((link.fixes[k].valid_fields & GnssFix::kValidSpeed) != 0, k < 5 || k == 14) << "epoch " << k;
      }
      EXPECT_EQ(s.late_sentences_after_fix, 9u);  // epochs 5 to 13
      continue;
    }
    ASSERT_EQ(link.fixes.size(), 15u);
    expectWhole(link.fixes, 0);
    EXPECT_EQ(s.late_sentences_merged, 9u);  // epochs 5 to 13; epoch 14's RMC finds it still current
    EXPECT_EQ(s.late_sentences_after_fix, 0u);
  }
}

// The idle flush (a pause in the bytes) must not complete an epoch whose RMC is still on the way,
// until the reorder wait has passed; a sentence later than that is counted and makes no second
// fix of its epoch.
TEST(GnssEpochReorder, TheIdleFlushWaitsForALateSentenceThenGivesUp)
{
  ReorderingLink link(0.3);
  double t = 0.0;
  for (int k = 0; k < 4; ++k)
  {
    link.send(epochLines(k).gga, t += 0.01);
    link.send(epochLines(k).rmc, t += 0.01);
    link.decoder.flushEpoch(t += 0.06);
  }
  ASSERT_EQ(link.fixes.size(), 4u);
  link.send(epochLines(4).gga, t += 0.03);
  link.decoder.flushEpoch(t += 0.06);  // idle, but its RMC is missing: waits
  EXPECT_EQ(link.fixes.size(), 4u);
  link.send(epochLines(4).rmc, t += 0.1);  // 0.16 s after the GGA: in time
  link.decoder.flushEpoch(t += 0.06);
  ASSERT_EQ(link.fixes.size(), 5u);
  expectWhole(link.fixes, 0);

  link.send(epochLines(5).gga, t += 0.03);
  link.decoder.flushEpoch(t += 0.1);
  EXPECT_EQ(link.fixes.size(), 5u);
  link.decoder.flushEpoch(t += 0.25);  // past the wait: published without speed
  ASSERT_EQ(link.fixes.size(), 6u);
  EXPECT_FALSE(link.fixes.back().valid_fields & GnssFix::kValidSpeed);
  link.send(epochLines(5).rmc, t += 0.1);  // too late
  link.decoder.finish(t);
  EXPECT_EQ(link.fixes.size(), 6u);
  EXPECT_EQ(link.decoder.statistics().late_sentences_after_fix, 1u);
}

// A receiver whose epochs never carry speed (GGA only) is not held back: nothing is missing from
// what its epochs usually carry.
TEST(GnssEpochReorder, AStreamWithoutSpeedIsNotHeldBack)
{
  ReorderingLink link(0.5);
  double t = 0.0;
  for (int k = 0; k < 6; ++k)
  {
    link.send(epochLines(k).gga, t += 0.1);
    link.decoder.flushEpoch(t += 0.06);
    EXPECT_EQ(link.fixes.size(), static_cast<std::size_t>(k + 1)) << "epoch " << k << " waited";
  }
}

// A sentence without its checksum field is malformed (the parser requires "*hh"), and counted
// apart, so that a whole log written without checksums is explained rather than called malformed
// line by line. Fails if such lines are not counted, or lines with a bad checksum are.
TEST(GnssEpoch, SentencesWithoutAChecksumAreCountedApart)
{
  const auto d = decode({joinLines({
      "$GNGGA,000000.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,",
      "$GNGGA,000000.10,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*00",
      "$GNGGA,000000.20,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4C",
  })});
  EXPECT_EQ(d.statistics.malformed, 1u);
  EXPECT_EQ(d.statistics.without_checksum, 1u);
  EXPECT_EQ(d.statistics.bad_checksum, 1u);
  EXPECT_EQ(d.fixes.size(), 1u);
  EXPECT_NE(d.statistics.summary().find("1 malformed (1 without a checksum *hh"), std::string::npos)
      << d.statistics.summary();
  EXPECT_TRUE(acc::lacksChecksumField("$GPVTG,77.52,T,,M,0.004,N,0.008,K,A"));
  EXPECT_FALSE(acc::lacksChecksumField("$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*06"));
  EXPECT_FALSE(acc::lacksChecksumField("binary noise"));
}
