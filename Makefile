# The course workspace: `make demo` and `make test` do all the set-up they need.
SHELL := /bin/bash
ROOT := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
WS := $(ROOT)/catkin_ws
# The reference solutions (solutions/, under the texts' package names) are an overlay of their own,
# solutions_ws, chained on the course workspace: the course (catkin_ws) holds infrastructure only.
# The student image has no solutions/ and so no overlay.
SOLUTIONS_WS := $(ROOT)/solutions_ws
HAVE_SOLUTIONS := $(wildcard $(ROOT)/solutions/*/package.xml)
# Every ROS command runs in the course's environment, with the venv's python3 first; the tests and
# benchmarks in the reference overlay's (the grader re-runs itself in the course's alone).
ROSENV := source $(WS)/devel/setup.bash &&
REFENV := source $(if $(HAVE_SOLUTIONS),$(SOLUTIONS_WS),$(WS))/devel/setup.bash &&

.PHONY: deps build demo lab jupyter hub hub-password hub-grade hub-check test flake-hunt unit rostest grade autograder bench bench-grade docker-check autograder-check clean

deps:
	@bash $(ROOT)/tools/deps.sh

build: deps
	@cd $(WS) && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release > $(WS)/build.log 2>&1 \
	  || { tail -n 60 $(WS)/build.log; exit 1; }
	@echo "build: ok (log in catkin_ws/build.log)"
ifneq ($(HAVE_SOLUTIONS),)
	@$(ROSENV) cd $(SOLUTIONS_WS) && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release \
	  > $(SOLUTIONS_WS)/build.log 2>&1 || { tail -n 60 $(SOLUTIONS_WS)/build.log; exit 1; }
	@echo "build: reference solutions ok, an overlay in solutions_ws (log in solutions_ws/build.log)"
endif

demo: build
	@$(ROSENV) python3 $(ROOT)/tools/demo.py

test: build
	@$(REFENV) cd $(ROOT) && python3 -m pytest

# make flake-hunt K=10: the whole suite K times in a row, failures per test (docs/testing.md).
# UNTIL_FAIL=1 stops at the first failing run; ARGS="..." goes to pytest (a subset, -k ...).
K ?= 10
flake-hunt: build
	@$(REFENV) cd $(ROOT) && python3 tools/flake_hunt.py $(if $(UNTIL_FAIL),--until-fail) $(K) $(ARGS)

# make grade: our reference solutions, every milestone. make grade SUBMISSIONS=DIR: every entry of
# DIR (folder, .zip, .tar.gz) is one student's submission. Results in $(GRADES) (default ./grades).
GRADES ?= $(ROOT)/grades
grade: build
	@$(ROSENV) cd $(ROOT) && rosrun course_grader grade $(if $(SUBMISSIONS),--class $(abspath $(SUBMISSIONS))) \
	  --out $(GRADES) $(if $(JOBS),--jobs $(JOBS))

# The lab page with turtlesim (http://127.0.0.1:8080/). In the course image LAB_ADDRESS=0.0.0.0 (the
# port published by the container engine), which requires a token: the URL printed carries it.
LAB_ADDRESS ?= 127.0.0.1
LAB_URL_HOST ?=
LAB_PORT ?= 8080
lab: build
	@$(ROSENV) roslaunch course_web lab_view.launch turtlesim:=true address:=$(LAB_ADDRESS) port:=$(LAB_PORT) \
	  url_host:=$(LAB_URL_HOST)

# The student's workbench: JupyterLab (http://127.0.0.1:8888/lab?token=..., JUPYTER_PORT, JUPYTER_TOKEN),
# its terminals with the course and ~/catkin_ws sourced, the lab page at /roslab/, course-check.
# In the course image JUPYTER_ADDRESS=0.0.0.0 (the port published by the container engine). docs/workbench.md
JUPYTER_ADDRESS ?= 127.0.0.1
JUPYTER_URL_HOST ?=
JUPYTER_PORT ?= 8888
# It builds only what was never built: a no-op `make build` (catkin_make) would add 10-25 s to every start,
# and the image's sources never change; after editing the course's sources, run make build.
jupyter:
	@[ -f $(WS)/devel/share/course_workbench/cmake/course_workbenchConfig.cmake ] \
	  && [ -x $(ROOT)/.venv-jupyter/bin/jupyter-lab ] || $(MAKE) --no-print-directory build
	@$(ROSENV) rosrun course_workbench workbench --address $(JUPYTER_ADDRESS) --port '$(JUPYTER_PORT)' \
	  --url-host '$(JUPYTER_URL_HOST)'

# The class's hub (docs/hub.md): JupyterHub at $(HUB_URL), each student a container of $(HUB_IMAGE)
# (the student image) through podman's Docker API, accounts from $(HUB_CLASS_LIST), students' files in
# $(HUB_DATA)/users/. Root. Its config: deploy/jupyterhub/jupyterhub_config.py.
HUB_DATA ?= /var/lib/ros-course-hub
HUB_CLASS_LIST ?= $(ROOT)/deploy/jupyterhub/classlist.csv
HUB_IMAGE ?= localhost/ros-course
HUB_URL ?= http://127.0.0.1:8000
HUB_ENV := HUB_DATA='$(HUB_DATA)' HUB_CLASS_LIST='$(abspath $(HUB_CLASS_LIST))' HUB_IMAGE='$(HUB_IMAGE)' HUB_URL='$(HUB_URL)'
hub:
	@COURSE_HUB=1 bash $(ROOT)/tools/deps.sh
	@$(HUB_ENV) /usr/bin/python3 $(ROOT)/src/course_hub/scripts/hub --config $(ROOT)/deploy/jupyterhub/jupyterhub_config.py \
	  --jupyterhub $(ROOT)/.venv-hub/bin/jupyterhub

# The hand-out sheet of initial passwords, $(HUB_DATA)/initial-passwords.csv (the hub's start fills it for
# users without a password). RESET=alice gives alice a new one at once, while the hub runs or not.
hub-password:
	@COURSE_HUB=1 bash $(ROOT)/tools/deps.sh
	@$(ROOT)/.venv-hub/bin/python $(ROOT)/src/course_hub/scripts/hub_passwords --data '$(HUB_DATA)' \
	  --class-list '$(abspath $(HUB_CLASS_LIST))' $(foreach u,$(RESET),--reset $(u))

# At a deadline: every student's catkin_ws/src snapshotted read-only, graded as a class (the gradebook
# keyed by hub user), each report copied into its student's ~/grades. MILESTONES="chatter ..." as for autograder.
hub-grade: build
	@$(ROSENV) rosrun course_hub hub_grade --data '$(HUB_DATA)' --class-list '$(abspath $(HUB_CLASS_LIST))' \
	  $(foreach m,$(MILESTONES),--only $(m))

# The hub end to end with real parts (root, podman; ~1.5 min, plus the image's build): the image, a hub,
# seven students and a TA logging in over HTTP and in Chromium, isolation, the admin, culling, a failed
# start, snapshot-and-grade, and every attack of a hostile student (docs/hub.md). Not in make test.
# HUB_CHECK_ARGS="--image localhost/ros-course-hub --no-build" tries an image already built.
hub-check: build
	@COURSE_HUB=1 bash $(ROOT)/tools/deps.sh
	@$(REFENV) cd $(ROOT) && python3 tools/hub_check.py $(HUB_CHECK_ARGS)

# Gradescope autograder: setup.sh + run_autograder + this repository; MILESTONES="chatter ..." grades only those.
autograder: build
	@$(ROSENV) rosrun course_grader make_autograder --out $(ROOT)/autograder.zip $(foreach m,$(MILESTONES),--only $(m))

bench: build
	@$(REFENV) cd $(ROOT) && python3 bench/turtlesim_bench.py && python3 bench/relay_bench.py \
	  && python3 bench/sim_bench.py && python3 bench/web_bench.py --simulator && python3 bench/workbench_bench.py

# The grader's trust and speed: the reference graded 20 times, then a class of 30 (about 45 min),
# then the similarity check on a class of 30.
bench-grade: build
	@$(REFENV) cd $(ROOT) && python3 bench/grade_bench.py && python3 bench/similarity_bench.py

# docker/Dockerfile built and run by podman (root): the demo, make lab and make jupyter through their
# published ports, then make grade and make test in containers; each step's time.
# DOCKER_CHECK_ARGS="--skip-test" or "--rebuild"; COURSE_IMAGE=... INSTRUCTOR_IMAGE=... other tags.
# See tools/podman_check.py.
docker-check:
	@/usr/bin/python3 $(ROOT)/tools/podman_check.py docker-check $(DOCKER_CHECK_ARGS)

# The Gradescope autograder as Gradescope runs it: setup.sh as root in a fresh container of the base
# image, then run_autograder on a correct, a buggy, a non-building and an attack submission.
autograder-check:
	@$(MAKE) --no-print-directory autograder MILESTONES=chatter
	@/usr/bin/python3 $(ROOT)/tools/podman_check.py autograder-check $(ROOT)/autograder.zip

# The course image for linux/amd64 and linux/arm64 (Apple Silicon), both built here by podman (root) from
# docker/Dockerfile, the arm64 one under qemu-user-static, joined in the manifest list ros-course-multiarch.
# image-arm64-check: the arm64 image under emulation: the demo, course-check on a correct chatter package,
# make jupyter answering over HTTP. image-figures: sizes, the demo's time emulated against native.
# Hours of emulated work on a small machine; not part of make test. See docs/images.md.
.PHONY: image-multiarch image-arm64-check image-figures
image-multiarch:
	@/usr/bin/python3 $(ROOT)/tools/multiarch.py image $(MULTIARCH_ARGS)

image-arm64-check:
	@/usr/bin/python3 $(ROOT)/tools/multiarch.py check $(MULTIARCH_ARGS)

image-figures:
	@/usr/bin/python3 $(ROOT)/tools/multiarch.py figures $(MULTIARCH_ARGS)

# ROS 1's own tutorials as an overlay on this workspace: built, their tests run, turtle_tf2's demos
# (Python and C++) against our turtlesim. TUTORIALS=DIR holds ros_tutorials, geometry_tutorials and
# common_tutorials (sources, never committed); not part of make test. See docs/noetic_cxx.md.
.PHONY: tutorials-check
ifneq ($(filter tutorials-check,$(MAKECMDGOALS)),)
ifeq ($(TUTORIALS),)
$(error make tutorials-check TUTORIALS=DIR: the folder holding ros_tutorials, geometry_tutorials, common_tutorials)
endif
endif
tutorials-check: build
	@$(ROSENV) cd $(ROOT) && python3 tools/tutorials_check.py $(abspath $(TUTORIALS)) $(TUTORIALS_CHECK_ARGS)

clean:
	rm -rf $(WS)/build $(WS)/devel $(WS)/build.log $(SOLUTIONS_WS)/build $(SOLUTIONS_WS)/devel $(SOLUTIONS_WS)/build.log
