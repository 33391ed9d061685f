// Parser tests on real u-blox sentences (u-blox protocol specification examples) and on
// sentences written for the cases below; every checksum is the real one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "acc_identification/gnss/nmea_fields.h"
#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/gnss/utc_date.h"

using acc::NmeaParseOutcome;
using acc::NmeaSentenceType;

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kKnot = 1852.0 / 3600.0;

NmeaParseOutcome parse(const std::string& line, acc::NmeaSentence& s) { return acc::parseNmeaSentence(line, s); }
}  // namespace

TEST(NmeaChecksum, XorOfBody)
{
  EXPECT_EQ(acc::nmeaChecksumValue("GPVTG,77.52,T,,M,0.004,N,0.008,K,A"), 0x06);
  EXPECT_EQ(acc::nmeaChecksumValue(""), 0);
}

TEST(NmeaParser, UbloxGga)
{
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B", s),
            NmeaParseOutcome::kOk);
  EXPECT_EQ(s.type, NmeaSentenceType::kGga);
  EXPECT_NEAR(s.time_of_day_s, 9 * 3600 + 27 * 60 + 25.0, 1e-9);
  EXPECT_NEAR(s.latitude_deg, 47 + 17.11399 / 60, 1e-12);
  EXPECT_NEAR(s.longitude_deg, 8 + 33.91590 / 60, 1e-12);
  EXPECT_EQ(s.fix_quality, 1);
  EXPECT_EQ(s.satellites, 8);
  EXPECT_DOUBLE_EQ(s.hdop, 1.01);
  EXPECT_DOUBLE_EQ(s.altitude_m, 499.6);
  EXPECT_DOUBLE_EQ(s.geoid_separation_m, 48.0);
  EXPECT_FALSE(s.day.has_value());
}

TEST(NmeaParser, UbloxRmcWithDate)
{
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,A*57", s),
            NmeaParseOutcome::kOk);
  EXPECT_EQ(s.type, NmeaSentenceType::kRmc);
  EXPECT_NEAR(s.speed_mps, 0.004 * kKnot, 1e-12);
  EXPECT_NEAR(s.course_rad, 77.52 * kPi / 180, 1e-12);
  ASSERT_TRUE(s.day.has_value());
  EXPECT_EQ(*s.day, acc::daysFromCivil(2002, 12, 9));
  EXPECT_EQ(s.fix_quality, 1);
}

TEST(NmeaParser, UbloxVtgGstZdaPubx)
{
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*06", s), NmeaParseOutcome::kOk);
  EXPECT_TRUE(std::isnan(s.time_of_day_s));
  EXPECT_NEAR(s.speed_mps, 0.008 / 3.6, 1e-12);  // km/h field, the finer one
  EXPECT_NEAR(s.course_rad, 77.52 * kPi / 180, 1e-12);

  ASSERT_EQ(parse("$GPGST,082356.00,1.8,,,,1.7,1.3,2.2*7E", s), NmeaParseOutcome::kOk);
  EXPECT_DOUBLE_EQ(s.latitude_sigma_m, 1.7);
  EXPECT_DOUBLE_EQ(s.longitude_sigma_m, 1.3);
  EXPECT_DOUBLE_EQ(s.altitude_sigma_m, 2.2);

  ASSERT_EQ(parse("$GPZDA,082710.00,16,09,2002,00,00*64", s), NmeaParseOutcome::kOk);
  EXPECT_EQ(*s.day, acc::daysFromCivil(2002, 9, 16));
  EXPECT_NEAR(s.time_of_day_s, 8 * 3600 + 27 * 60 + 10.0, 1e-9);

  ASSERT_EQ(parse("$PUBX,00,081350.00,4717.113210,N,00833.915187,E,546.589,G3,2.1,2.0,0.007,77.52,0.007,,0.92,"
                  "1.19,0.77,9,0,0*5F",
                  s),
            NmeaParseOutcome::kOk);
  EXPECT_EQ(s.type, NmeaSentenceType::kPubx00);
  EXPECT_NEAR(s.latitude_deg, 47 + 17.113210 / 60, 1e-12);
  EXPECT_NEAR(s.latitude_sigma_m, 2.1 / std::sqrt(2.0), 1e-12);
  EXPECT_DOUBLE_EQ(s.altitude_sigma_m, 2.0);
  EXPECT_EQ(s.satellites, 9);
  EXPECT_NEAR(s.speed_mps, 0.007 / 3.6, 1e-12);
}

