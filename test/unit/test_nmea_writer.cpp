// The NMEA writer: u-blox precision, and what it writes reads back through the parser.
#include <gtest/gtest.h>

#include <cmath>

#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/gnss/nmea_writer.h"
#include "acc_identification/gnss/utc_date.h"


namespace
{
constexpr double kPi = 3.14159265358979323846;

acc::GnssFix ubloxExampleFix()
{
  acc::GnssFix fix;
  fix.gnss_time_s = acc::daysFromCivil(2002, 12, 9) * acc::kSecondsPerDay + 9 * 3600 + 27 * 60 + 25.0;
  fix.has_date = true;
  fix.latitude_deg = 47 + 17.11399 / 60;
  fix.longitude_deg = 8 + 33.91590 / 60;
  fix.altitude_m = 499.6;
  fix.geoid_separation_m = 48.0;
  fix.fix_quality = 1;
  fix.satellites_used = 8;
  fix.hdop = 1.01;
  fix.speed_over_ground_mps = 0.004 * 1852.0 / 3600.0;
  fix.course_rad = 77.52 * kPi / 180.0;
  fix.valid_fields = acc::GnssFix::kValidPosition | acc::GnssFix::kValidAltitude | acc::GnssFix::kValidSatellites |
                     acc::GnssFix::kValidHdop | acc::GnssFix::kValidSpeed | acc::GnssFix::kValidCourse |
                     acc::GnssFix::kValidDate;
  return fix;
}
}  // namespace

TEST(NmeaWriter, Checksum)
{
  EXPECT_EQ(acc::nmeaChecksum("GPVTG,77.52,T,,M,0.004,N,0.008,K,A"), "06");
  EXPECT_EQ(acc::nmeaChecksum("GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,"), "5B");
}

TEST(NmeaWriter, GgaAsUbloxWritesIt)
{
  EXPECT_EQ(acc::formatGga(ubloxExampleFix(), "GP"),
            "$GPGGA,092725.00,4717.11399,N,00833.91590,E,1,08,1.01,499.6,M,48.0,M,,*5B");
}

TEST(NmeaWriter, RmcAsUbloxWritesIt)
{
  EXPECT_EQ(acc::formatRmc(ubloxExampleFix(), "GN"),
            "$GNRMC,092725.00,A,4717.11399,N,00833.91590,E,0.004,77.52,091202,,,A,V*" +
                acc::nmeaChecksum("GNRMC,092725.00,A,4717.11399,N,00833.91590,E,0.004,77.52,091202,,,A,V"));
}

TEST(NmeaWriter, RoundingCarriesIntoDegreesAndSeconds)
{
  acc::GnssFix fix = ubloxExampleFix();
  fix.latitude_deg = -(45 + 59.9999999 / 60);  // rounds to 46 deg 00.00000 min
  fix.longitude_deg = -(7 + 0.5 / 60);
  fix.gnss_time_s = acc::daysFromCivil(2020, 12, 31) * acc::kSecondsPerDay + 86399.996;  // rounds to midnight
  const std::string gga = acc::formatGga(fix);
  EXPECT_NE(gga.find(",000000.00,4600.00000,S,00700.50000,W,"), std::string::npos) << gga;
}

TEST(NmeaWriter, RoundTripThroughParser)
{
  acc::GnssFix fix = ubloxExampleFix();
  fix.latitude_deg = -33.8688197;
  fix.longitude_deg = 151.2092955;
  fix.speed_over_ground_mps = 27.345;
  fix.course_rad = 3.0;
  acc::NmeaSentence gga, rmc;
  ASSERT_EQ(acc::parseNmeaSentence(acc::formatGga(fix), gga), acc::NmeaParseOutcome::kOk);
  ASSERT_EQ(acc::parseNmeaSentence(acc::formatRmc(fix), rmc), acc::NmeaParseOutcome::kOk);
  // 1e-5 minute of latitude is 1.85 cm: half of it is the worst rounding error.
  const double half_unit_deg = 0.5e-5 / 60.0;
  EXPECT_NEAR(gga.latitude_deg, fix.latitude_deg, half_unit_deg);
  EXPECT_NEAR(gga.longitude_deg, fix.longitude_deg, half_unit_deg);
  EXPECT_NEAR(rmc.latitude_deg, fix.latitude_deg, half_unit_deg);
  EXPECT_NEAR(rmc.speed_mps, fix.speed_over_ground_mps, 0.5e-3 * 1852.0 / 3600.0);
  EXPECT_NEAR(rmc.course_rad, fix.course_rad, 0.005 * kPi / 180.0);
  ASSERT_TRUE(rmc.day.has_value());
  EXPECT_EQ(*rmc.day, acc::daysFromCivil(2002, 12, 9));
  EXPECT_NEAR(rmc.time_of_day_s, 9 * 3600 + 27 * 60 + 25.0, 1e-9);
}

TEST(NmeaWriter, MissingFieldsAreEmpty)
{
  acc::GnssFix fix;
  fix.gnss_time_s = 3600.0;  // time of day only
  const std::string rmc = acc::formatRmc(fix);
  EXPECT_EQ(rmc.substr(0, rmc.size() - 3), "$GNRMC,010000.00,V,,,,,,,,,,N,V");
  acc::NmeaSentence s;
  ASSERT_EQ(acc::parseNmeaSentence(rmc, s), acc::NmeaParseOutcome::kOk);
  EXPECT_FALSE(s.day.has_value());
  ASSERT_EQ(acc::parseNmeaSentence(acc::formatGga(fix), s), acc::NmeaParseOutcome::kOk);
  EXPECT_EQ(s.fix_quality, 0);
}
