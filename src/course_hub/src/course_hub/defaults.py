"""The course hub's defaults, in one place.

The traits of the course's JupyterHub plug-ins (course_hub.spawner.CourseSpawner,
course_hub.auth.CourseAuthenticator) take their defaults from here, and so do make hub's start
(course_hub.runner), the config file (deploy/jupyterhub/jupyterhub_config.py, for make's
variables left unset) and the tests: a value written twice would drift. What a course changes
it sets in the config file; these are the values when it does not.
"""
from __future__ import annotations

from typing import Tuple

# The hub's data folder: the students' disks and mount points, the hub's database, cookie secret,
# password file and hand-out sheet, the snapshots and gradings (course_hub.layout)
DATA_DIR = "/var/lib/ros-course-hub"
IMAGE = "localhost/ros-course"          # the student image (docker/Dockerfile's default target)
BIND_URL = "http://127.0.0.1:8000"      # where the hub's proxy listens (behind TLS for a real class)
HUB_API_PORT = 8081                     # the hub's API, which the containers call (JupyterHub's own default)
# The hub's name on one machine: a dotted name under .localhost (every name there is loopback, for
# browsers and, with libnss-myhostname, for the machine's own programs), so that JupyterHub's
# cookies for the hub and its subdomains have a domain browsers and cookie jars accept.
LOCAL_DOMAIN = "hub.localhost"

# The student image's user (docker/Dockerfile) and where their folders appear in the container
STUDENT_HOME = "/home/student"
STUDENT_UID = 1000
SRC_IN_CONTAINER = STUDENT_HOME + "/catkin_ws/src"
GRADES_IN_CONTAINER = STUDENT_HOME + "/grades"
# What `make jupyter` runs, exec'd down to the server itself (bash, rosrun, the start-up, then
# jupyterhub-singleuser): the server is the container's main process, so the container ends with
# the server's own exit status (137 when the memory limit killed it) and not make's 2.
SINGLEUSER_COMMAND: Tuple[str, ...] = (
    "bash", "-c", "source catkin_ws/devel/setup.bash && exec rosrun course_workbench workbench")

# Each student's container (docs/hub.md's figures: master, turtlesim, the lab page, a build)
MEM_LIMIT = "2G"
CPU_LIMIT = 1.0
PIDS_LIMIT = 1024
DISK_LIMIT = "1G"       # each student's disk (course_hub.disks), its blocks reserved when made
HOME_LIMIT = "512M"     # the container's home and /tmp, each a tmpfs counted in MEM_LIMIT
START_TIMEOUT_S = 180
# podman's user namespace for each container: `auto` gives each a range of host ids no other
# running container has (from the `containers` entry of /etc/subuid, which make hub's set-up writes)
USERNS = "auto"
