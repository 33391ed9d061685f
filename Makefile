# The two commands of the README: `make demo` and `make test`. Both install what is missing
# (as root, with apt-get), build the package in a catkin workspace under build/, and run.
SHELL := /bin/bash
.SHELLFLAGS := -eo pipefail -c
# A pyenv python3 without catkin_pkg may come first on PATH; ROS needs Debian's.
export PATH := /usr/bin:/bin:/usr/sbin:/sbin:$(PATH)
export ROS_HOME := $(CURDIR)/build/ros_home
export ROS_LOG_DIR := $(CURDIR)/build/ros_home/log
# The tests and the demo run every node on this machine. A bare machine or a container may not
# resolve its own hostname, which ROS nodes advertise by default: use localhost unless the user
# chose a name or address for ROS already.
ifeq ($(strip $(ROS_HOSTNAME)$(ROS_IP)),)
export ROS_HOSTNAME := localhost
endif

WS ?= $(CURDIR)/build/ws
JOBS ?= 2
# Build some components only, e.g. COMPONENTS='gnss;relative_state' (default: all of them).
COMPONENTS ?=
# Extra CMake arguments passed to catkin_make as they are.
CMAKE_ARGS ?=
DEV := $(WS)/devel/setup.bash
# Debian packages for every dependency that package.xml declares, as rosdep.yaml maps them, plus
# the compilers and ROS's core. test/python/test_dependencies.py fails when a declared dependency
# (or a Python module a script imports) has no package here: keep package.xml, rosdep.yaml and
# this list in step.
APT_PACKAGES := build-essential cmake clang libclang-rt-14-dev \
  catkin python3-catkin-pkg ros-core-dev ros-message-generation ros-message-runtime \
  libroscpp-dev librosbag-dev python3-rosbag libstd-msgs-dev python3-std-msgs \
  libsensor-msgs-dev python3-sensor-msgs libgeometry-msgs-dev python3-geometry-msgs libdiagnostic-msgs-dev python3-diagnostic-msgs \
  libdiagnostic-updater-dev libros-rosgraph-msgs-dev python3-rosgraph-msgs \
  python3-rospy python3-rosgraph python3-rostest librostest-dev python3-rosunit \
  python3-roslaunch python3-rostopic python3-rosnode python3-rosparam python3-rosmaster \
  rosout rosbash \
  libnlopt-cxx-dev libeigen3-dev libboost-dev libgeographiclib-dev libgtest-dev libbenchmark-dev \
  nlohmann-json3-dev libcli11-dev libtinyxml2-dev libyaml-cpp-dev sumo sumo-tools pybind11-dev python3-dev python3-pandas python3-pytest iproute2 python3-matplotlib python3-numpy python3-pil python3-yaml

.PHONY: check-path deps build demo test unit-tests bench clean print-apt-packages

# catkin runs the tests it builds through a shell with their paths unquoted (its run_tests.py), and
# roslaunch splits node arguments at spaces: from a folder whose path holds whitespace the build
# succeeds, then almost every test and the demo fail far from the cause. A colon ends the build in
# the Makefiles CMake writes ("target pattern contains no '%'"), and splits ROS's path lists
# (CMAKE_PREFIX_PATH, ROS_PACKAGE_PATH). Say so before anything is installed or built.
check-path:
	$(if $(or $(filter-out 1,$(words $(CURDIR))),$(findstring :,$(CURDIR))),$(error the path of this clone \
	  ($(CURDIR)) holds whitespace or a colon: catkin's test runner and roslaunch split paths at spaces, \
	  make and ROS's path lists at colons. Clone or move the repository to a path without either \
	  (e.g. ~/acc_identification) and run make there))

# The list above, one package a line (read by test/python/test_dependencies.py).
print-apt-packages:
	@printf '%s\n' $(APT_PACKAGES)

deps: check-path
	@missing=$$(for p in $(APT_PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing missing packages: $$missing"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	fi

build: deps
	@mkdir -p "$(WS)/src" "$(ROS_LOG_DIR)"
	@touch "$(CURDIR)/build/CATKIN_IGNORE"
	@# The package in the workspace is a folder of links to the repository's entries, all but
	@# build/ itself: linking the whole repository would make a loop that rosrun's find trips on.
	@pkg="$(WS)/src/acc_identification"; [ -L "$$pkg" ] && rm -f "$$pkg"; mkdir -p "$$pkg"; \
	  find "$$pkg" -maxdepth 1 -type l ! -exec test -e {} \; -delete; \
	  for entry in "$(CURDIR)"/* "$(CURDIR)/.ci"; do \
	    [ "$$(basename "$$entry")" = build ] || ln -sfn "$$entry" "$$pkg/"; \
	  done
	cd "$(WS)" && catkin_make -j$(JOBS) -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON '-DACC_COMPONENTS=$(or $(COMPONENTS),all)' $(CMAKE_ARGS) > "$(WS)/catkin_make.log" 2>&1 \
	  || { tail -n 60 "$(WS)/catkin_make.log"; exit 1; }
	@echo "built in $(WS) (log: $(WS)/catkin_make.log)"

demo: build
	@source "$(DEV)" && bash scripts/demo.sh

test: build
	@source "$(DEV)" && JOBS=$(JOBS) bash scripts/run_tests.sh "$(WS)"

bench: build
	@source "$(DEV)" && bash scripts/run_benchmarks.sh "$(WS)"

clean:
	rm -rf build
