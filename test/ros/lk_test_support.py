"""Helpers shared by the lane_keeping rostests: wait for a run's end, run lk_simulate on the same
configuration, compare logs, parse the summary the plant prints."""
import csv
import os
import re
import subprocess
import tempfile
import time

import rospy
import roslib.packages
from lane_keeping.msg import RunStatus

STATE_NAMES = {RunStatus.RUNNING: 'running', RunStatus.COMPLETED: 'completed', RunStatus.DIVERGED: 'diverged',
               RunStatus.FAILED: 'failed'}


def package_path():
    import rospkg
    return rospkg.RosPack().get_path('lane_keeping')


def lk_simulate_binary():
    for path in roslib.packages.find_node('lane_keeping', 'lk_simulate'):
        return path
    raise RuntimeError('lk_simulate not found (build the package first)')


class StatusWatcher(object):
    """Latest RunStatus of one run (namespace)."""

    def __init__(self, ns):
        self.ns = ns
        self.status = None
        self.first_running = None
        self.sub = rospy.Subscriber('/%s/run_status' % ns, RunStatus, self._on_status, queue_size=10)

    def _on_status(self, msg):
        if msg.state == RunStatus.RUNNING and self.first_running is None:
            self.first_running = time.time()
        self.status = msg

    def running(self):
        return self.status is not None and self.status.state == RunStatus.RUNNING

    def ended(self):
        return self.status is not None and self.status.state != RunStatus.RUNNING

    def wait_running(self, timeout):
        return wait_for(self.running, timeout) or self.ended()

    def wait_end(self, timeout):
        wait_for(self.ended, timeout)
        return self.status


def wait_for(predicate, timeout, period=0.02):
    deadline = time.time() + timeout
    while time.time() < deadline and not rospy.is_shutdown():
        if predicate():
            return True
        time.sleep(period)
    return predicate()


def publishers_of(topic):
    """Callers the master lists as publishing `topic` (a resolved name)."""
    import rosgraph
    publishers, _, _ = rosgraph.Master(rospy.get_name()).getSystemState()
    for name, nodes in publishers:
        if name == topic:
            return list(nodes)
    return []


def wait_connected(subscriber, topic, expected, timeout):
    """Waits until `subscriber` has a connection to each of at least `expected` publishers of `topic`.
    A message published before its connection is up is lost (not latched); a check that counts
    announcements must not start the changes before then (reconfigure_in_lockstep lost the actuator's
    announcement once under ctest -j2). Returns the publishers found."""
    wait_for(lambda: len(publishers_of(topic)) >= expected and
             subscriber.get_num_connections() >= len(publishers_of(topic)), timeout, period=0.05)
    return publishers_of(topic)


def run_lk_simulate(configs, sets, out_csv, changes=()):
    """Runs the in-process loop on the same files (and runtime changes, "T:key=value"); returns
    (exit code, stdout)."""
    cmd = [lk_simulate_binary()]
    for c in configs:
        cmd += ['--config', c]
    for s in sets:
        cmd += ['--set', s]
    for c in changes:
        cmd += ['--change', c]
    cmd += ['--out', out_csv]
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    return proc.returncode, proc.stdout


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def compare_logs(path_a, path_b):
    """(identical, max |difference| over every value, rows a, rows b, first difference text)."""
    header_a, rows_a = read_csv(path_a)
    header_b, rows_b = read_csv(path_b)
    if header_a != header_b:
        return False, float('inf'), len(rows_a), len(rows_b), 'headers differ'
    worst = 0.0
    first = ''
    for i, (ra, rb) in enumerate(zip(rows_a, rows_b)):
        for name, x, y in zip(header_a, ra, rb):
            if x != y:
                d = abs(float(x) - float(y))
                worst = max(worst, d)
                if not first:
                    first = 'row %d column %s: %s vs %s' % (i, name, x, y)
    identical = worst == 0.0 and len(rows_a) == len(rows_b) and not first
    return identical, worst, len(rows_a), len(rows_b), first


def temp_csv(name):
    fd, path = tempfile.mkstemp(prefix='lk_%s_' % name, suffix='.csv')
    os.close(fd)
    return path


_STEERING = re.compile(r'steering mode \(d-d_des\):\s+([0-9.eE+-]+) Hz over (\d+) cycles, (\w+) \(growth rate ([0-9.eE+-]+)')
_LATERAL_TREND = re.compile(r'lateral mode \(e_y\):.*?(decays|grows|steady|none)[ ,(]+(?:growth )?rate ([0-9.eE+-]+) 1/s')
_FINAL = re.compile(r'final lateral offset:\s+([0-9.eE+-]+) m')


def summary_changes(text):
    """The lines of the summary's 'changes:' block ("t = 10 s: key old -> new (node)")."""
    lines = text.splitlines()
    out = []
    for i, line in enumerate(lines):
        if line.startswith('changes:'):
            out.append(line[len('changes:'):].strip())
            for more in lines[i + 1:]:
                if not more.startswith(' ' * 10):
                    break
                out.append(more.strip())
            break
    return out


def parse_summary(text):
    """Numbers of interest from the lk_simulate summary text."""
    out = {}
    m = _STEERING.search(text)
    if m:
        out['steering_hz'] = float(m.group(1))
        out['steering_trend'] = m.group(3)
        out['steering_rate'] = float(m.group(4))
    m = _LATERAL_TREND.search(text)
    if m:
        out['lateral_trend'] = m.group(1)
        out['lateral_rate'] = float(m.group(2))
    m = _FINAL.search(text)
    if m:
        out['final_offset'] = float(m.group(1))
    return out
