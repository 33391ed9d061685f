// The driver wrapper's conversions: the library fix <-> acc_identification/GnssFix, and the standard
// messages navsat_fix (status, covariance), vel and time_reference.
#include <gtest/gtest.h>

#include "acc_identification/ros/gps_driver_ros.h"
#include "acc_identification/gnss/utc_date.h"
#include "acc_identification/ros/ros_time.h"

#include <cmath>
#include <limits>


TEST(GnssFixConversion, RoundTripAndExactStamp)
{
  acc::GnssFix fix;
  fix.gnss_time_s = acc::daysFromCivil(2020, 10, 27) * acc::kSecondsPerDay + 36930.3;
  fix.has_date = true;
  fix.receive_time_s = 1603793730.35;
  fix.latitude_deg = 45.13;
  fix.longitude_deg = 8.45;
  fix.speed_over_ground_mps = 12.5;
  fix.course_rad = 1.0;
  fix.fix_quality = 4;
  fix.satellites_used = 17;
  fix.valid_fields = acc::GnssFix::kValidPosition | acc::GnssFix::kValidSpeed | acc::GnssFix::kValidCourse |
                     acc::GnssFix::kValidDate | acc::GnssFix::kValidSatellites;
  const acc_identification::GnssFix m = acc::toMessage(fix, "leader_gps");
  EXPECT_EQ(m.header.stamp.sec, 1603793730u);
  EXPECT_EQ(m.header.stamp.nsec, 300000000u);
  EXPECT_EQ(m.header.frame_id, "leader_gps");
  EXPECT_EQ(m.valid_fields & acc_identification::GnssFix::VALID_DATE, acc_identification::GnssFix::VALID_DATE);
  const acc::GnssFix back = acc::fromMessage(m);
  EXPECT_TRUE(back.has_date);
  EXPECT_NEAR(back.gnss_time_s, fix.gnss_time_s, 1e-6);
  EXPECT_NEAR(back.receive_time_s, fix.receive_time_s, 1e-6);
  EXPECT_EQ(back.latitude_deg, fix.latitude_deg);
  EXPECT_EQ(back.fix_quality, 4);
  EXPECT_EQ(back.satellites_used, 17);
  EXPECT_EQ(back.valid_fields, fix.valid_fields);
}

TEST(GnssFixConversion, TimeOfDayOnlyBeforeTheFirstDate)
{
  acc::GnssFix fix;
  fix.gnss_time_s = 36930.3;  // 10:15:30.3 of an unknown day
  const acc_identification::GnssFix m = acc::toMessage(fix, "gps");
  EXPECT_EQ(m.header.stamp.sec, 36930u);
  EXPECT_EQ(m.header.stamp.nsec, 300000000u);
  EXPECT_EQ(m.valid_fields & acc_identification::GnssFix::VALID_DATE, 0u);
  EXPECT_FALSE(acc::fromMessage(m).has_date);
}