TEST(NmeaParser, EveryTalker)
{
  const char* lines[] = {
      "$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B",
      "$GNGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*45",
      "$GLGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*47",
      "$GAGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4A",
      "$GBGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*49",
      "$BDGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4A",
      "$GQGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5A",
      "$GIGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*42",
  };
  for (const char* line : lines)
  {
    acc::NmeaSentence s;
    ASSERT_EQ(parse(line, s), NmeaParseOutcome::kOk) << line;
    EXPECT_EQ(std::string(s.talker, 2), std::string(line + 1, 2));
    EXPECT_NEAR(s.latitude_deg, 47 + 17.11399 / 60, 1e-12);
  }
}

TEST(NmeaParser, BadChecksum)
{
  acc::NmeaSentence s;
  EXPECT_EQ(parse("$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5C", s),
            NmeaParseOutcome::kBadChecksum);
  // One changed digit, checksum of the original.
  EXPECT_EQ(parse("$GPGGA,092725.00,4717.11399,N,00833.91591,E,1,08,1.01,499.6,M,48.0,M,,*5B", s),
            NmeaParseOutcome::kBadChecksum);
  EXPECT_EQ(parse("$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*06", s), NmeaParseOutcome::kOk);
  EXPECT_EQ(parse("$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*6", s), NmeaParseOutcome::kMalformed);
  EXPECT_EQ(parse("$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*0G", s), NmeaParseOutcome::kMalformed);
  // Ten letters lower-cased flip bit 5 ten times: the checksum still matches, the address does not.
  EXPECT_EQ(parse("$gpvtg,77.52,t,,m,0.004,n,0.008,k,a*06", s), NmeaParseOutcome::kMalformed);
  EXPECT_EQ(parse("$GPVTG,77.52,t,,M,0.004,N,0.008,K,A*06", s), NmeaParseOutcome::kBadChecksum);
}

TEST(NmeaParser, LowerCaseChecksumAndLineEndingsAccepted)
{
  acc::NmeaSentence s;
  EXPECT_EQ(parse("$GPGST,082356.00,1.8,,,,1.7,1.3,2.2*7E" "\r\n", s), NmeaParseOutcome::kOk);
  EXPECT_EQ(parse("$PUBX,00,081350.00,4717.113210,N,00833.915187,E,546.589,G3,2.1,2.0,0.007,77.52,0.007,,0.92,"
                  "1.19,0.77,9,0,0*5f",
                  s),
            NmeaParseOutcome::kOk);
}

TEST(NmeaParser, TruncatedLine)
{
  acc::NmeaSentence s;
  EXPECT_EQ(parse("$GPGGA,092725.00,4717.11399,N,00833.9", s), NmeaParseOutcome::kMalformed);
  EXPECT_EQ(parse("$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*", s),
            NmeaParseOutcome::kMalformed);
  EXPECT_EQ(parse("$", s), NmeaParseOutcome::kMalformed);
  EXPECT_EQ(parse("", s), NmeaParseOutcome::kMalformed);
  EXPECT_EQ(parse("GPGGA,092725.00*00", s), NmeaParseOutcome::kMalformed);
  // A checksum-valid sentence that lost its last fields (e.g. a receiver's truncation).
  EXPECT_EQ(parse("$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08*57", s), NmeaParseOutcome::kMalformed);
  EXPECT_EQ(parse("$GPRMC,083559.00,A,4717.11437*11", s), NmeaParseOutcome::kMalformed);
}

