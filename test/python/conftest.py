"""The Python module's tests (docs/python_api.md). Run by the README's test command (catkin's run_tests:
CMakeLists.txt, `pytest lane_keeping_python`), or by hand after a build:

    source build/ws/devel/setup.bash && /usr/bin/python3 -m pytest -q test/python

LK_BIN_DIR names the folder of lk_simulate, lk_gap, lk_stability and lk_gap_benchmark (default: this
worktree's build)."""
import os
import subprocess
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
BIN = os.environ.get("LK_BIN_DIR", os.path.join(REPO, "build", "ws", "devel", "lib", "lane_keeping"))
DEVEL_PYTHON = os.path.join(os.path.dirname(os.path.dirname(BIN)), "lib", "python3", "dist-packages")
if DEVEL_PYTHON not in sys.path and os.path.isdir(DEVEL_PYTHON):
    sys.path.insert(0, DEVEL_PYTHON)  # without setup.bash sourced: the build's devel space
SCENARIOS = os.path.join(REPO, "config", "scenarios")


def tool(name):
    return os.path.join(BIN, name)


def run_tool(*argv, check=True):
    """A tool's (exit status, stdout, stderr)."""
    proc = subprocess.run([tool(argv[0])] + list(argv[1:]), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          timeout=600)
    if check and proc.returncode not in (0, 3):
        raise AssertionError(f"{argv[0]} exited {proc.returncode}: {proc.stderr}")
    return proc.returncode, proc.stdout, proc.stderr


def csv_text(columns, values):
    """A log as lk_simulate --out writes it: the header, then every value with %.17g."""
    lines = [",".join(columns)]
    lines += [",".join("%.17g" % v for v in row) for row in values.tolist()]
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="session")
def lk():
    import lane_keeping
    return lane_keeping