/// Issue "one model core": navsat_fix and vel carried GNSS time (from 1970 before a date is
/// known), which tf and message_filters users drop. Receive time by default, GNSS time on request.
TEST(StandardMessages, NavSatFixAndVelocityCarryTheReceiveTimeUnlessAsked)
{
  acc::GnssFix fix;
  fix.gnss_time_s = 36930.3;        // 10:15:30.3 of a day not known yet
  fix.receive_time_s = 1700000000.25;
  fix.latitude_deg = 45.13;
  fix.longitude_deg = 8.45;
  fix.speed_over_ground_mps = 10.0;
  fix.course_rad = 0.0;             // north
  fix.fix_quality = 1;
  fix.valid_fields = acc::GnssFix::kValidPosition | acc::GnssFix::kValidSpeed | acc::GnssFix::kValidCourse;
  sensor_msgs::NavSatFix navsat;
  ASSERT_TRUE(acc::toNavSatFix(fix, "gps", 3.0, false, navsat));
  EXPECT_DOUBLE_EQ(navsat.header.stamp.toSec(), 1700000000.25);
  EXPECT_EQ(navsat.header.frame_id, "gps");
  EXPECT_DOUBLE_EQ(navsat.latitude, 45.13);
  geometry_msgs::TwistStamped twist;
  ASSERT_TRUE(acc::toEnuTwist(fix, "gps_enu", false, twist));
  EXPECT_DOUBLE_EQ(twist.header.stamp.toSec(), 1700000000.25);
  EXPECT_NEAR(twist.twist.linear.y, 10.0, 1e-9);  // north
  EXPECT_NEAR(twist.twist.linear.x, 0.0, 1e-9);

  ASSERT_TRUE(acc::toNavSatFix(fix, "gps", 3.0, true, navsat));
  EXPECT_DOUBLE_EQ(navsat.header.stamp.toSec(), 36930.3);
  ASSERT_TRUE(acc::toEnuTwist(fix, "gps_enu", true, twist));
  EXPECT_DOUBLE_EQ(twist.header.stamp.toSec(), 36930.3);

  fix.valid_fields = acc::GnssFix::kValidSpeed;  // no position, no course
  EXPECT_FALSE(acc::toNavSatFix(fix, "gps", 3.0, false, navsat));
  EXPECT_FALSE(acc::toEnuTwist(fix, "gps_enu", false, twist));
}

/// Issue "one model core": ros::Time(inf) threw in two nodes; one bounded conversion serves all.
TEST(RosTime, OneBoundedConversionNeverThrows)
{
  EXPECT_EQ(acc::toRosTime(std::nan("")), ros::Time());
  EXPECT_EQ(acc::toRosTime(std::numeric_limits<double>::infinity()), ros::Time());
  EXPECT_EQ(acc::toRosTime(-1.0), ros::Time());
  EXPECT_EQ(acc::toRosTime(4294967296.0), ros::Time());  // 2^32 s: beyond ros::Time
  EXPECT_EQ(acc::toRosTime(1.0e12), ros::Time());
  const ros::Time t = acc::toRosTime(1603793730.3);  // rounded to the microsecond: .300000000
  EXPECT_EQ(t.sec, 1603793730u);
  EXPECT_EQ(t.nsec, 300000000u);
}

/// The flag form of the one conversion: false (and an unset time) for every time ros::Time cannot
/// hold, true and the time otherwise, at both ends of the range.
TEST(RosTime, FailureIsAFlagAndAnUnsetTime)
{
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {std::nan(""), inf, -inf, -1.0, -1e-9, 4294967296.0, 4294967296.5, 1e12, 1e300})
  {
    ros::Time t(12, 34);
    EXPECT_FALSE(acc::toRosTime(bad, t)) << bad;
    EXPECT_TRUE(t.isZero()) << bad;
  }
  ros::Time t;
  ASSERT_TRUE(acc::toRosTime(0.0, t));
  EXPECT_TRUE(t.isZero());
  ASSERT_TRUE(acc::toRosTime(4294967295.25, t));  // the last second ros::Time holds
  EXPECT_EQ(t.sec, 4294967295u);
  EXPECT_EQ(t.nsec, 250000000u);
  ASSERT_TRUE(acc::toRosTime(36930.3, t));
  EXPECT_EQ(t.sec, 36930u);
  EXPECT_EQ(t.nsec, 300000000u);
}

/// A fix whose GNSS time ros::Time cannot hold: not published on fix (it would pair as a time
/// reset), and no navsat_fix or vel stamped with it; the receive-time stamp still works.
TEST(StandardMessages, AGnssTimeOutsideRosTimeIsNotStampedZero)
{
  acc::GnssFix fix;
  fix.gnss_time_s = 5.0e9;  // year 2128 (a ZDA with a 4-digit year can say anything)
  fix.receive_time_s = 1700000000.25;
  fix.latitude_deg = 45.13;
  fix.longitude_deg = 8.45;
  fix.speed_over_ground_mps = 10.0;
  fix.course_rad = 0.0;
  fix.fix_quality = 1;
  fix.valid_fields = acc::GnssFix::kValidPosition | acc::GnssFix::kValidSpeed | acc::GnssFix::kValidCourse;
  EXPECT_FALSE(acc::hasRosGnssTime(fix));
  sensor_msgs::NavSatFix navsat;
  geometry_msgs::TwistStamped twist;
  EXPECT_FALSE(acc::toNavSatFix(fix, "gps", 3.0, true, navsat));
  EXPECT_FALSE(acc::toEnuTwist(fix, "gps_enu", true, twist));
  ASSERT_TRUE(acc::toNavSatFix(fix, "gps", 3.0, false, navsat));
  EXPECT_DOUBLE_EQ(navsat.header.stamp.toSec(), 1700000000.25);
  ASSERT_TRUE(acc::toEnuTwist(fix, "gps_enu", false, twist));
  fix.gnss_time_s = 36930.3;
  EXPECT_TRUE(acc::hasRosGnssTime(fix));
}

