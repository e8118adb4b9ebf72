# Sourced by the other scripts: where things live, and Debian's python first on PATH (the pyenv
# python3 on this machine lacks the ROS modules that catkin, roslaunch and rostest import).
REPO_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_ROOT="${LK_BUILD_ROOT:-$REPO_ROOT/build}"
WS="$BUILD_ROOT/ws"
export PATH="/usr/bin:/bin:$PATH"
export ROS_HOME="${ROS_HOME:-$BUILD_ROOT/ros_home}"
export ROS_LOG_DIR="${ROS_LOG_DIR:-$ROS_HOME/log}"
