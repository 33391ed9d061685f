// gps_driver_node: NMEA from one GNSS receiver (serial, UDP, TCP or a replayed log) to fixes.
#include "acc_identification/ros/gps_driver_ros.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "gps_driver");
  acc::GpsDriverRos driver(ros::NodeHandle(), ros::NodeHandle("~"));
  return driver.run();
}