namespace
{
/// A dated fix at 2020-10-27 10:15:30.3 UTC, received 0.35 s later on the ROS clock, with a
/// position: what the driver's epoch assembler hands the wrapper.
acc::GnssFix datedFixWithPosition()
{
  acc::GnssFix fix;
  fix.gnss_time_s = acc::daysFromCivil(2020, 10, 27) * acc::kSecondsPerDay + 36930.3;
  fix.has_date = true;
  fix.receive_time_s = fix.gnss_time_s + 0.35;
  fix.latitude_deg = 45.13;
  fix.longitude_deg = 8.45;
  fix.fix_quality = 1;
  fix.valid_fields = acc::GnssFix::kValidPosition | acc::GnssFix::kValidDate;
  return fix;
}

void expectDiagonal(const sensor_msgs::NavSatFix& navsat, double east_m2, double north_m2, double up_m2)
{
  for (std::size_t i = 0; i < 9; ++i)
  {
    const double expected = i == 0 ? east_m2 : i == 4 ? north_m2 : i == 8 ? up_m2 : 0.0;
    EXPECT_NEAR(navsat.position_covariance[i], expected, 1e-12) << "element " << i;
  }
}
}  // namespace

/// Issue 25 item 4: time_reference as nmea_navsat_driver publishes it. header.stamp is the receive
/// time on the ROS clock (navsat_fix's default stamp), time_ref the GNSS time: swapping them, or
/// stamping both with one, fails here because the two differ by 0.35 s.
TEST(TimeReference, StampIsTheReceiveTimeAndTimeRefTheGnssTime)
{
  const acc::GnssFix fix = datedFixWithPosition();
  sensor_msgs::TimeReference reference;
  ASSERT_EQ(acc::toTimeReference(fix, "leader_gps", "leader_receiver", reference), acc::TimeReferenceOutcome::kMade);
  EXPECT_EQ(reference.time_ref.sec, 1603793730u);
  EXPECT_EQ(reference.time_ref.nsec, 300000000u);  // the same exact stamp as fix's header
  EXPECT_EQ(reference.time_ref, acc::toMessage(fix, "leader_gps").header.stamp);
  EXPECT_EQ(reference.header.stamp.sec, 1603793730u);
  EXPECT_EQ(reference.header.stamp.nsec, 650000000u);
  EXPECT_EQ(reference.header.stamp, acc::toMessage(fix, "leader_gps").receive_time);
  EXPECT_EQ(reference.header.frame_id, "leader_gps");
  EXPECT_EQ(reference.source, "leader_receiver");
}

