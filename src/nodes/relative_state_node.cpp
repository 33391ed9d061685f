// relative_state_node: the leader's and the follower's GNSS fixes paired by epoch into the gap,
// speeds and relative speed (RelativeState), with quality and health.
#include "acc_identification/ros/relative_state_ros.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "relative_state");
  acc::RelativeStateRos node(ros::NodeHandle(), ros::NodeHandle("~"));
  if (!node.ok())
    return 1;
  ros::spin();
  return 0;
}
