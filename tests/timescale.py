"""How long a test may wait for something, on a machine that may be busy.

A test waits for the state it checks, never a fixed time; the limit after
which it gives up is a base in seconds (right for an idle 2-core machine
running ctest -j2) times the scale: RG_TEST_TIME_SCALE where it is set
(tools/test.sh sets it from the load it finds, CMake multiplies ctest's
timeouts by it), and at least the load per core now, so that work started
beside the tests after they began lengthens the waits too.
"""
import os


def time_scale():
    try:
        scale = float(os.environ.get("RG_TEST_TIME_SCALE", "1"))
    except ValueError:
        scale = 1.0
    try:
        scale = max(scale, os.getloadavg()[0] / (os.cpu_count() or 1))
    except OSError:
        pass
    return max(1.0, scale)


def seconds(base):
    """`base` seconds, scaled for how busy the machine is."""
    return base * time_scale()