/// Only an absolute GNSS time is a time reference: before the first date the GNSS time is a time
/// of day counted from 1970, which would say the clock is 50 years off. A time ros::Time cannot
/// hold is not stamped 0 either. Neither touches the message.
TEST(TimeReference, NoneWithoutADateOrOutsideRosTime)
{
  const sensor_msgs::TimeReference untouched;
  acc::GnssFix undated = datedFixWithPosition();
  undated.gnss_time_s = 36930.3;
  undated.has_date = false;
  undated.valid_fields &= ~acc::GnssFix::kValidDate;
  sensor_msgs::TimeReference reference;
  EXPECT_EQ(acc::toTimeReference(undated, "gps", "gps", reference), acc::TimeReferenceOutcome::kNoDate);
  EXPECT_EQ(reference, untouched);

  acc::GnssFix beyond = datedFixWithPosition();
  beyond.gnss_time_s = 5.0e9;  // 2128: a ZDA with a 4-digit year can say anything
  EXPECT_EQ(acc::toTimeReference(beyond, "gps", "gps", reference), acc::TimeReferenceOutcome::kOutsideRosTime);
  EXPECT_EQ(reference, untouched);

  acc::GnssFix unreceived = datedFixWithPosition();
  unreceived.receive_time_s = std::nan("");
  EXPECT_EQ(acc::toTimeReference(unreceived, "gps", "gps", reference), acc::TimeReferenceOutcome::kOutsideRosTime);
  EXPECT_EQ(reference, untouched);
}

/// Issue 25 item 4: every GGA quality 0..8 to NavSatStatus (nmea_navsat_driver's rows; 3 PPS a
/// plain fix; 6 dead reckoning, 7 manual, 8 simulator no satellite fix), through toNavSatFix too.
TEST(NavSatStatusMapping, EveryGgaQuality)
{
  using Status = sensor_msgs::NavSatStatus;
  const std::int8_t expected[9] = {Status::STATUS_NO_FIX,   Status::STATUS_FIX,      Status::STATUS_SBAS_FIX,
                                   Status::STATUS_FIX,      Status::STATUS_GBAS_FIX, Status::STATUS_GBAS_FIX,
                                   Status::STATUS_NO_FIX,   Status::STATUS_NO_FIX,   Status::STATUS_NO_FIX};
  acc::GnssFix fix = datedFixWithPosition();
  for (std::uint8_t quality = 0; quality <= 8; ++quality)
  {
    EXPECT_EQ(acc::navSatStatusOf(quality), expected[quality]) << "GGA quality " << int(quality);
    fix.fix_quality = quality;
    sensor_msgs::NavSatFix navsat;
    ASSERT_TRUE(acc::toNavSatFix(fix, "gps", 3.0, false, navsat));
    EXPECT_EQ(navsat.status.status, expected[quality]) << "GGA quality " << int(quality);
    EXPECT_EQ(navsat.status.service, Status::SERVICE_GPS);
  }
}

/// NavSatStatus says GBAS for both RTK solutions; fix tells them apart by fix_quality, unchanged.
TEST(NavSatStatusMapping, RtkFixedAndFloatDifferOnlyInTheGnssFix)
{
  acc::GnssFix fixed = datedFixWithPosition();
  fixed.fix_quality = acc_identification::GnssFix::FIX_RTK_FIXED;
  acc::GnssFix floating = fixed;
  floating.fix_quality = acc_identification::GnssFix::FIX_RTK_FLOAT;
  sensor_msgs::NavSatFix fixed_navsat, float_navsat;
  ASSERT_TRUE(acc::toNavSatFix(fixed, "gps", 3.0, false, fixed_navsat));
  ASSERT_TRUE(acc::toNavSatFix(floating, "gps", 3.0, false, float_navsat));
  EXPECT_EQ(fixed_navsat.status.status, sensor_msgs::NavSatStatus::STATUS_GBAS_FIX);
  EXPECT_EQ(float_navsat.status.status, sensor_msgs::NavSatStatus::STATUS_GBAS_FIX);
  EXPECT_EQ(acc::toMessage(fixed, "gps").fix_quality, acc_identification::GnssFix::FIX_RTK_FIXED);
  EXPECT_EQ(acc::toMessage(floating, "gps").fix_quality, acc_identification::GnssFix::FIX_RTK_FLOAT);
  EXPECT_EQ(acc::fromMessage(acc::toMessage(floating, "gps")).fix_quality, 5);
}

