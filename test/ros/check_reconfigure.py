#!/usr/bin/env python3
"""rostest checker of runtime tuning with dynamic_reconfigure in lockstep (docs/ros.md, "Runtime tuning").

While a lockstep run goes, a dynamic_reconfigure client (the Python dynamic_reconfigure.client):
  * reads the servers' values: the loaded configuration (k_y and p set by the launch), not the .cfg defaults;
  * sets k_psi = 1.2 with apply_at = 4 s: it must take effect at exactly t = 4 s;
  * sets k_psi = NaN and tau1 = 10.5 s (beyond the 10 s limit; the .cfg range reaches to 11 s so that it is
    refused rather than clamped), and tau2 = 0 on the actuator (a lockstep
    schedule that cannot advance): each refused, the server reads back the old value, and the reason is in
    /rosout (an ERROR of the node naming the key and the rule);
  * shortens tau1 to 5 ms at the next sample (below the plant's vehicle_state batching, which must shrink
    in time or the loop stalls), and sets p = 2600 at the next sample.
Then: exactly the three accepted changes were announced on parameter_changes with their stamps, the plant's
summary lists them, and lk_simulate given the announced changes (--change) writes a log bit-identical to the
run's, which differs from the run without changes from the first change on.

Parameters: ~ns, ~log_file, ~reference_configs, ~reference_sets, ~timeout.
"""
import math
import os
import sys
import time
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client
from rosgraph_msgs.msg import Log

from lane_keeping.msg import ParameterChange
from lk_test_support import StatusWatcher, compare_logs, run_lk_simulate, summary_changes, temp_csv, wait_connected


