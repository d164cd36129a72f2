# JupyterHub for the ROS course: the one file a course edits (docs/hub.md). Plain JupyterHub
# configuration: the course's parts are JupyterHub plug-ins of the course_hub package, which
# `make hub` installs into the hub's venv (.venv-hub): CourseSpawner (DockerSpawner: each student a
# container of the student image, on a disk and a network of their own) and CourseAuthenticator
# (the class list's accounts, passwords, failed logins limited) or CourseLTIAuthenticator (the
# login from the LMS, LTI 1.3). Their traits are below;
# `.venv-hub/bin/jupyterhub --help-all` lists every one.
#
# `make hub` (course-hub, course_hub.runner) lays out the data folder and gives every listed user
# without a password an initial one (the hand-out sheet <data>/initial-passwords.csv) before it
# starts JupyterHub with this file; loading this file does nothing but set configuration.
# make's variables HUB_DATA, HUB_CLASS_LIST, HUB_IMAGE and HUB_URL arrive in the environment, so
# that make hub-grade and make hub-password use the same class and folder; so do HUB_AUTH and
# HUB_LTI_* when given (`sudo make hub HUB_AUTH=lti HUB_LTI_ISSUER=...`).
import os
import sys

from course_hub import defaults
from course_hub.names import subdomain_hook
from course_hub.origins import subdomain_host

c = get_config()  # noqa: F821 (JupyterHub's)
env = os.environ.get
data = env("HUB_DATA") or defaults.DATA_DIR  # the students' disks, the hub's database and secrets, gradings

# --- the hub ---------------------------------------------------------------------------------
c.JupyterHub.bind_url = env("HUB_URL") or defaults.BIND_URL  # the proxy; TLS in front for a real class
# Each student's server on its own origin, <user>.<host>: http://hub.localhost:<port> on one
# machine. A class sets its public address instead, with wildcard DNS and a wildcard certificate:
# c.JupyterHub.subdomain_host = "https://hub.example.org"
c.JupyterHub.subdomain_host = subdomain_host(c.JupyterHub.bind_url)  # refuses a bind_url off loopback
c.JupyterHub.subdomain_hook = subdomain_hook  # <user>.<host> named as everything else of the user
# The containers call the hub's API on their network's gateway: it listens on every address,
# and make hub closes its port to the network while it runs (course_hub.firewall)
c.JupyterHub.hub_ip = "0.0.0.0"
c.JupyterHub.hub_port = int(env("HUB_API_PORT") or defaults.HUB_API_PORT)
c.JupyterHub.db_url = "sqlite:///" + os.path.join(data, "jupyterhub.sqlite")
c.JupyterHub.cookie_secret_file = os.path.join(data, "jupyterhub_cookie_secret")
c.ConfigurableHTTPProxy.pid_file = os.path.join(data, "jupyterhub-proxy.pid")
# c.JupyterHub.ssl_cert = "/etc/letsencrypt/live/hub.example.org/fullchain.pem"
# c.JupyterHub.ssl_key = "/etc/letsencrypt/live/hub.example.org/privkey.pem"

# --- accounts: the class list, or the LMS ------------------------------------------------------
# A class chooses one: the class list's accounts and initial passwords (CourseAuthenticator, entry
# point "course": a course without an LMS), or the login from the LMS, an LTI 1.3 launch
# (CourseLTIAuthenticator, entry point "course-lti"): HUB_AUTH=lti (`sudo make hub HUB_AUTH=lti`).
c.CourseAuthenticator.class_list = env("HUB_CLASS_LIST") or os.path.join(os.path.dirname(__file__), "classlist.csv")
c.CourseAuthenticator.data_dir = data  # passwords.dbm, initial-passwords.csv
# c.CourseAuthenticator.failures_per_name = 5        # failed logins in the window, then refused
# c.CourseAuthenticator.failures_per_address = 50
# c.CourseAuthenticator.failure_window_s = 300.0
if (env("HUB_AUTH") or "classlist") != "lti":
    # who may log in (everyone listed, nobody else), TAs the admins, an initial password each
    c.JupyterHub.authenticator_class = "course_hub.auth.CourseAuthenticator"
else:
    # The LMS's launch: whoever the class's LMS sends (a signed id_token of its platform, this
    # tool's client id and deployment) comes in; Instructor or TeachingAssistant is a TA (admin),
    # Learner a student; the user name is the LTI user id (sub), through the hub's name rules.
    # The platform's and tool's registration (docs/hub.md, "Logging in from the LMS": Canvas,
    # Moodle): the values the LMS shows, here or in the environment.
    c.JupyterHub.authenticator_class = "course_hub.lti.CourseLTIAuthenticator"
    c.CourseLTIAuthenticator.data_dir = data  # lti-users.json: each hub user's LMS identity
    c.CourseLTIAuthenticator.issuer = env("HUB_LTI_ISSUER") or ""  # e.g. "https://canvas.instructure.com"
    c.CourseLTIAuthenticator.client_id = set(filter(None, (env("HUB_LTI_CLIENT_ID") or "").split(",")))
    c.CourseLTIAuthenticator.deployment_ids = set(filter(None, (env("HUB_LTI_DEPLOYMENT_ID") or "").split(",")))
    c.CourseLTIAuthenticator.authorize_url = env("HUB_LTI_AUTHORIZE_URL") or ""  # the platform's OIDC auth URL
    c.CourseLTIAuthenticator.jwks_endpoint = env("HUB_LTI_JWKS_URL") or ""  # the platform's public keys
    # c.CourseLTIAuthenticator.username_key = "sub"          # or "custom_login_id": the custom parameter login_id
    # c.CourseLTIAuthenticator.milestone_parameter = "milestone"   # a course link's custom milestone=<id>
    # c.CourseLTIAuthenticator.uri_scheme = "https"          # behind TLS that ends before the hub
# A campus login instead (OAuthenticator, LDAPAuthenticator ...): set authenticator_class, and
# c.Authenticator.allowed_users / admin_users from the class list (course_hub.classlist.load).

# --- each student: course_hub.spawner.CourseSpawner (entry point "course") ----------------------
c.JupyterHub.spawner_class = "course_hub.spawner.CourseSpawner"
c.CourseSpawner.data_dir = data  # <data>/disks/<user>.img mounted at <data>/users/<user>
c.CourseSpawner.image = env("HUB_IMAGE") or defaults.IMAGE  # the student image, built on this machine
# the course's defaults, per student (docs/hub.md's figures); uncomment to change:
# c.CourseSpawner.mem_limit = "2G"      # master, turtlesim, the lab page, a build
# c.CourseSpawner.cpu_limit = 1.0       # cores, at most
# c.CourseSpawner.pids_limit = 1024     # processes, at most
# c.CourseSpawner.disk_limit = "1G"     # their disk (catkin_ws/src, ~/grades), reserved when first made
# c.CourseSpawner.home_limit = "512M"   # the home folder and /tmp, tmpfs counted in mem_limit
# c.CourseSpawner.start_timeout = 180   # seconds for a server to start

# --- idle servers: jupyterhub-idle-culler, with only the scopes it needs ------------------------
# An idle server is stopped after an hour, any server after 12 h (its own token can report
# activity); the culler looks every 5 min. The student's files stay.
c.JupyterHub.services = [{"name": "idle-culler", "command": [
    sys.executable, "-m", "jupyterhub_idle_culler", "--timeout=3600", "--max-age=43200", "--cull-every=300"]}]
c.JupyterHub.load_roles = [{"name": "idle-culler", "services": ["idle-culler"],
                            "scopes": ["list:users", "read:users:activity", "read:servers", "delete:servers"]}]
