#!/usr/bin/env python3
"""rostest: a loop node killed mid-run (SIGKILL, no clean shutdown) makes the plant stop within a
bounded time with a message naming the topic and the node; nothing hangs.

Parameter ~cases: list of {ns, kill, expect: [substrings of the stop message]}."""
import os
import signal
import sys
import time
import unittest

try:
    from xmlrpc.client import ServerProxy
except ImportError:  # pragma: no cover
    from xmlrpclib import ServerProxy

import rosgraph
import rospy
import rostest
from rosgraph_msgs.msg import Clock

from lk_test_support import StatusWatcher, read_csv, wait_for


class CheckNodeFailure(unittest.TestCase):
    def test_killed_node_stops_the_plant(self):
        cases = rospy.get_param('~cases')
        bound = rospy.get_param('~detection_bound', 3.0)
        clock = {'t': 0.0}
        rospy.Subscriber('/clock', Clock, lambda m: clock.__setitem__('t', m.clock.to_sec()), queue_size=1)
        watchers = {c['ns']: StatusWatcher(c['ns']) for c in cases}
        problems = []
        for case in cases:
            ns, victim = case['ns'], '/%s/%s' % (case['ns'], case['kill'])
            watcher = watchers[ns]
            self.assertTrue(watcher.wait_running(60.0), '%s never started' % ns)
            self.assertFalse(watcher.ended(), '%s ended before the kill: %s' % (ns, watcher.status.message))
            time.sleep(case.get('kill_after', 0.5))  # mid-run
            self.assertFalse(watcher.ended(), '%s ended before the kill: %s' % (ns, watcher.status.message))
            api = rosgraph.Master('/check_node_failure').lookupNode(victim)
            code, _, pid = ServerProxy(api).getPid('/check_node_failure')
            self.assertEqual(code, 1)
            os.kill(pid, signal.SIGKILL)
            killed = time.time()
            wait_for(watcher.ended, 30.0)
            delay = time.time() - killed
            status = watcher.status
            rospy.loginfo('%s: killed %s (pid %d); plant: state %d after %.2f s wall: %s', ns, victim, pid,
                          status.state, delay, status.message)
            if status.state != status.FAILED:
                problems.append('%s: plant state %d, expected FAILED' % (ns, status.state))
                continue
            if delay > bound:
                problems.append('%s: the plant needed %.2f s to notice (bound %.1f s)' % (ns, delay, bound))
            for text in case['expect']:
                if text not in status.message:
                    problems.append('%s: stop message lacks "%s": %s' % (ns, text, status.message))
            if 'log_file' in case:
                problems += self.check_log_up_to_the_stop(ns, case['log_file'], status)
        self.assertEqual(problems, [], '\n'.join(problems))

    @staticmethod
    def check_log_up_to_the_stop(ns, path, status):
        """The log of a stopped run holds every row up to the stop, each complete, with rising t."""
        if not os.path.exists(path):
            return ['%s: no log at %s after the stop' % (ns, path)]
        header, rows = read_csv(path)
        problems = []
        if len(rows) < 10:
            return ['%s: the log holds %d rows only' % (ns, len(rows))]
        if any(len(r) != len(header) or '' in r for r in rows):
            problems.append('%s: a log row is incomplete' % ns)
        t = [float(r[header.index('t')]) for r in rows]
        if any(b <= a for a, b in zip(t, t[1:])):
            problems.append('%s: log times do not rise' % ns)
        # The log's rows reach the stop, less the controllers' delays (a row waits for their outputs).
        if not status.simulated_time - 0.05 <= t[-1] <= status.simulated_time + 1e-9:
            problems.append('%s: log ends at t = %.4f s, the run stopped at %.4f s' % (ns, t[-1], status.simulated_time))
        if 'rows)' not in status.summary:
            problems.append('%s: the stop does not name the log: %r' % (ns, status.summary))
        rospy.loginfo('%s: log %s: %d rows up to t = %.4f s (stopped at %.4f s)', ns, path, len(rows), t[-1],
                      status.simulated_time)
        os.remove(path)
        return problems


if __name__ == '__main__':
    rospy.init_node('check_node_failure')
    rostest.rosrun('lane_keeping', 'check_node_failure', CheckNodeFailure, sys.argv)
