#!/usr/bin/env python3
"""rostest: the clock jumping backwards. The path tracker and the steering actuator, without the plant,
are fed from a bag played in a loop (`rosbag play --loop --clock`): a 2 s run of Fig 6 written into a bag
from lk_simulate's log (vehicle_state in 10 ms batches, measured_steering at 1 kHz). Each time the bag
starts again, the clock and the stamps go back by 2 s. Each controller must say so (a warning naming the
jump) and restart from its initial state, so that every pass gives exactly the outputs of the first --
the same desired steering and torque samples, same stamps, same values, a pass losing at most its last
50 ms at the jump -- instead of rejecting the second pass as stale and going silent."""
import math
import os
import subprocess
import sys
import tempfile
import time
import unittest

import rosbag
import rosgraph
import rospy
import rostest
from lane_keeping.msg import (DesiredSteeringArray, MeasuredSteering, MeasuredSteeringArray, SteeringTorqueArray,
                              VehicleState, VehicleStateArray)
from rosgraph_msgs.msg import Log

from lk_test_support import read_csv, run_lk_simulate, temp_csv, wait_for


TAIL = 0.05  # [s] how much of its end a pass may lose at a jump


def write_bag(csv_path, bag_path, ns):
    """The log's rows as the plant would publish them: vehicle_state in 10-row batches, measured_steering
    one sample a row. Returns (rows, first stamp, last stamp)."""
    header, rows = read_csv(csv_path)
    col = {name: i for i, name in enumerate(header)}

    def value(row, name):
        return float(row[col[name]])

    with rosbag.Bag(bag_path, 'w') as bag:
        batch = VehicleStateArray()
        for i, row in enumerate(rows):
            stamp = rospy.Time.from_sec(value(row, 't'))
            s = VehicleState()
            s.header.stamp = stamp
            s.x, s.y, s.psi = value(row, 'x'), value(row, 'y'), value(row, 'psi')
            s.delta, s.steering_rate = value(row, 'delta'), value(row, 'delta_rate')
            s.lateral_velocity, s.yaw_rate = value(row, 'sigma1'), value(row, 'yaw_rate')
            s.speed, s.lateral_acceleration = value(row, 'v'), value(row, 'ay')
            s.x_dot = s.speed * math.cos(s.psi) - s.lateral_velocity * math.sin(s.psi)
            s.y_dot = s.speed * math.sin(s.psi) + s.lateral_velocity * math.cos(s.psi)
            s.slip_angle_front, s.slip_angle_rear = value(row, 'alpha_f'), value(row, 'alpha_r')
            s.force_front, s.force_rear = value(row, 'force_f'), value(row, 'force_r')
            s.moment_front, s.moment_rear = value(row, 'moment_f'), value(row, 'moment_r')
            s.steering_torque = value(row, 'torque_applied')
            batch.samples.append(s)
            if len(batch.samples) == 10 or i == len(rows) - 1:
                batch.header.stamp = stamp
                bag.write('/%s/vehicle_state' % ns, batch, stamp)
                batch = VehicleStateArray()
            m = MeasuredSteering()
            m.header.stamp = stamp
            m.delta, m.delta_rate = s.delta, s.steering_rate
            measured = MeasuredSteeringArray()
            measured.header.stamp = stamp
            measured.samples.append(m)
            bag.write('/%s/measured_steering' % ns, measured, stamp)
    return len(rows), value(rows[0], 't'), value(rows[-1], 't')


def split_passes(samples):
    """[(stamp, values)] in arrival order -> one list per pass (a new pass where the stamps go back)."""
    passes = [[]]
    for stamp, values in samples:
        if passes[-1] and stamp < passes[-1][-1][0] - 0.5:
            passes.append([])
        passes[-1].append((stamp, values))
    return passes


