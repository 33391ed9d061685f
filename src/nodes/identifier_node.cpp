// identifier_node: ACC parameters and string stability, recalibrated every period over a sliding
// window of relative_state (Gunter et al. Section IV, online).
#include <malloc.h>

#include "acc_identification/ros/identifier_ros.h"

int main(int argc, char** argv)
{
  // One malloc arena: every period copies the drive so far (a few MB) across three threads, and
  // per-thread arenas kept their high-water marks, so the resident memory crept up for an hour
  // after the drive's bound filled (+5 MB). With one, it stays level: 22 MB at most over 3 hours.
  mallopt(M_ARENA_MAX, 1);
  ros::init(argc, argv, "identifier");
  acc::IdentifierRos node(ros::NodeHandle(), ros::NodeHandle("~"));
  if (!node.ok())
    return 1;
  ros::spin();
  return 0;
}