/// Issue 25 item 4: GST sigmas are a known diagonal in ENU order: east = longitude sigma^2,
/// north = latitude sigma^2, up = altitude sigma^2 (three different sigmas, so a swap fails).
/// GST wins over HDOP when both are there.
TEST(NavSatCovariance, GstSigmasAreAKnownEnuDiagonal)
{
  acc::GnssFix fix = datedFixWithPosition();
  fix.latitude_sigma_m = 0.7;
  fix.longitude_sigma_m = 0.5;
  fix.altitude_sigma_m = 1.5;
  fix.hdop = 0.8;
  fix.valid_fields |= acc::GnssFix::kValidPositionSigma | acc::GnssFix::kValidHdop;
  sensor_msgs::NavSatFix navsat;
  ASSERT_TRUE(acc::toNavSatFix(fix, "gps", 3.0, false, navsat));
  EXPECT_EQ(navsat.position_covariance_type, sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN);
  expectDiagonal(navsat, 0.25, 0.49, 2.25);
}

/// Without GST: east = north = (hdop * hdop_uere_m)^2, up = (2 * hdop * hdop_uere_m)^2, APPROXIMATED.
TEST(NavSatCovariance, HdopOnlyIsApproximated)
{
  acc::GnssFix fix = datedFixWithPosition();
  fix.hdop = 1.2;
  fix.valid_fields |= acc::GnssFix::kValidHdop;
  sensor_msgs::NavSatFix navsat;
  ASSERT_TRUE(acc::toNavSatFix(fix, "gps", 2.5, false, navsat));
  EXPECT_EQ(navsat.position_covariance_type, sensor_msgs::NavSatFix::COVARIANCE_TYPE_APPROXIMATED);
  expectDiagonal(navsat, 9.0, 9.0, 36.0);  // (1.2 * 2.5)^2, (2 * 1.2 * 2.5)^2
}

/// Neither GST nor HDOP: UNKNOWN and all nine elements zero, also in a message reused from a fix
/// that had GST (the node builds one per fix; a caller reusing one must not keep the old covariance).
TEST(NavSatCovariance, NothingIsUnknownAndZero)
{
  acc::GnssFix with_gst = datedFixWithPosition();
  with_gst.latitude_sigma_m = with_gst.longitude_sigma_m = with_gst.altitude_sigma_m = 1.0;
  with_gst.valid_fields |= acc::GnssFix::kValidPositionSigma;
  sensor_msgs::NavSatFix navsat;
  ASSERT_TRUE(acc::toNavSatFix(with_gst, "gps", 3.0, false, navsat));
  navsat.position_covariance[1] = 0.5;  // whatever the caller left off the diagonal goes too
  ASSERT_TRUE(acc::toNavSatFix(datedFixWithPosition(), "gps", 3.0, false, navsat));
  EXPECT_EQ(navsat.position_covariance_type, sensor_msgs::NavSatFix::COVARIANCE_TYPE_UNKNOWN);
  expectDiagonal(navsat, 0.0, 0.0, 0.0);
}

/// A GST without its altitude sigma (the field may be empty) is not a known diagonal with a NaN in
/// it: HDOP's rule when there is an HDOP, UNKNOWN otherwise.
TEST(NavSatCovariance, PartialGstFallsBackToHdopOrUnknown)
{
  acc::GnssFix fix = datedFixWithPosition();
  fix.latitude_sigma_m = 0.7;
  fix.longitude_sigma_m = 0.5;
  fix.valid_fields |= acc::GnssFix::kValidPositionSigma;  // altitude_sigma_m stays NaN
  sensor_msgs::NavSatFix navsat;
  ASSERT_TRUE(acc::toNavSatFix(fix, "gps", 3.0, false, navsat));
  EXPECT_EQ(navsat.position_covariance_type, sensor_msgs::NavSatFix::COVARIANCE_TYPE_UNKNOWN);
  expectDiagonal(navsat, 0.0, 0.0, 0.0);
  fix.hdop = 1.0;
  fix.valid_fields |= acc::GnssFix::kValidHdop;
  ASSERT_TRUE(acc::toNavSatFix(fix, "gps", 3.0, false, navsat));
  EXPECT_EQ(navsat.position_covariance_type, sensor_msgs::NavSatFix::COVARIANCE_TYPE_APPROXIMATED);
  expectDiagonal(navsat, 9.0, 9.0, 36.0);
}