TEST(NmeaParser, MissingFieldsAreAbsentNotErrors)
{
  acc::NmeaSentence s;
  // No fix yet: empty position, quality 0, empty HDOP and altitude.
  ASSERT_EQ(parse("$GNGGA,000012.00,,,,,0,00,99.99,,,,,,*7B", s), NmeaParseOutcome::kOk);
  EXPECT_EQ(s.fix_quality, 0);
  EXPECT_TRUE(std::isnan(s.latitude_deg));
  EXPECT_TRUE(std::isnan(s.altitude_m));
  EXPECT_NEAR(s.time_of_day_s, 12.0, 1e-9);
  // u-blox before its first fix: not even a time.
  ASSERT_EQ(parse("$GNRMC,,V,,,,,,,,,,N,V*37", s), NmeaParseOutcome::kOk);
  EXPECT_TRUE(std::isnan(s.time_of_day_s));
  EXPECT_FALSE(s.day.has_value());
  EXPECT_EQ(s.fix_quality, 0);
  // Standstill: speed but no course.
  ASSERT_EQ(parse("$GNRMC,101010.00,A,4717.11437,N,00833.91522,E,0.000,,091202,,,A,V*1D", s),
            NmeaParseOutcome::kOk);
  EXPECT_DOUBLE_EQ(s.speed_mps, 0.0);
  EXPECT_TRUE(std::isnan(s.course_rad));
  ASSERT_EQ(parse("$GNVTG,,T,,M,0.000,N,0.000,K,A*3D", s), NmeaParseOutcome::kOk);
  EXPECT_TRUE(std::isnan(s.course_rad));
  ASSERT_EQ(parse("$GNGST,000012.00,,,,,,,*64", s), NmeaParseOutcome::kOk);
  EXPECT_TRUE(std::isnan(s.latitude_sigma_m));
  ASSERT_EQ(parse("$GNZDA,000012.00,,,,00,00*7B", s), NmeaParseOutcome::kOk);
  EXPECT_FALSE(s.day.has_value());
}

TEST(NmeaParser, InvalidStatusClearsPositionAndVelocity)
{
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GNRMC,083559.00,V,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,N,V*2B", s),
            NmeaParseOutcome::kOk);
  EXPECT_EQ(s.fix_quality, 0);
  EXPECT_TRUE(std::isnan(s.latitude_deg));
  EXPECT_TRUE(std::isnan(s.speed_mps));
  EXPECT_TRUE(s.day.has_value());  // the date is still good
}

TEST(NmeaParser, SouthWestAndRtkMode)
{
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GNRMC,120000.00,A,3352.12800,S,15112.56000,W,20.000,359.99,010121,,,R,V*22", s),
            NmeaParseOutcome::kOk);
  EXPECT_NEAR(s.latitude_deg, -(33 + 52.128 / 60), 1e-12);
  EXPECT_NEAR(s.longitude_deg, -(151 + 12.56 / 60), 1e-12);
  EXPECT_EQ(s.fix_quality, 4);
  EXPECT_NEAR(s.course_rad, 359.99 * kPi / 180, 1e-12);
}

TEST(NmeaParser, MalformedFields)
{
  acc::NmeaSentence s;
  const char* lines[] = {
      "$GPGGA,092725.00,47x7.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*12",  // not a number
      "$GPGGA,092725.00,4717.11399,X,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*4D",  // hemisphere
      "$GPGGA,092725.00,4717.11399,N,,,1,08,1.01,499.6,M,48.0,M,,*3C",              // half a position
      "$GPGGA,092725.00,9117.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*50",  // > 90 deg
      "$GPGGA,092765.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5F",  // 65 seconds
      "$GPGGA,252725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*55",  // hour 25
      "$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,310202,,,A*5D",     // 31 February
      "$GPRMC,083559.00,A,4717.11437,N,00833.91522,E,-1.0,77.52,091202,,,A*7F",      // negative speed
      "$GPVTG,400.0,T,,M,0.004,N,0.008,K,A*05",                                     // course > 360
      "$GPZDA,082710.00,16,13,2002,00,00*6F",                                       // month 13
      "$GP GGA,1*6B",                                                               // address
  };
  for (const char* line : lines)
    EXPECT_EQ(parse(line, s), NmeaParseOutcome::kMalformed) << line;
}

