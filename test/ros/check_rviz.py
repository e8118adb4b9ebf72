#!/usr/bin/env python3
"""rostest: rviz, started with the shipped rviz/lane_keeping.rviz under xvfb-run while the loop runs in
realtime, shows the car and the lane. Takes a screenshot and counts, inside the 3D view, the pixels of
each display's colour: car body (blue), lane boundaries (yellow), lane centre (cyan), driven trail
(magenta). A display that is broken (wrong topic, frame or type, rviz failing to render) leaves its
colour out and fails the test."""
import os
import subprocess
import sys
import unittest

import numpy as np
import rospy
import rostest
from matplotlib import image

from lk_test_support import StatusWatcher, package_path

# (name, predicate on r, g, b in 0..255, minimum pixel count)
CLASSES = [
    ('car body (blue)', lambda r, g, b: (b > 150) & (r < 110) & (g < 140) & (b - g > 60), 1200),
    ('lane boundaries (yellow)', lambda r, g, b: (r > 180) & (g > 150) & (b < 90), 1000),
    ('lane centre (cyan)', lambda r, g, b: (r < 90) & (g > 140) & (b > 180), 300),
    ('driven trail (magenta)', lambda r, g, b: (r > 170) & (b > 170) & (g < 130), 100),
]


def render_area(rgb):
    """Bounding box of rviz's 3D view: the pixels of its background colour (48, 48, 48)."""
    background = np.all(np.abs(rgb - 48) <= 2, axis=2)
    cols = np.where(background.mean(axis=0) > 0.4)[0]
    rows = np.where(background.mean(axis=1) > 0.4)[0]
    if len(rows) < 100 or len(cols) < 100:
        return None
    return rows.min(), rows.max() + 1, cols.min(), cols.max() + 1


class CheckRviz(unittest.TestCase):
    def test_rviz_shows_car_and_lane(self):
        ns = rospy.get_param('~ns')
        wait = rospy.get_param('~wait', 12.0)
        out = rospy.get_param('~screenshot', '/tmp/lk_rviz_screenshot.png')
        config = os.path.join(package_path(), 'rviz', 'lane_keeping.rviz')
        script = os.path.join(package_path(), 'test', 'ros', 'rviz_screenshot.sh')
        watcher = StatusWatcher(ns)
        self.assertTrue(watcher.wait_running(60.0), 'the loop never started')
        if os.path.exists(out):
            os.remove(out)
        cmd = ['xvfb-run', '-a', '-s', '-screen 0 1280x1024x24', script, config, out, str(wait)]
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                              timeout=wait + 90)
        self.assertTrue(os.path.exists(out), 'no screenshot: %s' % proc.stdout[-3000:])
        rgb = (image.imread(out)[:, :, :3] * 255.0).astype(np.int32)
        area = render_area(rgb)
        self.assertIsNotNone(area, 'no 3D view in the screenshot %s (rviz did not render)' % out)
        top, bottom, left, right = area
        view = rgb[top:bottom, left:right]
        r, g, b = view[:, :, 0], view[:, :, 1], view[:, :, 2]
        problems = []
        for name, predicate, minimum in CLASSES:
            count = int(np.count_nonzero(predicate(r, g, b)))
            rospy.loginfo('%s: %d pixels (need %d) in the %dx%d view of %s', name, count, minimum, right - left,
                          bottom - top, out)
            if count < minimum:
                problems.append('%s: %d pixels, need %d' % (name, count, minimum))
        self.assertEqual(problems, [], 'screenshot %s:\n%s\nrviz output:\n%s' %
                         (out, '\n'.join(problems), proc.stdout[-2000:]))


if __name__ == '__main__':
    rospy.init_node('check_rviz')
    rostest.rosrun('lane_keeping', 'check_rviz', CheckRviz, sys.argv)
