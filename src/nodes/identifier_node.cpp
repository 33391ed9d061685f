// identifier_node: ACC parameters and string stability, recalibrated every period over a sliding
// window of relative_state (Gunter et al. Section IV, online).
#include "acc_identification/ros/identifier_ros.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "identifier");
  acc::IdentifierRos node(ros::NodeHandle(), ros::NodeHandle("~"));
  if (!node.ok())
    return 1;
  ros::spin();
  return 0;
}
