# The two commands of the README: `make demo` and `make test`. Both install what is missing
# (as root, with apt-get), build the package in a catkin workspace under build/, and run.
SHELL := /bin/bash
.SHELLFLAGS := -eo pipefail -c
# A pyenv python3 without catkin_pkg may come first on PATH; ROS needs Debian's.
export PATH := /usr/bin:/bin:/usr/sbin:/sbin:$(PATH)
export ROS_HOME := $(CURDIR)/build/ros_home
export ROS_LOG_DIR := $(CURDIR)/build/ros_home/log

WS ?= $(CURDIR)/build/ws
JOBS ?= 2
# Build some components only, e.g. COMPONENTS='gnss;relative_state' (default: all of them).
COMPONENTS ?=
# Extra CMake arguments passed to catkin_make as they are.
CMAKE_ARGS ?=
DEV := $(WS)/devel/setup.bash
APT_PACKAGES := build-essential cmake clang libclang-rt-14-dev \
  catkin ros-core-dev librosbag-dev python3-rostest python3-roslaunch python3-rosbag \
  python3-rostopic rosout python3-rosmaster python3-rosnode python3-rosparam rosbash \
  python3-catkin-pkg libdiagnostic-updater-dev libsensor-msgs-dev libgeometry-msgs-dev \
  libstd-msgs-dev libdiagnostic-msgs-dev libnlopt-cxx-dev libeigen3-dev libgeographiclib-dev \
  libgtest-dev libbenchmark-dev nlohmann-json3-dev python3-matplotlib python3-numpy

.PHONY: deps build demo test unit-tests bench clean

deps:
	@missing=$$(for p in $(APT_PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing missing packages: $$missing"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	fi

build: deps
	@mkdir -p $(WS)/src $(ROS_LOG_DIR)
	@touch $(CURDIR)/build/CATKIN_IGNORE
	@# The package in the workspace is a folder of links to the repository's entries, all but
	@# build/ itself: linking the whole repository would make a loop that rosrun's find trips on.
	@pkg=$(WS)/src/acc_identification; [ -L $$pkg ] && rm -f $$pkg; mkdir -p $$pkg; \
	  find $$pkg -maxdepth 1 -type l ! -exec test -e {} \; -delete; \
	  for entry in $(CURDIR)/* $(CURDIR)/.ci; do \
	    [ "$$(basename $$entry)" = build ] || ln -sfn $$entry $$pkg/; \
	  done
	cd $(WS) && catkin_make -j$(JOBS) -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON $(if $(COMPONENTS),'-DACC_COMPONENTS=$(COMPONENTS)') $(CMAKE_ARGS) > $(WS)/catkin_make.log 2>&1 \
	  || { tail -n 60 $(WS)/catkin_make.log; exit 1; }
	@echo "built in $(WS) (log: $(WS)/catkin_make.log)"

demo: build
	@source $(DEV) && bash scripts/demo.sh

test: build
	@source $(DEV) && JOBS=$(JOBS) bash scripts/run_tests.sh $(WS)

bench: build
	@source $(DEV) && bash scripts/run_benchmarks.sh $(WS)

clean:
	rm -rf build