TEST(NmeaParser, UnsupportedTypesAreCountedApart)
{
  acc::NmeaSentence s;
  EXPECT_EQ(parse("$GPGSV,3,1,11,03,03,111,00,04,15,270,00,06,01,010,00,13,06,292,00*74", s),
            NmeaParseOutcome::kUnsupported);
  EXPECT_EQ(parse("$GNTXT,01,01,02,u-blox AG - www.u-blox.com*4E", s), NmeaParseOutcome::kUnsupported);
  EXPECT_EQ(parse("$PUBX,03,00*1C", s), NmeaParseOutcome::kUnsupported);
  EXPECT_EQ(parse("$PGRME,15.0,M,45.0,M,25.0,M*1C", s), NmeaParseOutcome::kUnsupported);
}

TEST(NmeaParser, TimeOfDayForPacing)
{
  double t = 0.0;
  ASSERT_TRUE(acc::nmeaLineTimeOfDay("$GPGST,082356.00,1.8,,,,1.7,1.3,2.2*7E", t));
  EXPECT_NEAR(t, 8 * 3600 + 23 * 60 + 56.0, 1e-9);
  EXPECT_FALSE(acc::nmeaLineTimeOfDay("$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*06", t));
  EXPECT_FALSE(acc::nmeaLineTimeOfDay("garbage", t));
}

TEST(UtcDate, DaysFromCivil)
{
  EXPECT_EQ(acc::daysFromCivil(1970, 1, 1), 0);
  EXPECT_EQ(acc::daysFromCivil(2000, 3, 1), 11017);
  EXPECT_EQ(acc::daysFromCivil(2020, 10, 27), 18562);
  EXPECT_TRUE(acc::isValidDate(2020, 2, 29));
  EXPECT_FALSE(acc::isValidDate(2021, 2, 29));
  EXPECT_FALSE(acc::isValidDate(2100, 2, 29));
}

TEST(NmeaFields, NumbersReadExactlyAsStrtod)
{
  const char* numbers[] = {"0", "1.01", "4717.11399", "00833.91590", "-12.5", "+3.25", "499.6", "0.004",
                           "123456789012345", "1234567890.123456789", "0.1", "99999.99999", ".5", "7."};
  for (const char* text : numbers)
  {
    double value = 0.0;
    ASSERT_EQ(acc::readDouble(text, value), acc::FieldStatus::kOk) << text;
    EXPECT_EQ(value, std::strtod(text, nullptr)) << text;  // bit-exact, not near
  }
  // Every 5-decimal minute value of a degree: exact as the library reader of the C library.
  for (int units = 0; units < 6000000; units += 997)
  {
    char text[32];
    std::snprintf(text, sizeof text, "47%02d.%05d", units / 100000, units % 100000);
    double value = 0.0;
    ASSERT_EQ(acc::readDouble(text, value), acc::FieldStatus::kOk);
    ASSERT_EQ(value, std::strtod(text, nullptr)) << text;
  }
  double value = 0.0;
  EXPECT_EQ(acc::readDouble("", value), acc::FieldStatus::kAbsent);
  for (const char* bad : {"-", ".", "1.2.3", "1e5", "12a", " 1", "nan", "inf", "--1"})
    EXPECT_EQ(acc::readDouble(bad, value), acc::FieldStatus::kInvalid) << bad;
}

