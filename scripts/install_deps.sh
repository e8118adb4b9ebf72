#!/usr/bin/env bash
# Installs the Debian 12 packages lane_keeping needs (ROS 1 from Debian, Eigen, yaml-cpp, Ceres,
# GoogleTest, matplotlib, Xvfb, Dask and pytest for lk_fleet; clang 16 with libFuzzer and the sanitizer runtimes
# for the fuzz targets in fuzz/; diagnostic_updater and rosdiagnostic for the gap monitor; dynamic_reconfigure for runtime tuning of the controllers, rosbash for rosrun;
# pybind11, the Python headers, setuptools and catkin_pkg for the Python module, pandas for its logs, nbclient,
# nbformat and ipykernel to run its notebook in the tests). Does nothing when everything is already installed.
set -euo pipefail

PACKAGES=(
  build-essential cmake ccache
  ros-core-dev libroscpp-dev catkin ros-message-generation librostest-dev python3-rostest
  libtf2-ros-dev libtf2-eigen-dev libgeometry-msgs-dev libnav-msgs-dev libvisualization-msgs-dev
  librosbag-dev python3-rosbag libnodeletlib-dev libnodeletlib-tools pluginlib-dev rviz
  libdiagnostic-updater-dev libdiagnostic-msgs-dev python3-diagnostic-msgs libdiagnostic-aggregator-tools rosdiagnostic
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure rosbash
  libeigen3-dev libyaml-cpp-dev libceres-dev libboost-dev libgtest-dev nlohmann-json3-dev python3-matplotlib python3-numpy
  xvfb xauth imagemagick
  python3-distributed python3-dask python3-pytest python3-yaml
  pybind11-dev python3-dev python3-setuptools python3-catkin-pkg python3-pandas
  python3-nbclient python3-nbformat python3-ipykernel
  clang-16 libfuzzer-16-dev libclang-rt-16-dev
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "[install_deps] installing: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
