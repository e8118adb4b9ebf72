#!/usr/bin/env python3
"""rostest: samples stamped at times the loop has already passed, injected mid-run into every loop
input, are rejected: a duplicate of the run's first sample, a batch out of order (0.02 s then 0.01 s),
and a flood of stale single-sample messages over one second of wall time: ten for every message of the loop's
own on its slow topics, as many as a Python publisher sends on the fast ones. Each node warns naming the topic, the plant counts the torque samples it rejected in its
summary, nothing stalls, and the log stays bit-identical to lk_simulate's."""
import sys
import time
import unittest

import rospy
import rostest
from lane_keeping.msg import (DesiredSteering, DesiredSteeringArray, MeasuredSteering, MeasuredSteeringArray,
                              SteeringTorque, SteeringTorqueArray, VehicleState, VehicleStateArray)
from rosgraph_msgs.msg import Clock, Log

from lk_test_support import StatusWatcher, compare_logs, run_lk_simulate, temp_csv, wait_for

TOPICS = [  # topic, array type, sample type, the node that must reject it
    ('vehicle_state', VehicleStateArray, VehicleState, 'path_tracking'),
    ('measured_steering', MeasuredSteeringArray, MeasuredSteering, 'steering_actuator'),
    ('desired_steering', DesiredSteeringArray, DesiredSteering, 'steering_actuator'),
    ('steering_torque', SteeringTorqueArray, SteeringTorque, 'vehicle_plant'),
]

SLOW = ('vehicle_state', 'desired_steering')  # a message a tracker cycle; the others one an actuator step


def batch(array_type, sample_type, stamps):
    msg = array_type()
    for s in stamps:
        sample = sample_type()
        sample.header.stamp = rospy.Time.from_sec(s)
        msg.samples.append(sample)
    msg.header.stamp = msg.samples[-1].header.stamp
    return msg