// ---- Receivers of other makes (test/data/nmea_captures, docs/GNSS_RECEIVERS.md). Lines quoted
// from gpsd's regression logs (BSD-2-Clause, see test/data/nmea_captures/ATTRIBUTION.md) unless
// marked "written": those are made for the case, with their real checksum.

TEST(NmeaReceivers, GnsIsDecodedLikeGga)
{
  // Ericsson GRU 04 (ST Teseo III, Trimble firmware) sends GNS, not GGA, for its position.
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GNGNS,213712.000,4111.59903,N,11156.54809,W,AANN,13,0.93,01482.5,-016.5,,*52", s),
            NmeaParseOutcome::kOk);
  EXPECT_STREQ(acc::toString(s.type), "GNS");
  EXPECT_NEAR(s.time_of_day_s, 21 * 3600 + 37 * 60 + 12.0, 1e-9);
  EXPECT_NEAR(s.latitude_deg, 41 + 11.59903 / 60, 1e-12);
  EXPECT_NEAR(s.longitude_deg, -(111 + 56.54809 / 60), 1e-12);
  EXPECT_DOUBLE_EQ(s.altitude_m, 1482.5);
  EXPECT_DOUBLE_EQ(s.geoid_separation_m, -16.5);
  EXPECT_EQ(s.satellites, 13);
  EXPECT_DOUBLE_EQ(s.hdop, 0.93);
  EXPECT_EQ(s.fix_quality, 1);  // GPS and GLONASS autonomous, Galileo and BeiDou none
  // SiRF-TriG before its fix: every constellation N, no position, the time still good.
  ASSERT_EQ(parse("$GNGNS,074150.799,,,,,NNNN,00,,,0.0,,0000*63", s), NmeaParseOutcome::kOk);
  EXPECT_EQ(s.fix_quality, 0);
  EXPECT_TRUE(std::isnan(s.latitude_deg));
  EXPECT_NEAR(s.time_of_day_s, 7 * 3600 + 41 * 60 + 50.799, 1e-9);
  // Written: the best constellation's mode gives the quality (RTK fixed); an unknown mode letter
  // is malformed.
  ASSERT_EQ(parse("$GNGNS,132827.20,4134.49941239,N,09345.03495785,W,RNDN,19,0.7,280.340,-31.442,1.0,0002*50", s),
            NmeaParseOutcome::kOk);
  EXPECT_EQ(s.fix_quality, 4);
  EXPECT_EQ(parse("$GNGNS,132827.20,4134.49941239,N,09345.03495785,W,AX,19,0.7,280.340,-31.442,1.0,0002*5F", s),
            NmeaParseOutcome::kMalformed);
}

TEST(NmeaReceivers, GllIsDecoded)
{
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GNGLL,4111.59903,N,11156.54809,W,213712.000,A,A*50", s), NmeaParseOutcome::kOk);
  EXPECT_STREQ(acc::toString(s.type), "GLL");
  EXPECT_NEAR(s.time_of_day_s, 21 * 3600 + 37 * 60 + 12.0, 1e-9);
  EXPECT_NEAR(s.latitude_deg, 41 + 11.59903 / 60, 1e-12);
  EXPECT_EQ(s.fix_quality, 1);
  // Garmin GPSmap 76S in simulator mode: status V (mode S), no position.
  ASSERT_EQ(parse("$GPGLL,3854.5087,N,07726.4523,W,125106,V,S*55", s), NmeaParseOutcome::kOk);
  EXPECT_EQ(s.fix_quality, 0);
  EXPECT_TRUE(std::isnan(s.latitude_deg));
  EXPECT_NEAR(s.time_of_day_s, 12 * 3600 + 51 * 60 + 6.0, 1e-9);
}