class CheckReconfigure(unittest.TestCase):
    def test_reconfigure_in_lockstep(self):
        ns = rospy.get_param('~ns')
        timeout = rospy.get_param('~timeout', 150.0)
        watcher = StatusWatcher(ns)
        announced = []
        logs = []
        changes_sub = rospy.Subscriber('/%s/parameter_changes' % ns, ParameterChange, announced.append,
                                       queue_size=100)
        rospy.Subscriber('/rosout', Log, logs.append, queue_size=1000)
        tracker = Client('/%s/path_tracking' % ns, timeout=60)
        actuator = Client('/%s/steering_actuator' % ns, timeout=60)

        # The servers start from the loaded configuration (launch: k_y = 0.02, p = 2500), not the .cfg's.
        shown = tracker.get_configuration(timeout=10)
        self.assertEqual((shown['k_psi'], shown['k_y'], shown['tau1'], shown['apply_at']), (0.8, 0.02, 0.2, 0.0))
        shown = actuator.get_configuration(timeout=10)
        self.assertEqual((shown['p'], shown['tau2']), (2500.0, 1e-4))

        self.assertTrue(watcher.wait_running(60), 'the run did not start')
        # The announcements are not latched: connect to all three nodes' parameter_changes first.
        found = wait_connected(changes_sub, '/%s/parameter_changes' % ns, 3, 60)
        self.assertEqual(changes_sub.get_num_connections(), 3, 'parameter_changes publishers: %s' % found)
        # A change at a stamped time, well ahead of the run.
        answer = tracker.update_configuration({'k_psi': 1.2, 'apply_at': 4.0})
        self.assertEqual(answer['k_psi'], 1.2)
        self.assertEqual(answer['apply_at'], 0.0)  # one-shot
        # Refused: the value stays, the reason is logged.
        answer = tracker.update_configuration({'k_psi': float('nan')})
        self.assertEqual(answer['k_psi'], 1.2)
        answer = tracker.update_configuration({'tau1': 10.5})
        self.assertEqual(answer['tau1'], 0.2)
        answer = actuator.update_configuration({'tau2': 0.0})
        self.assertEqual(answer['tau2'], 1e-4)
        # Accepted at the next sample.
        answer = tracker.update_configuration({'tau1': 0.005})
        self.assertEqual(answer['tau1'], 0.005)
        answer = actuator.update_configuration({'p': 2600.0})
        self.assertEqual(answer['p'], 2600.0)
        time.sleep(0.5)
        self.assertEqual(tracker.get_configuration(timeout=5)['k_psi'], 1.2)  # read back from the server
        self.assertEqual(tracker.get_configuration(timeout=5)['tau1'], 0.005)
        self.assertEqual(actuator.get_configuration(timeout=5)['tau2'], 1e-4)

        status = watcher.wait_end(timeout)
        self.assertIsNotNone(status)
        self.assertEqual(status.state, 1, '%s: run did not complete: %s' % (ns, status.message))
        time.sleep(0.5)

        # The reasons, in /rosout.
        def logged(node, *parts):
            return any(m.name == '/%s/%s' % (ns, node) and m.level == Log.ERROR and all(p in m.msg for p in parts)
                       for m in logs)
        self.assertTrue(logged('path_tracking', 'refused tracker.k_psi = .nan', 'tracker.k_psi = nan'),
                        'no ERROR naming tracker.k_psi = nan in /rosout')
        self.assertTrue(logged('path_tracking', 'refused delays.pose_to_tracker = 10.5',
                               'delays.pose_to_tracker = 10.5 s, must be in [0, 10] s'),
                        'no ERROR naming delays.pose_to_tracker = 10.5 s in /rosout')
        self.assertTrue(logged('steering_actuator', 'refused tau2', 'delays.desired_steering_to_actuator = 0',
                               'cannot run in lockstep'),
                        'no ERROR naming tau2 = 0 and the lockstep schedule in /rosout')

        # Exactly the accepted changes were announced (tau1: 1, p: 1, k_psi: 1), with their stamps.
        by_key = {}
        for m in announced:
            by_key.setdefault(m.key, []).append(m)
        rospy.loginfo('announced: %s', [(m.key, m.header.stamp.to_sec(), m.old_value, m.new_value, m.change)
                                        for m in announced])
        self.assertEqual(sorted(by_key), ['actuator.p', 'delays.pose_to_tracker', 'tracker.k_psi'])
        self.assertTrue(all(len(v) == 1 for v in by_key.values()), by_key)
        k_psi = by_key['tracker.k_psi'][0]
        self.assertEqual((k_psi.header.stamp.secs, k_psi.header.stamp.nsecs), (4, 0))
        self.assertEqual((k_psi.old_value, k_psi.new_value, k_psi.change), ('0.8', '1.2', '4:tracker.k_psi=1.2'))
        self.assertEqual(k_psi.node, '/%s/path_tracking' % ns)
        tau1 = by_key['delays.pose_to_tracker'][0]
        self.assertEqual((tau1.old_value, tau1.new_value), ('0.2', '0.005'))
        self.assertEqual(tau1.header.stamp.nsecs % 1000000, 0)  # on the tracker's 1 ms grid
        self.assertGreater(tau1.header.stamp.to_sec(), 0.0)
        self.assertLess(tau1.header.stamp.to_sec(), 4.0)
        p = by_key['actuator.p'][0]
        self.assertEqual((p.old_value, p.new_value, p.node), ('2500', '2600', '/%s/steering_actuator' % ns))
        self.assertEqual(p.header.stamp.nsecs % 100000, 0)  # on the actuator's 0.1 ms grid

        # The summary lists them in stamp order.
        listed = summary_changes(status.summary)
        rospy.loginfo('summary lists: %s', listed)
        self.assertEqual(len(listed), 3, status.summary)
        self.assertIn('t = 4 s: tracker.k_psi 0.8 -> 1.2 (path_tracking)', listed)

        # Reproduced in-process from the announcements alone, bit for bit.
        configs = rospy.get_param('~reference_configs')
        sets = rospy.get_param('~reference_sets')
        reference = temp_csv('reconfigure_reference')
        code, out = run_lk_simulate(configs, sets, reference, [m.change for m in announced])
        self.assertEqual(code, 0, out)
        log_file = rospy.get_param('~log_file')
        identical, worst, rows_ros, rows_ref, first = compare_logs(log_file, reference)
        rospy.loginfo('ROS log %d rows vs lk_simulate --change %d rows: %s (max |difference| %g)', rows_ros, rows_ref,
                      'bit-identical' if identical else 'differ: ' + first, worst)
        self.assertTrue(identical, 'differs from lk_simulate --change: %s' % first)
        self.assertEqual(rows_ros, 6001)
        # ... and the changes did something: without them the log differs, from the first change on.
        unchanged = temp_csv('reconfigure_unchanged')
        code, out = run_lk_simulate(configs, sets, unchanged)
        self.assertEqual(code, 0, out)
        identical, worst, _, _, first = compare_logs(log_file, unchanged)
        rospy.loginfo('without the changes: %s', first)
        self.assertFalse(identical)
        first_row = int(first.split()[1].rstrip(':'))
        first_change = min(m.header.stamp.to_sec() for m in announced)
        self.assertTrue(math.isclose(first_row / 1000.0, first_change) or first_row / 1000.0 > first_change,
                        'rows before the first change (%.4f s) differ: %s' % (first_change, first))
        os.remove(reference)
        os.remove(unchanged)


if __name__ == '__main__':
    rospy.init_node('check_reconfigure')
    rostest.rosrun('lane_keeping', 'check_reconfigure', CheckReconfigure, sys.argv)