class CheckBadStamps(unittest.TestCase):
    def test_stale_stamps_are_rejected_and_do_not_disturb(self):
        ns = rospy.get_param('~ns')
        warnings = []
        rospy.Subscriber('/rosout', Log, lambda m: warnings.append(m) if m.level >= Log.WARN else None,
                         queue_size=1000)
        # The loop's own messages on each topic (stamped after 0.15 s; the injected ones are older).
        own = {topic: 0 for topic, _, _, _ in TOPICS}

        def count_own(msg, topic):
            if msg.samples and msg.samples[-1].header.stamp.to_sec() > 0.15:
                own[topic] += 1

        counters = [rospy.Subscriber('/%s/%s' % (ns, topic), array_type, count_own, callback_args=topic,
                                     queue_size=100000) for topic, array_type, _, _ in TOPICS]
        sim = {'t': 0.0}
        rospy.Subscriber('/clock', Clock, lambda m: sim.__setitem__('t', m.clock.to_sec()), queue_size=1)
        watcher = StatusWatcher(ns)
        publishers = {topic: rospy.Publisher('/%s/%s' % (ns, topic), array_type, queue_size=100000)
                      for topic, array_type, _, _ in TOPICS}
        self.assertTrue(watcher.wait_running(60.0), 'the run never started')
        self.assertTrue(wait_for(lambda: all(p.get_num_connections() > 1 for p in publishers.values()), 10.0),
                        'injectors did not connect')
        self.assertTrue(wait_for(lambda: sim['t'] > 0.2, 30.0), 'the run did not reach t = 0.2 s')
        self.assertFalse(watcher.ended(), 'the run ended before the injection; make it longer')
        injected = {topic: 0 for topic in own}
        for topic, array_type, sample_type, _ in TOPICS:
            publishers[topic].publish(batch(array_type, sample_type, [0.0]))           # a duplicate
            publishers[topic].publish(batch(array_type, sample_type, [0.02, 0.01]))    # out of order
            injected[topic] += 3
        # The flood: for a second of wall time, ten stale messages on each topic for every message of the
        # loop's own on it (counted as they arrive), the loop's four topics at once.
        start = time.time()
        for topic in own:
            own[topic] = 0
        flood = {topic: 0 for topic in own}

        deadline = start + 1.0

        def top_up(target):
            # The slow topics first, to their tenfold; the fast ones in turns of at most 20 messages each.
            for topic, array_type, sample_type, _ in TOPICS:
                for _ in range(10**9 if topic in SLOW else 20):
                    if flood[topic] >= target(topic) or time.time() >= deadline:
                        break
                    publishers[topic].publish(batch(array_type, sample_type, [0.001 * (flood[topic] % 100)]))
                    flood[topic] += 1

        while time.time() < deadline and not watcher.ended():
            top_up(lambda topic: 10 * own[topic])
            time.sleep(0.0005)
        seconds = time.time() - start
        during = dict(own)
        for topic, array_type, sample_type, _ in TOPICS:  # the slow topics' last few, owed at the deadline
            while topic in SLOW and flood[topic] < 10 * during[topic]:
                publishers[topic].publish(batch(array_type, sample_type, [0.001 * (flood[topic] % 100)]))
                flood[topic] += 1
        flooded_while_running = not watcher.ended()
        for topic in own:
            injected[topic] += flood[topic]
        rospy.loginfo('flood over %.2f s wall: the loop\'s own messages %s, stale ones sent %s', seconds, during,
                      flood)
        status = watcher.wait_end(150.0)
        self.assertIsNotNone(status)
        self.assertTrue(flooded_while_running, 'the run ended during the flood; make it longer')
        self.assertEqual(status.state, status.COMPLETED, status.message)
        # /rosout delivers the nodes' warnings some time after the run ends: under load (tests in parallel on
        # two cores) more than the 1 s once waited. Wait until every expected one is there, for 20 s at most.
        def delivered():
            return all(any(w.name == '/%s/%s' % (ns, node) and '/%s/%s' % (ns, topic) in w.msg and 'rejected' in w.msg
                           for w in list(warnings)) for topic, _, _, node in TOPICS)
        wait_for(delivered, 20.0)

        problems = []
        for topic, _, _, node in TOPICS:
            full_topic, full_node = '/%s/%s' % (ns, topic), '/%s/%s' % (ns, node)
            found = [w for w in warnings if w.name == full_node and full_topic in w.msg and 'rejected' in w.msg]
            rospy.loginfo('%s on %s: %s', full_node, full_topic, found[-1].msg if found else 'NO WARNING')
            if not found:
                problems.append('no warning from %s about %s' % (full_node, full_topic))
            if during[topic] == 0:
                problems.append('%s: no message of the loop\'s own during the flood' % topic)
            elif topic in SLOW and flood[topic] < 10 * during[topic]:
                # The loop's slow topics (one message a tracker cycle) get their tenfold; on the fast ones
                # (a message an actuator step) the Python injector sends what it can, logged above.
                problems.append('%s: %d stale messages against %d of the loop\'s own' % (topic, flood[topic],
                                                                                       during[topic]))
        rospy.loginfo('plant summary:\n%s', status.summary)
        expect = 'rejected inputs:        %d on /%s/steering_torque' % (injected['steering_torque'], ns)
        if expect not in status.summary:
            problems.append('the summary does not count the %d rejected torque samples: %s'
                            % (injected['steering_torque'], status.summary))
        reference = temp_csv('stamps_reference')
        code, out = run_lk_simulate(rospy.get_param('~reference_configs'), rospy.get_param('~reference_sets'),
                                    reference)
        self.assertEqual(code, 0, out)
        identical, worst, rows_ros, rows_ref, first = compare_logs(rospy.get_param('~log_file'), reference)
        rospy.loginfo('log with injected stale stamps vs in-process: %d vs %d rows, %s', rows_ros, rows_ref,
                      'bit-identical' if identical else 'differ: ' + first)
        if not identical:
            problems.append('the run was disturbed: %s (max |difference| %g)' % (first, worst))
        self.assertEqual(problems, [], '\n'.join(problems))


if __name__ == '__main__':
    rospy.init_node('check_bad_stamps')
    rostest.rosrun('lane_keeping', 'check_bad_stamps', CheckBadStamps, sys.argv)
