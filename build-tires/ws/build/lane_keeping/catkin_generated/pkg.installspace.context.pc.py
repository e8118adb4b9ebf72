# generated from catkin/cmake/template/pkg.context.pc.in
CATKIN_PACKAGE_PREFIX = ""
PROJECT_PKG_CONFIG_INCLUDE_DIRS = "${prefix}/include;/usr/include/eigen3".split(';') if "${prefix}/include;/usr/include/eigen3" != "" else []
PROJECT_CATKIN_DEPENDS = "".replace(';', ' ')
PKG_CONFIG_LIBRARIES_WITH_PREFIX = "-llane_keeping_core".split(';') if "-llane_keeping_core" != "" else []
PROJECT_NAME = "lane_keeping"
PROJECT_SPACE_DIR = "/work/main/build-tires/ws/install"
PROJECT_VERSION = "0.1.0"
PROJECT_LIB_DIR = "lib"
