# The Python package lane_keeping (src/python/lane_keeping; docs/python_api.md), for catkin_python_setup():
# in devel space catkin relays the package to this source folder, beside the generated message modules and
# the extension module lane_keeping._lane_keeping (CMakeLists.txt). Not for pip: build with scripts/build.sh.
from setuptools import setup

from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["lane_keeping"], package_dir={"": "src/python"}))
