#!/usr/bin/env python3
"""A node that keeps every core busy (one spinning process per core, or ~count) until it is shut down:
the load under which a lockstep run must still give a bit-identical log (issue 16 item 5)."""
import multiprocessing
import os
import signal

import rospy


def spin(parent):
    # Spin until the parent is gone (a killed launch must not leave busy processes behind).
    x = 0
    while os.getppid() == parent:
        for _ in range(100000):
            x = (x * 1103515245 + 12345) & 0x7FFFFFFF


if __name__ == '__main__':
    rospy.init_node('busy_load')
    count = rospy.get_param('~count', 0) or multiprocessing.cpu_count()
    workers = [multiprocessing.Process(target=spin, args=(os.getpid(),), daemon=True) for _ in range(count)]
    for w in workers:
        w.start()
    rospy.loginfo('busy_load: %d spinning processes', count)
    rospy.spin()
    for w in workers:
        os.kill(w.pid, signal.SIGKILL)
