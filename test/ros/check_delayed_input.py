#!/usr/bin/env python3
"""rostest: a message delayed beyond its delay budget. The path tracker's pose comes through this test: a
relay from vehicle_state to vehicle_state_relayed that forwards each message at once, except the first one
stamped at or after ~hold_at, which it holds for ~hold_for seconds of wall time (everything after it waits
behind it, in order). The tracker needs the pose only tau1 = 0.2 s later, so a hold of 1 s is five times
the budget: in realtime mode the loop cannot go on without it. Expected: the plant waits (a value never
depends on when a message arrived), warns on /rosout while the run is behind the wall clock, its summary
says FELL BEHIND, nothing is lost or changed -- the log is bit-identical to lk_simulate's -- and the run
completes."""
import re
import sys
import threading
import time
import unittest

import rospy
import rostest
from lane_keeping.msg import VehicleStateArray
from rosgraph_msgs.msg import Log

from lk_test_support import StatusWatcher, compare_logs, run_lk_simulate, temp_csv, wait_for

_LAG = re.compile(r'realtime run ([0-9.]+) s behind the wall clock')


class CheckDelayedInput(unittest.TestCase):
    def test_a_message_late_beyond_its_budget_delays_but_does_not_change_the_run(self):
        ns = rospy.get_param('~ns')
        hold_at, hold_for = rospy.get_param('~hold_at'), rospy.get_param('~hold_for')
        watcher = StatusWatcher(ns)
        lag_warnings = []
        rospy.Subscriber('/rosout', Log, lambda m: lag_warnings.append((time.time(), m.msg, watcher.ended()))
                         if m.level == Log.WARN and 'behind the wall clock' in m.msg else None, queue_size=1000)
        relay = {'held': None, 'forwarded': 0, 'lock': threading.Lock()}
        out = rospy.Publisher('/%s/vehicle_state_relayed' % ns, VehicleStateArray, queue_size=100000, tcp_nodelay=True)
        self.assertTrue(wait_for(lambda: out.get_num_connections() > 0, 60.0), 'the tracker never subscribed')

        def forward(msg):
            with relay['lock']:  # one message at a time, in order (rospy runs this in the subscriber's thread)
                if relay['held'] is None and msg.samples and msg.samples[-1].header.stamp.to_sec() >= hold_at:
                    start = time.time()
                    time.sleep(hold_for)
                    relay['held'] = (msg.samples[-1].header.stamp.to_sec(), start, time.time())
                out.publish(msg)
                relay['forwarded'] += 1

        # Subscribed only now that the tracker listens: the plant starts once the relay listens.
        rospy.Subscriber('/%s/vehicle_state' % ns, VehicleStateArray, forward, queue_size=100000, tcp_nodelay=True)
        self.assertTrue(watcher.wait_running(60.0), 'the run never started')
        status = watcher.wait_end(120.0)
        self.assertIsNotNone(status, 'the run never ended')
        time.sleep(1.0)  # the last /rosout messages
        self.assertEqual(status.state, status.COMPLETED, status.message)
        self.assertIsNotNone(relay['held'], 'no message reached t = %g s' % hold_at)
        stamp, held_from, held_until = relay['held']
        rospy.loginfo('relay: held the pose message stamped %.3f s for %.2f s of wall time; %d messages forwarded',
                      stamp, held_until - held_from, relay['forwarded'])
        rospy.loginfo('plant lag warnings: %s', [w[1] for w in lag_warnings])
        rospy.loginfo('summary:\n%s', status.summary)

        problems = []
        during = [w for w in lag_warnings if not w[2]]
        if not during:
            problems.append('no warning that the run was behind the wall clock while it ran')
        else:
            worst = max(float(_LAG.search(w[1]).group(1)) for w in during if _LAG.search(w[1]))
            # The hold less the 0.2 s of poses the tracker did not need yet (and a margin for the jitter).
            if worst < hold_for - 0.2 - 0.2:
                problems.append('the warnings show a lag of at most %.3f s; the pose was held %.2f s' % (worst, hold_for))
        if 'FELL BEHIND the wall clock' not in status.summary:
            problems.append('the summary does not say the run fell behind')
        reference = temp_csv('delayed_reference')
        code, text = run_lk_simulate(rospy.get_param('~reference_configs'), rospy.get_param('~reference_sets'),
                                     reference)
        self.assertEqual(code, 0, text)
        identical, worst, rows_ros, rows_ref, first = compare_logs(rospy.get_param('~log_file'), reference)
        rospy.loginfo('log with a late pose vs in-process: %d vs %d rows, %s', rows_ros, rows_ref,
                      'bit-identical' if identical else 'differ: ' + first)
        if not identical:
            problems.append('the late message changed the run: %s (max |difference| %g)' % (first, worst))
        self.assertEqual(problems, [], '\n'.join(problems))


if __name__ == '__main__':
    rospy.init_node('check_delayed_input')
    rostest.rosrun('lane_keeping', 'check_delayed_input', CheckDelayedInput, sys.argv)
