#!/usr/bin/env python3
"""rostest: the live gap monitor's statuses over a closed-loop run (test/gap_monitor_*.test).

Collects every lane_keeping/GapStatus on /<ns>/gap_status and every gap status on /diagnostics until
the run ends, then asserts, per the private parameters:
  ~expect_warn    subsystem that must go WARN or ERROR ('' = none may: a no-effect run)
  ~onset          [s] when the effect sets in: no WARN/ERROR before it, the WARN within ~max_delay after
  ~max_delay      [s] of stamp time
  ~min_statuses   evaluations that must have been published
  ~reconfigure    check the monitor's dynamic_reconfigure after the run: error_excess below warn_excess is
                  refused (the old value reads back), a valid warn_excess is taken
  ~record         a file to write the (stamp, subsystem, level, net excess) rows to ('' = none), for
                  comparing a live run with a bag replay (compare_gap_statuses.py)
"""
import sys
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from lane_keeping.msg import GapStatus, SubsystemGapStatus

from lk_test_support import StatusWatcher

LEVEL = {0: 'OK', 1: 'WARN', 2: 'ERROR', 3: 'STALE'}


class GapMonitorTest(unittest.TestCase):
    def test_statuses(self):
        rospy.init_node('check_gap_monitor', anonymous=True)
        ns = rospy.get_param('~ns', 'lane_keeping')
        expect_warn = rospy.get_param('~expect_warn', '')
        onset = float(rospy.get_param('~onset', 0.0))
        max_delay = float(rospy.get_param('~max_delay', 3.0))
        min_statuses = int(rospy.get_param('~min_statuses', 10))
        record = rospy.get_param('~record', '')
        statuses, diagnostics = [], []
        rospy.Subscriber('/%s/gap_status' % ns, GapStatus, statuses.append, queue_size=1000)
        rospy.Subscriber('/diagnostics', DiagnosticArray,
                         lambda m: diagnostics.extend(s for s in m.status if ' gap ' in ' ' + s.name.split(':')[-1] + ' '),
                         queue_size=1000)
        watcher = StatusWatcher(ns)
        status = watcher.wait_end(600.0)
        self.assertIsNotNone(status, 'the run did not end')
        rospy.sleep(rospy.Duration(0))  # (sim time: returns at once)
        import time
        time.sleep(3.0)  # the last evaluations of the window (the monitor runs behind a lockstep loop)

        rows = [(s.header.stamp.to_sec(), sub.name, sub.level, sub.net_excess) for s in statuses for sub in s.subsystems]
        for stamp, name, level, net in rows:
            if level in (SubsystemGapStatus.WARN, SubsystemGapStatus.ERROR):
                print('%.2f s: %s %s (net excess %.4f)' % (stamp, name, LEVEL[level], net))
        if record:
            with open(record, 'w') as f:
                for row in rows:
                    f.write('%.6f %s %d %.9f\n' % row)
        self.assertGreaterEqual(len(statuses), min_statuses,
                                'only %d gap statuses published (expected >= %d)' % (len(statuses), min_statuses))
        self.assertTrue(diagnostics, 'no gap status on /diagnostics')
        self.assertEqual(sorted(set(d.name.split(': ')[-1] for d in diagnostics)),
                         ['gap actuator', 'gap chassis', 'gap steering', 'gap tracker'])
        alarms = [(t, n, l, x) for (t, n, l, x) in rows if l in (SubsystemGapStatus.WARN, SubsystemGapStatus.ERROR)]
        if not expect_warn:
            self.assertEqual(alarms, [], 'WARN/ERROR in a run without an effect: %s' % alarms[:5])
            judged = [r for r in rows if r[2] == SubsystemGapStatus.OK]
            self.assertGreater(len(judged), len(rows) // 2, 'most statuses should be judged OK, not STALE')
            return
        early = [a for a in alarms if a[0] < onset]
        self.assertEqual(early, [], 'WARN/ERROR before the effect set in at %g s: %s' % (onset, early[:5]))
        first = [a for a in alarms if a[1] == expect_warn]
        self.assertTrue(first, '%s never went WARN/ERROR' % expect_warn)
        self.assertLessEqual(first[0][0] - onset, max_delay,
                             '%s went WARN %.2f s after the onset (allowed %.1f s)' % (expect_warn, first[0][0] - onset, max_delay))
        others = [a for a in alarms if a[1] != expect_warn]
        self.assertEqual(others, [], 'subsystems other than %s went WARN/ERROR: %s' % (expect_warn, others[:5]))
        diag_alarm = [d for d in diagnostics if d.level in (DiagnosticStatus.WARN, DiagnosticStatus.ERROR)]
        self.assertTrue(any(expect_warn in d.name for d in diag_alarm), '/diagnostics never showed the WARN')
        if rospy.get_param('~reconfigure', False):
            self.check_reconfigure('/%s/gap_monitor' % ns)

    def check_reconfigure(self, server):
        import dynamic_reconfigure.client
        client = dynamic_reconfigure.client.Client(server, timeout=30)
        before = client.get_configuration(timeout=10)
        refused = client.update_configuration({'error_excess': 0.01})  # below warn_excess 0.03
        self.assertAlmostEqual(refused['error_excess'], before['error_excess'], msg='error_excess below warn_excess taken')
        taken = client.update_configuration({'warn_excess': 0.05})
        self.assertAlmostEqual(taken['warn_excess'], 0.05)  # (the service's answer: the values the server holds)


if __name__ == '__main__':
    rostest.rosrun('lane_keeping', 'check_gap_monitor', GapMonitorTest, sys.argv)