class CheckClockJump(unittest.TestCase):
    def test_controllers_restart_when_the_clock_jumps_back(self):
        ns = rospy.get_param('~ns')
        wanted = rospy.get_param('~passes')
        reference = temp_csv('clock_jump_reference')
        code, out = run_lk_simulate(rospy.get_param('~reference_configs'), rospy.get_param('~reference_sets'),
                                    reference)
        self.assertEqual(code, 0, out)
        bag_path = tempfile.mktemp(prefix='lk_clock_jump_', suffix='.bag')
        rows, first, last = write_bag(reference, bag_path, ns)
        rospy.loginfo('bag %s: %d rows, %.3f s to %.3f s', bag_path, rows, first, last)

        outputs = {'desired_steering': [], 'steering_torque': []}
        warnings = []
        rospy.Subscriber('/rosout', Log, lambda m: warnings.append(m) if m.level >= Log.WARN else None,
                         queue_size=1000)
        rospy.Subscriber('/%s/desired_steering' % ns, DesiredSteeringArray,
                         lambda m: outputs['desired_steering'].extend(
                             (s.header.stamp.to_sec(), (s.delta_des, s.delta_des_rate)) for s in m.samples),
                         queue_size=100000)
        rospy.Subscriber('/%s/steering_torque' % ns, SteeringTorqueArray,
                         lambda m: outputs['steering_torque'].extend(
                             (s.header.stamp.to_sec(), (s.torque, s.integral)) for s in m.samples),
                         queue_size=100000)
        master = rosgraph.Master('/check_clock_jump')

        def subscribed(topic):
            _, subscribers, _ = master.getSystemState()
            return any(t == topic and any(n.startswith('/%s/' % ns) for n in nodes) for t, nodes in subscribers)

        self.assertTrue(wait_for(lambda: subscribed('/%s/vehicle_state' % ns) and
                                 subscribed('/%s/measured_steering' % ns), 60.0), 'the controllers never subscribed')
        player = subprocess.Popen(['rosbag', 'play', '--clock', '--loop', '-q', '-d', '1', bag_path],
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        try:
            def passes_seen():
                return len(split_passes(list(outputs['steering_torque'])))
            # `wanted` complete passes: the next one has begun.
            done = wait_for(lambda: passes_seen() > wanted, 20.0 + 4.0 * wanted * (last - first))
        finally:
            player.terminate()
            player.wait(10)
            os.remove(bag_path)
        time.sleep(1.0)  # let /rosout deliver
        self.assertTrue(done, 'only %d pass(es) of torque within the time limit; warnings: %s'
                        % (passes_seen(), [w.msg for w in warnings[-5:]]))

        problems = []
        for topic, samples in outputs.items():
            passes = split_passes(samples)[:wanted]
            rospy.loginfo('%s: %s samples per pass, %.4f s to %s s', topic, [len(p) for p in passes],
                          passes[0][0][0], ['%.4f' % p[-1][0] for p in passes])
            # Every pass gives the first pass's samples, sample for sample; one may end a little early (the
            # actuator drops the old pass's last desired samples if they arrive after its restart).
            longest = max(passes, key=len)
            if len(longest) < 10:
                problems.append('%s: the longest pass has %d samples' % (topic, len(longest)))
            for k, p in enumerate(passes, start=1):
                if p != longest[:len(p)]:
                    diff = next(((a, b) for a, b in zip(longest, p) if a != b), None)
                    problems.append('%s: pass %d differs (%d vs %d samples; first difference %s)'
                                    % (topic, k, len(p), len(longest), diff))
                elif p[-1][0] < longest[-1][0] - TAIL:
                    problems.append('%s: pass %d ends at %.4f s, the longest at %.4f s' % (topic, k, p[-1][0],
                                                                                          longest[-1][0]))
        for node in ('path_tracking', 'steering_actuator'):
            jumps = [w.msg for w in warnings if w.name == '/%s/%s' % (ns, node) and 'jumped back' in w.msg]
            rospy.loginfo('/%s/%s: %s', ns, node, jumps[:1])
            if len(jumps) < wanted - 1:
                problems.append('/%s/%s warned of %d clock jump(s), expected at least %d'
                                % (ns, node, len(jumps), wanted - 1))
        self.assertEqual(problems, [], '\n'.join(problems))


if __name__ == '__main__':
    rospy.init_node('check_clock_jump')
    rostest.rosrun('lane_keeping', 'check_clock_jump', CheckClockJump, sys.argv)
