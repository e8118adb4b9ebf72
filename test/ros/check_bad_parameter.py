#!/usr/bin/env python3
"""rostest: a bad parameter fails the launch of closed_loop.launch with a message naming it.

Runs roslaunch (against the test's master) with one bad parameter per case and expects it to end by
itself within a time limit, its output naming the key. Cases: an out-of-range delay (three
processes), a non-numeric gain (nodelets), a misspelt key in an overlay file, a key missing from the
parameter server, and bad runtime changes (~changes: a negative friction, a key fixed for a run)."""
import os
import subprocess
import sys
import tempfile
import time
import unittest

import rospy
import rostest

from lk_test_support import package_path


class CheckBadParameter(unittest.TestCase):
    def run_launch(self, ns, args, limit=60.0):
        launch = os.path.join(package_path(), 'launch', 'closed_loop.launch')
        cmd = ['roslaunch', launch, 'ns:=' + ns, 'exit_when_done:=true', 'duration:=1'] + args
        start = time.time()
        try:
            proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                  timeout=limit)
        except subprocess.TimeoutExpired as e:
            self.fail('%s did not end within %.0f s (hang): %s' % (' '.join(cmd), limit, (e.output or '')[-2000:]))
        elapsed = time.time() - start
        rospy.loginfo('%s: ended after %.1f s', ' '.join(args), elapsed)
        return proc.stdout

    def check(self, ns, args, key, value):
        out = self.run_launch(ns, args)
        lines = [l for l in out.splitlines() if key in l]
        rospy.loginfo('%s -> %s', ' '.join(args), lines[:3])
        self.assertTrue(lines, 'no message names %s; output:\n%s' % (key, out[-3000:]))
        self.assertTrue(any(value in l for l in lines), 'the message does not show the value %s: %s' % (value, lines))
        self.assertIn('invalid configuration', out)
        self.assertNotIn('run summary', out)  # nothing ran

    def test_out_of_range_delay_three_processes(self):
        self.check('bad_delay', ['tau1:=-0.5'], 'delays.pose_to_tracker', '-0.5')

    def test_non_numeric_gain_nodelets(self):
        self.check('bad_gain', ['nodelets:=true', 'p:=strong'], 'actuator.p', 'strong')

    def test_misspelt_key_in_an_overlay(self):
        with tempfile.NamedTemporaryFile('w', suffix='.yaml', delete=False) as f:
            f.write('tracker:\n  k_yy: 0.15\n')
        try:
            self.check('bad_key', ['overrides:=' + f.name], 'tracker.k_yy', 'not a known parameter')
        finally:
            os.remove(f.name)


    def test_key_missing_from_the_parameter_server(self):
        # A full configuration (config:=) that lacks a key: every node refuses the partial tree naming the
        # key, rather than filling it with a compiled-in default the user never saw.
        with open(os.path.join(package_path(), 'config', 'default.yaml')) as f:
            lines = [l for l in f if not l.startswith('  mass:')]  # vehicle.mass (the scenario sets no mass)
        with tempfile.NamedTemporaryFile('w', suffix='.yaml', delete=False) as f:
            f.writelines(lines)
        try:
            self.check('missing_key', ['config:=' + f.name], 'vehicle.mass', 'is missing')
        finally:
            os.remove(f.name)

    def test_bad_runtime_change(self):
        self.check('bad_change', ["changes:=['10:steering.coulomb_friction=-3']"], 'steering.coulomb_friction', '-3')

    def test_runtime_change_of_a_fixed_key_nodelets(self):
        self.check('bad_change_key', ['nodelets:=true', "changes:=['1:simulation.step=1e-5']"], 'simulation.step',
                   'cannot change during a run')


if __name__ == '__main__':
    rospy.init_node('check_bad_parameter')
    rostest.rosrun('lane_keeping', 'check_bad_parameter', CheckBadParameter, sys.argv)
