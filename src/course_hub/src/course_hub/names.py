"""One user, one place: every name the hub derives from a user name comes from `places()`.

A hub user's container, network, folders, web address, snapshot and gradebook row must never be
shared with another user. Each tool spelling them its own way (DockerSpawner escapes `-` as
`-2d`, JupyterHub's subdomains escape `_` as `_5f`, a hook used the name as it is) once sent two
users to one folder. So the spawner, its hooks, the subdomain hook, `hub_grade` and the password
tools all ask this module, and nothing else spells a user's place.

The host-side name is the user's `slug`: the name with `_` written `-`, which is a valid DNS label
(lower-case letters, digits and single dashes, starting with a letter and ending with a letter
or digit, at most 32 characters), so the same word serves as the container's and network's name,
the folder's name and the server's subdomain. Two names with one slug (`jean_luc`, `jean-luc`)
would share all of them: the class list refuses the second (course_hub.classlist). The gradebook
row and the snapshot's folder keep the user name itself, as the TA's roster spells it.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass

PREFIX = "course-hub-"  # containers course-hub-<slug>, networks course-hub-net-<slug>
SLUG = re.compile(r"^[a-z](?:[a-z0-9-]{0,30}[a-z0-9])?$")


def slug(user: str) -> str:
    """The host-side name of `user`: `_` written `-`. ValueError when that is no plain DNS label
    (course_hub.classlist checks every listed name with it before the hub starts)."""
    word = user.replace("_", "-")
    if not SLUG.match(word) or "--" in word:
        raise ValueError("%r has no safe name on the hub: lower case, a letter first, then letters, digits "
                         "and single - or _ between them, at most 32 characters" % user)
    return word


@dataclass(frozen=True)
class Places:
    """Where one user's things are, on the host and in the engine."""

    user: str        # the hub's user name (the login, the gradebook's row, the snapshot's folder)
    slug: str        # the host-side name (course_hub.names.slug)
    container: str   # the workbench's container
    network: str     # the user's own internal bridge network
    home: str        # <data>/users/<slug>: their disk's mount point (course_hub.disks)
    src: str         # their catkin_ws/src
    grades: str      # their ~/grades (read-only in the workbench)
    disk_image: str  # <data>/disks/<slug>.img: the file system their folders live on

    def subdomain(self, domain: str) -> str:
        """The host name of their server under `domain` (JupyterHub's subdomain_host)."""
        return "%s.%s" % (self.slug, domain)


def container(user: str) -> str:
    """The name of `user`'s workbench container (the spawner's object name)."""
    return PREFIX + slug(user)


def places(data_dir: str, user: str) -> Places:
    """Every place of `user` on the hub whose data folder is `data_dir`."""
    word = slug(user)
    home = os.path.join(data_dir, "users", word)
    return Places(user=user, slug=word, container=container(user), network="%snet-%s" % (PREFIX, word),
                  home=home, src=os.path.join(home, "src"), grades=os.path.join(home, "grades"),
                  disk_image=os.path.join(data_dir, "disks", word + ".img"))


def subdomain_hook(name: str, domain: str, kind: str) -> str:
    """JupyterHub's `subdomain_hook`: a user's server at `<slug>.<domain>`, services at
    `services.<domain>` (as JupyterHub's own default hook puts them)."""
    if kind == "user":
        return "%s.%s" % (slug(name), domain)
    if kind == "service":
        return "services.%s" % domain
    raise ValueError("kind must be 'user' or 'service', not %r" % kind)
