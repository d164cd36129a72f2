# JupyterHub for the ROS course: the one file a course adapts (docs/hub.md). `make hub` runs
# JupyterHub with it (as root, podman's Docker API started beside it); course_hub.hubconfig does
# the rest: each student a container of the student image on a network of their own, their
# catkin_ws/src kept in <data>/users/<name>/src, TAs as admins, idle servers culled.
#
# The class list, the data folder and the image also come from make's variables (HUB_CLASS_LIST,
# HUB_DATA, HUB_IMAGE), so `make hub-grade` grades the same class from the same folder.
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CHECKOUT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(CHECKOUT, "src", "course_hub", "src"))
sys.path.insert(0, HERE)  # course_spawner, the spawner hubconfig names
from course_hub import hubconfig  # noqa: E402

c = get_config()  # noqa: F821 (JupyterHub's)

settings = hubconfig.HubSettings(
    class_list=os.environ.get("HUB_CLASS_LIST") or os.path.join(HERE, "classlist.csv"),
    data_dir=os.environ.get("HUB_DATA") or "/var/lib/ros-course-hub",
    image=os.environ.get("HUB_IMAGE") or "localhost/ros-course",
    bind_url=os.environ.get("HUB_URL") or "http://127.0.0.1:8000",  # behind a TLS proxy for a real class
    # subdomain_host="https://hub.example.org",  # a class's public address: wildcard DNS and TLS (docs/hub.md)
    hub_port=int(os.environ.get("HUB_API_PORT") or hubconfig.DEFAULT_HUB_PORT),  # the containers call it; make hub firewalls it
    mem_limit="2G",          # per student: master, turtlesim, the lab page, a build (docs/hub.md's figures)
    cpu_limit=1.0,           # cores per student, at most
    idle_timeout_s=3600,     # a server idle this long is stopped; the files stay
    proxy_command=[os.path.join(CHECKOUT, ".hub", "node", "node_modules", ".bin", "configurable-http-proxy")],
)
hubconfig.apply(c, settings)

# Anything else is JupyterHub's own configuration, e.g.:
# c.JupyterHub.ssl_cert = "/etc/letsencrypt/live/hub.example.org/fullchain.pem"
# c.JupyterHub.ssl_key = "/etc/letsencrypt/live/hub.example.org/privkey.pem"
