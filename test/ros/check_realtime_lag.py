#!/usr/bin/env python3
"""rostest: a realtime run reports whether it kept up with the wall clock. Behind: at least one
warning on /rosout naming the lag arrives while the run is still going, and the summary says FELL
BEHIND with a real-time factor below 1. Keeping up: no such warning, and the summary says "kept up".

Parameters: ~ns (the run's namespace), ~expect_behind (bool)."""
import sys
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log

from lk_test_support import StatusWatcher


class CheckRealtimeLag(unittest.TestCase):
    def test_realtime_lag_is_reported(self):
        ns = rospy.get_param('~ns')
        expect_behind = rospy.get_param('~expect_behind')
        watcher = StatusWatcher(ns)
        warnings = []  # (wall time, message) of the plant's lag warnings

        def on_log(msg):
            if msg.level == Log.WARN and 'behind the wall clock' in msg.msg and ns in msg.name:
                warnings.append((time.time(), msg.msg, watcher.ended()))
            elif msg.level >= Log.WARN:
                rospy.loginfo('other %s message from %s: %s', msg.level, msg.name, msg.msg)

        # Straight from the nodes (the aggregated /rosout_agg repeats them once rosout has them).
        rospy.Subscriber('/rosout', Log, on_log, queue_size=1000)
        self.assertTrue(watcher.wait_running(60.0), '%s never started' % ns)
        status = watcher.wait_end(90.0)
        self.assertIsNotNone(status, '%s never ended' % ns)
        time.sleep(1.0)  # the last /rosout messages
        rospy.loginfo('%s: rtf %.3f, %d lag warning(s); summary:\n%s', ns, status.real_time_factor, len(warnings),
                      status.summary)
        self.assertEqual(status.state, status.COMPLETED, status.message)
        if expect_behind:
            self.assertGreater(len(warnings), 0, 'no lag warning while the run fell behind:\n' + status.summary)
            self.assertFalse(warnings[0][2], 'the first lag warning came only after the run ended')
            self.assertIn('FELL BEHIND the wall clock', status.summary)
            self.assertLess(status.real_time_factor, 0.95)
        else:
            self.assertEqual(warnings, [], 'lag warnings on a run that kept up')
            self.assertIn('realtime:               kept up', status.summary)
            self.assertGreater(status.real_time_factor, 0.95)


if __name__ == '__main__':
    rospy.init_node('check_realtime_lag')
    rostest.rosrun('lane_keeping', 'check_realtime_lag', CheckRealtimeLag, sys.argv)
