#!/usr/bin/env python3
"""rostest checker for one or more lockstep runs of closed_loop.launch (each in its namespace).

Parameter ~runs: list of
  ns:                 namespace of the run (its plant publishes <ns>/run_status)
  log_file:           the CSV the plant writes
  expect_state:       completed | diverged
  reference_configs:  config files for lk_simulate; with reference_sets, the in-process run to compare with
  reference_sets:     --set key=value list
  reference_changes:  --change T:key=value list (runtime changes, the same the run was given)
  summary_changes:    the lines the summary's 'changes:' block must hold (as lk_simulate prints them)
  tolerance:          max |difference| of any logged value vs the reference (0: bit-identical)
  summary:            optional checks of the printed summary: steering_hz: [lo, hi], steering_trend,
                      lateral_trend, lateral_rate: [lo, hi], max_final_offset, message_contains
Parameter ~identical_pairs: list of [ns_a, ns_b] whose logs must be bit-identical.
"""
import os
import sys
import unittest

import rospy
import rostest

from lk_test_support import (STATE_NAMES, StatusWatcher, compare_logs, parse_summary, run_lk_simulate,
                             summary_changes, temp_csv)


class CheckRuns(unittest.TestCase):
    def test_runs(self):
        runs = rospy.get_param('~runs')
        pairs = rospy.get_param('~identical_pairs', [])
        timeout = rospy.get_param('~timeout', 120.0)
        watchers = {run['ns']: StatusWatcher(run['ns']) for run in runs}
        problems = []
        for run in runs:
            ns = run['ns']
            status = watchers[ns].wait_end(timeout)
            self.assertIsNotNone(status, '%s: no RunStatus within %.0f s' % (ns, timeout))
            self.assertNotEqual(status.state, 0, '%s: still running after %.0f s' % (ns, timeout))
            state = STATE_NAMES[status.state]
            rospy.loginfo('%s: %s at t = %.4f s, %.3g x real time, %d rows\n%s', ns, state, status.simulated_time,
                          status.real_time_factor, status.log_rows, status.summary)
            if state != run.get('expect_state', 'completed'):
                problems.append('%s: ended %s (%s), expected %s' % (ns, state, status.message, run['expect_state']))
                continue
            if 'reference_configs' in run:
                reference = temp_csv('reference_' + ns)
                code, out = run_lk_simulate(run['reference_configs'], run.get('reference_sets', []), reference,
                                            run.get('reference_changes', []))
                if code not in (0, 3):
                    problems.append('%s: lk_simulate failed (%d): %s' % (ns, code, out))
                    continue
                identical, worst, rows_ros, rows_ref, first = compare_logs(run['log_file'], reference)
                tolerance = run.get('tolerance', 0.0)
                rospy.loginfo('%s: ROS log %d rows vs in-process %d rows: %s (max |difference| %g)', ns, rows_ros,
                              rows_ref, 'bit-identical' if identical else 'differ', worst)
                if rows_ros != rows_ref or worst > tolerance or (tolerance == 0.0 and not identical):
                    problems.append('%s: ROS run differs from lk_simulate: %d vs %d rows, max |difference| %g > %g; '
                                    'first: %s' % (ns, rows_ros, rows_ref, worst, tolerance, first))
                os.remove(reference)
                if 'summary_changes' in run:
                    simulated = summary_changes(out)
                    if simulated != run['summary_changes']:
                        problems.append('%s: lk_simulate lists the changes %s, expected %s' %
                                        (ns, simulated, run['summary_changes']))
            if 'summary_changes' in run:
                listed = summary_changes(status.summary)
                rospy.loginfo('%s: the summary lists %d change(s): %s', ns, len(listed), listed)
                if listed != run['summary_changes']:
                    problems.append('%s: the summary lists the changes %s, expected %s' %
                                    (ns, listed, run['summary_changes']))
            checks = run.get('summary', {})
            if checks:
                got = parse_summary(status.summary)
                rospy.loginfo('%s: summary figures %s', ns, got)
                for key in ('steering_hz', 'lateral_rate'):
                    if key in checks:
                        lo, hi = checks[key]
                        if not (key in got and lo <= got[key] <= hi):
                            problems.append('%s: %s = %s, expected in [%g, %g]' % (ns, key, got.get(key), lo, hi))
                for key in ('steering_trend', 'lateral_trend'):
                    if key in checks and got.get(key) != checks[key]:
                        problems.append('%s: %s = %s, expected %s' % (ns, key, got.get(key), checks[key]))
                if 'max_final_offset' in checks and not abs(got.get('final_offset', 1e9)) <= checks['max_final_offset']:
                    problems.append('%s: final offset %s m > %g m' % (ns, got.get('final_offset'),
                                                                      checks['max_final_offset']))
                if 'message_contains' in checks and checks['message_contains'] not in status.message:
                    problems.append('%s: stop message "%s" lacks "%s"' % (ns, status.message,
                                                                          checks['message_contains']))
        logs = {run['ns']: run['log_file'] for run in runs}
        for a, b in pairs:
            identical, worst, rows_a, rows_b, first = compare_logs(logs[a], logs[b])
            rospy.loginfo('%s vs %s: %d vs %d rows, %s', a, b, rows_a, rows_b,
                          'bit-identical' if identical else 'differ (%s)' % first)
            if not identical:
                problems.append('%s and %s differ: %d vs %d rows, max |difference| %g; first: %s' %
                                (a, b, rows_a, rows_b, worst, first))
        self.assertEqual(problems, [], '\n'.join(problems))


if __name__ == '__main__':
    rospy.init_node('check_runs')
    rostest.rosrun('lane_keeping', 'check_runs', CheckRuns, sys.argv)
