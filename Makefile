# The course workspace: `make demo` and `make test` do all the set-up they need.
SHELL := /bin/bash
ROOT := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
WS := $(ROOT)/catkin_ws
# The built-in course's reference solution (courses/robotics_labs/solution/, under the texts' package names) is an overlay of its own,
# solutions_ws, chained on the course workspace: the course (catkin_ws) holds infrastructure only.
# The student image has no course solution/ and so no overlay.
SOLUTIONS_WS := $(ROOT)/solutions_ws
HAVE_SOLUTIONS := $(wildcard $(ROOT)/courses/robotics_labs/solution/*/package.xml)
# Every ROS command runs in the course's environment, with the venv's python3 first; the tests and
# benchmarks in the reference overlay's (the grader re-runs itself in the course's alone).
ROSENV := source $(WS)/devel/setup.bash &&
REFENV := source $(if $(HAVE_SOLUTIONS),$(SOLUTIONS_WS),$(WS))/devel/setup.bash &&

.PHONY: help deps build demo lab jupyter hub hub-password hub-grade hub-check lti-check test flake-hunt grade course-lint autograder bench bench-grade docker-check autograder-check clean

# Every target has its line in `make help`: the text after `## ` on the target's own line
# (tests/test_makefile.py checks that none is missing).
help: ## this list: every target, one line each (the comments above a target say more)
	@echo "make TARGET, in $(ROOT):"
	@awk '/^[A-Za-z0-9_.-]+:[^=]*## / { name = $$0; sub(/:.*/, "", name); text = $$0; sub(/^[^#]*## /, "", text); \
	  printf "  %-18s %s\n", name, text }' $(MAKEFILE_LIST)

# Set-up, one line per step with its time, apt's, pip's and catkin_make's output in the logs it
# names (logs/, catkin_ws/build.log, solutions_ws/build.log); a failed step prints its log's tail.

deps: ## install what is missing: Debian's ROS 1 packages, the venvs .venv and .venv-jupyter (setup/install.sh)
	@bash $(ROOT)/setup/install.sh

build: ## deps, then catkin_make in catkin_ws (the course) and solutions_ws (the reference solutions' overlay)
	@bash $(ROOT)/setup/install.sh --build

demo: build ## a private master, turtlesim and a short scripted scene; the canvas saved as a PNG in output/
	@$(ROSENV) python3 $(ROOT)/tools/demo.py

# make test also sets up the hub's venv (.venv-hub: JupyterHub, ltiauthenticator, course_hub; no podman, no proxy):
# course_hub's unit tests run the hub's own code from it (its plug-ins, the LTI launches' refusals).
test: build ## every test (pytest: src, courses, tests), in the reference overlay's environment, and the hub's venv
	@bash $(ROOT)/setup/install.sh --hub-venv
	@$(REFENV) cd $(ROOT) && python3 -m pytest

# make flake-hunt K=10: the whole suite K times in a row, failures per test (docs/testing.md).
# UNTIL_FAIL=1 stops at the first failing run; ARGS="..." goes to pytest (a subset, -k ...).
K ?= 10
flake-hunt: build ## the whole suite K times in a row (K=10), failures per test (UNTIL_FAIL=1, ARGS=...)
	@bash $(ROOT)/setup/install.sh --hub-venv
	@$(REFENV) cd $(ROOT) && python3 tools/flake_hunt.py $(if $(UNTIL_FAIL),--until-fail) $(K) $(ARGS)

# make grade: our reference solutions, every milestone (ONLY="teleop chatter": those milestones).
# make grade SUBMISSIONS=DIR: every entry of DIR (folder, .zip, .tar.gz) is one student's submission.
# Results in $(GRADES) (default ./grades).
GRADES ?= $(ROOT)/grades
grade: build ## grade the reference solutions, or each student in SUBMISSIONS=DIR; results in GRADES=./grades
	@$(ROSENV) cd $(ROOT) && rosrun course_grader grade $(if $(SUBMISSIONS),--class $(abspath $(SUBMISSIONS))) \
	  --out $(GRADES) $(if $(JOBS),--jobs $(JOBS)) $(if $(ONLY),--only $(ONLY))

# A course's checks can fail: its reference solution passes every milestone and mutants of it fail
# (docs/course_lint.md). COURSE=courses/NAME (default the built-in course), LINT_ARGS="--only chatter".
COURSE ?=
course-lint: build ## a course's checks against its reference and mutants of it (COURSE=courses/NAME, LINT_ARGS=...)
	@$(ROSENV) cd $(ROOT) && rosrun course_lint course-lint $(if $(COURSE),$(abspath $(COURSE)),courses/robotics_labs) $(LINT_ARGS)

# The lab page with turtlesim (http://127.0.0.1:8080/). In the course image LAB_ADDRESS=0.0.0.0 (the
# port published by the container engine), which requires a token: the URL printed carries it.
LAB_ADDRESS ?= 127.0.0.1
LAB_URL_HOST ?=
LAB_PORT ?= 8080
lab: build ## the lab page with turtlesim, http://127.0.0.1:8080/ (LAB_ADDRESS, LAB_PORT)
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
jupyter: ## the student's workbench: JupyterLab at http://127.0.0.1:8888/lab?token=... (JUPYTER_PORT)
	@[ -f $(WS)/devel/share/course_workbench/cmake/course_workbenchConfig.cmake ] \
	  && [ -x $(ROOT)/.venv-jupyter/bin/jupyter-lab ] || $(MAKE) --no-print-directory build
	@$(ROSENV) rosrun course_workbench workbench --address $(JUPYTER_ADDRESS) --port '$(JUPYTER_PORT)' \
	  --url-host '$(JUPYTER_URL_HOST)'

# The class's hub (docs/hub.md): JupyterHub at $(HUB_URL), each student a container of $(HUB_IMAGE)
# (the student image) through podman's Docker API, accounts from $(HUB_CLASS_LIST), students' files in
# $(HUB_DATA)/users/. Root. Its config: deploy/jupyterhub/jupyterhub_config.py; its plug-ins and commands:
# the course_hub package in .venv-hub (setup/install.sh installs it there with pip).
HUB_DATA ?= /var/lib/ros-course-hub
HUB_CLASS_LIST ?= $(ROOT)/deploy/jupyterhub/classlist.csv
HUB_IMAGE ?= localhost/ros-course
HUB_URL ?= http://127.0.0.1:8000
# the proxy, configurable-http-proxy, is found on PATH (npm's, in .hub/node)
HUB_ENV := HUB_DATA='$(HUB_DATA)' HUB_CLASS_LIST='$(abspath $(HUB_CLASS_LIST))' HUB_IMAGE='$(HUB_IMAGE)' HUB_URL='$(HUB_URL)' \
  PATH='$(ROOT)/.hub/node/node_modules/.bin':"$$PATH"
hub: ## the class's JupyterHub, each student a container of the student image (root; docs/hub.md)
	@COURSE_HUB=1 bash $(ROOT)/setup/install.sh
	@$(HUB_ENV) $(ROOT)/.venv-hub/bin/course-hub --config $(ROOT)/deploy/jupyterhub/jupyterhub_config.py

# The hand-out sheet of initial passwords, $(HUB_DATA)/initial-passwords.csv (the hub's start fills it for
# users without a password: course-hub-passwords). RESET=alice gives alice a new one at once, while the hub runs or not.
hub-password: ## the hand-out sheet of initial passwords; RESET=alice gives alice a new one
	@COURSE_HUB=1 bash $(ROOT)/setup/install.sh
	@$(ROOT)/.venv-hub/bin/course-hub-passwords --data '$(HUB_DATA)' \
	  --class-list '$(abspath $(HUB_CLASS_LIST))' $(foreach u,$(RESET),--reset $(u))

# At a deadline: every student's catkin_ws/src snapshotted read-only, graded as a class (the gradebook
# keyed by hub user), each report copied into its student's ~/grades. MILESTONES="chatter ..." as for autograder.
# LTI=lti.yaml then posts the scores to the LMS gradebook (LTI 1.3 AGS: docs/grading.md).
hub-grade: build ## at a deadline: every student's files snapshotted, graded, reports into their ~/grades
	@$(ROSENV) rosrun course_hub hub_grade --data '$(HUB_DATA)' --class-list '$(abspath $(HUB_CLASS_LIST))' \
	  $(foreach m,$(MILESTONES),--only $(m)) $(if $(LTI),--lti '$(abspath $(LTI))')

# The end-to-end suites, tests/e2e/ (pytest's `e2e` marker, which make test leaves out: pytest.ini's addopts),
# each run by its target below with its lines printed as they come (-s); their options in the environment.
E2E := python3 -m pytest -m e2e -s
# The podman suites and tools run as root before anything is built, in Debian's python3 without ROS: the
# packages they import are plain Python without messages, taken from their source folders.
PLAIN_PACKAGES := course_testkit course_checks course_sandbox course_net
EMPTY :=
PLAIN_PYTHON := PYTHONPATH='$(subst $(EMPTY) $(EMPTY),:,$(PLAIN_PACKAGES:%=$(ROOT)/src/%/src))' /usr/bin/python3

# The hub end to end with real parts (root, podman; ~1.5 min, plus the image's build): the image, a hub,
# seven students and a TA logging in over HTTP and in Chromium, isolation, the admin, culling, a failed
# start, snapshot-and-grade, and every attack of a hostile student (docs/hub.md): tests/e2e/test_hub.py.
# HUB_CHECK_ARGS="--image localhost/ros-course-hub --no-build" tries an image already built.
hub-check: build ## the hub end to end with real parts: podman, students, a TA, attacks (root; not in test)
	@COURSE_HUB=1 bash $(ROOT)/setup/install.sh
	@$(REFENV) cd $(ROOT) && HUB_CHECK_ARGS='$(HUB_CHECK_ARGS)' $(E2E) tests/e2e/test_hub.py

# The login from the LMS and the grades back to it, end to end (root, podman, headless Chromium; ~2 min, plus the
# image's build): a real LTI 1.3 platform on loopback (PyPI's lti1p3platform), three students and a TA clicking its
# course links in Chromium into the hub, a milestone's link, hub_grade --lti posting to its gradebook
# (docs/hub.md): tests/e2e/test_lti.py. LTI_CHECK_ARGS as HUB_CHECK_ARGS ("--image ... --no-build").
lti-check: build ## the hub's login from a real LTI 1.3 platform in Chromium, the grades into its gradebook (root; not in test)
	@COURSE_HUB=1 bash $(ROOT)/setup/install.sh
	@$(REFENV) cd $(ROOT) && LTI_CHECK_ARGS='$(LTI_CHECK_ARGS)' $(E2E) tests/e2e/test_lti.py

# Gradescope autograder: setup.sh + run_autograder + this repository; MILESTONES="chatter ..." grades only those,
# COURSE=courses/NAME grades that course (its solution/ and samples/ left out, as every course's).
autograder: build ## autograder.zip for Gradescope (MILESTONES="chatter ..." grades only those; COURSE=DIR another course)
	@$(ROSENV) rosrun course_grader make_autograder --out $(ROOT)/autograder.zip $(foreach m,$(MILESTONES),--only $(m)) \
	  $(if $(COURSE),--course $(abspath $(COURSE)))

bench: build ## the benchmarks: turtlesim, the relay, the simulator, the lab page, the workbench
	@$(REFENV) cd $(ROOT) && python3 bench/turtlesim_bench.py && python3 bench/relay_bench.py \
	  && python3 bench/sim_bench.py && python3 bench/web_bench.py --simulator && python3 bench/workbench_bench.py

# The grader's trust and speed: the reference graded 20 times, then a class of 30 (about 45 min),
# then the similarity check on a class of 30.
bench-grade: build ## the grader's trust and speed: the reference 20 times, a class of 30, similarity
	@$(REFENV) cd $(ROOT) && python3 bench/grade_bench.py && python3 bench/similarity_bench.py

# docker/Dockerfile built and run by podman (root): the demo, make lab and make jupyter through their
# published ports, then make grade and make test in containers; each step's time.
# DOCKER_CHECK_ARGS="--skip-test" or "--rebuild"; COURSE_IMAGE=... INSTRUCTOR_IMAGE=... other tags.
# See tests/e2e/test_image.py.
docker-check: ## docker/Dockerfile's two images built by podman and tried: demo, lab, jupyter, grade, test (root)
	@cd $(ROOT) && DOCKER_CHECK_ARGS='$(DOCKER_CHECK_ARGS)' $(PLAIN_PYTHON) -m pytest -m e2e -s \
	  tests/e2e/test_image.py::test_the_course_images

# The Gradescope autograder as Gradescope runs it: setup.sh as root in a fresh container of the base
# image, then run_autograder on a correct, a buggy, a non-building and an attack submission.
autograder-check: ## the Gradescope autograder as Gradescope runs it, in fresh podman containers (root)
	@$(MAKE) --no-print-directory autograder MILESTONES=chatter
	@cd $(ROOT) && AUTOGRADER_ZIP='$(ROOT)/autograder.zip' $(PLAIN_PYTHON) -m pytest -m e2e -s \
	  tests/e2e/test_image.py::test_the_autograder_as_gradescope_runs_it

# The course image for linux/amd64 and linux/arm64 (Apple Silicon), both built here by podman (root) from
# docker/Dockerfile, the arm64 one under qemu-user-static, joined in the manifest list ros-course-multiarch.
# image-arm64-check: the arm64 image under emulation: the demo, course-check on a correct chatter package,
# make jupyter answering over HTTP. image-figures: sizes, the demo's time emulated against native.
# Hours of emulated work on a small machine; not part of make test. tools/multiarch.py, tests/e2e/test_arm64.py,
# docs/images.md.
.PHONY: image-multiarch image-arm64-check image-figures
image-multiarch: ## the course image for linux/amd64 and linux/arm64 (qemu), the manifest list ros-course-multiarch
	@$(PLAIN_PYTHON) $(ROOT)/tools/multiarch.py image $(MULTIARCH_ARGS)

image-arm64-check: ## the arm64 image under emulation: the demo, course-check, make jupyter
	@cd $(ROOT) && MULTIARCH_ARGS='$(MULTIARCH_ARGS)' $(PLAIN_PYTHON) -m pytest -m e2e -s tests/e2e/test_arm64.py

image-figures: ## the images' sizes, the demo's time emulated against native
	@$(PLAIN_PYTHON) $(ROOT)/tools/multiarch.py figures $(MULTIARCH_ARGS)

# ROS 1's own tutorials as an overlay on this workspace: built, their tests run, turtle_tf2's demos
# (Python and C++) against our turtlesim. TUTORIALS=DIR holds ros_tutorials, geometry_tutorials and
# common_tutorials (sources, never committed); not part of make test. tests/e2e/test_tutorials.py, docs/noetic_cxx.md.
.PHONY: tutorials-check
ifneq ($(filter tutorials-check,$(MAKECMDGOALS)),)
ifeq ($(TUTORIALS),)
$(error make tutorials-check TUTORIALS=DIR: the folder holding ros_tutorials, geometry_tutorials, common_tutorials)
endif
endif
tutorials-check: build ## ROS 1's own tutorials as an overlay: built, tested, turtle_tf2's demos (TUTORIALS=DIR)
	@$(ROSENV) cd $(ROOT) && TUTORIALS='$(abspath $(TUTORIALS))' TUTORIALS_CHECK_ARGS='$(TUTORIALS_CHECK_ARGS)' \
	  $(E2E) tests/e2e/test_tutorials.py

clean: ## the workspaces' build and devel spaces, their build logs and the set-up's logs/
	rm -rf $(WS)/build $(WS)/devel $(WS)/build.log $(SOLUTIONS_WS)/build $(SOLUTIONS_WS)/devel $(SOLUTIONS_WS)/build.log \
	  $(ROOT)/logs
