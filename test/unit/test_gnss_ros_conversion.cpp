// The library fix <-> acc_identification/GnssFix message conversion of the driver wrapper.
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
