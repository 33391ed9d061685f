#!/usr/bin/env python3
"""A recorded drive with a take-over by the safety driver, as drive.launch records one: a copy of
IN with the ACC's engagement reports on /acc_engaged (std_msgs/Bool) at bag times: engaged at the
start, off from OFF_S seconds into the bag, engaged again from ON_S. For end_to_end_take_over.test.

Usage: add_take_over.py IN OUT OFF_S ON_S
"""
import sys

import rosbag
import rospy
from std_msgs.msg import Bool


def main(source, target, off_s, on_s):
    if not 0.0 < off_s < on_s:
        sys.exit("add_take_over.py: need 0 < OFF_S < ON_S, not %s and %s" % (off_s, on_s))
    with rosbag.Bag(source) as bag_in, rosbag.Bag(target, "w") as bag_out:
        start = rospy.Time.from_sec(bag_in.get_start_time())
        for topic, message, stamp in bag_in.read_messages(raw=True):
            bag_out.write(topic, message, stamp, raw=True)
        for offset_s, engaged in ((0.0, True), (off_s, False), (on_s, True)):
            bag_out.write("/acc_engaged", Bool(data=engaged), start + rospy.Duration.from_sec(offset_s))


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))