TEST(NmeaReceivers, GgaWithoutTrailingFields)
{
  // Saab R4 ends its GGA after the fix quality: the fields the driver reads are there (empty).
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GPGGA,130711,5012.790800,N,00806.879600,W,2,,,,,,,*6A", s), NmeaParseOutcome::kOk);
  EXPECT_EQ(s.fix_quality, 2);
  EXPECT_NEAR(s.latitude_deg, 50 + 12.7908 / 60, 1e-12);
  EXPECT_NEAR(s.longitude_deg, -(8 + 6.8796 / 60), 1e-12);
  EXPECT_TRUE(std::isnan(s.altitude_m));
  EXPECT_EQ(s.satellites, -1);
}

TEST(NmeaReceivers, NoFixSentenceWithPlaceholderPositionKeepsItsTimeAndDate)
{
  // MediaTek MT3301 at cold start: 89 deg 60 minutes north, quality 0 / status V, 1980 dates.
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GPGGA,235946.005,8960.000000,N,00000.000000,E,0,0,,137.000,M,13.000,M,,*49", s),
            NmeaParseOutcome::kOk);
  EXPECT_EQ(s.fix_quality, 0);
  EXPECT_TRUE(std::isnan(s.latitude_deg));
  EXPECT_TRUE(std::isnan(s.altitude_m));
  EXPECT_NEAR(s.time_of_day_s, 23 * 3600 + 59 * 60 + 46.005, 1e-9);
  ASSERT_EQ(parse("$GPRMC,235946.005,V,8960.000000,N,00000.000000,E,0.000,0.00,050180,,,N*47", s),
            NmeaParseOutcome::kOk);
  EXPECT_TRUE(std::isnan(s.latitude_deg));
  ASSERT_TRUE(s.day.has_value());
  EXPECT_EQ(*s.day, acc::daysFromCivil(1980, 1, 5));
  // Written: the same position in a sentence that claims a fix is still malformed.
  EXPECT_EQ(parse("$GPRMC,235946.005,A,8960.000000,N,00000.000000,E,0.000,0.00,050180,,,A*5F", s),
            NmeaParseOutcome::kMalformed);
  EXPECT_EQ(parse("$GPGGA,235946.005,8960.000000,N,00000.000000,E,1,5,,137.000,M,13.000,M,,*4D", s),
            NmeaParseOutcome::kMalformed);
}

TEST(NmeaReceivers, SimulatorAndManualQualityAreNoPosition)
{
  // Garmin GPSmap 76S in simulator mode: GGA quality 8 with a made-up position.
  acc::NmeaSentence s;
  ASSERT_EQ(parse("$GPGGA,125106,3854.5087,N,07726.4523,W,8,10,2.0,268.8,M,-33.9,M,,*7F", s),
            NmeaParseOutcome::kOk);
  EXPECT_EQ(s.fix_quality, 8);
  EXPECT_TRUE(std::isnan(s.latitude_deg));
  EXPECT_TRUE(std::isnan(s.altitude_m));
  EXPECT_EQ(s.satellites, 10);
  // Written: quality 7, manual input.
  ASSERT_EQ(parse("$GPGGA,125106,3854.5087,N,07726.4523,W,7,10,2.0,268.8,M,-33.9,M,,*70", s),
            NmeaParseOutcome::kOk);
  EXPECT_TRUE(std::isnan(s.latitude_deg));
}

TEST(NmeaReceivers, EncapsulationSentencesAreValidButUnsupported)
{
  // Saab R4, an AIS transponder with a GPS: AIS messages start with '!'.
  acc::NmeaSentence s;
  EXPECT_EQ(parse("!AIVDM,1,1,,B,13aGhtw0R<OJf=6LgQ?Ad1FF05`L,0*24", s), NmeaParseOutcome::kUnsupported);
  EXPECT_EQ(parse("!AIVDO,1,1,,B,13`kvwO005wJnb0Lfo:@7P8F05`L,0*5B", s), NmeaParseOutcome::kUnsupported);
  EXPECT_EQ(parse("!AIVDO,1,1,,B,13`kvwO005wJnb0Lfo:@7P8F05`L,0*5C", s), NmeaParseOutcome::kBadChecksum);
}
