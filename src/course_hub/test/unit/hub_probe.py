"""The course's JupyterHub plug-ins, made from a configuration the way JupyterHub makes them, run
with the hub's own Python (.venv-hub: JupyterHub, DockerSpawner, FirstUseAuthenticator), where the
unit tests' Python has none of them (test_plugins.py runs this):

    .venv-hub/bin/python3 hub_probe.py < request.json > answer.json
    .venv-hub/bin/python3 hub_probe.py --serve   (a request per line, {"request": ..., "env": {...}},
                                                 an answer per line: one start of JupyterHub's imports)

The request (JSON): `config_file` (a JupyterHub config file, read as JupyterHub reads it) and/or
`config` ({section: {trait: value}}, applied over it); `user`; `action`:

- `traits`: CourseSpawner (for `user`) and, when `authenticator_traits` names some,
  CourseAuthenticator (or the class `authenticator_class` names, e.g.
  course_hub.lti.CourseLTIAuthenticator) made from the configuration; the answer holds the traits named in
  `spawner_traits` and `authenticator_traits`, the JupyterHub
  section of the configuration, the configuration's warnings (an option no class knows), and the
  `error` when a class refused its configuration;
- `spawn`: what CourseSpawner does before its container starts (`prepare`), with the disk's
  making recorded instead of done and a stand-in engine: the disks asked for, the networks made,
  the gateway returned;
- `prepare`: make hub's start before JupyterHub (course_hub.runner.prepare) on `config_file`.

No hub runs, no engine is called: the traits are read, nothing is started.
"""
from __future__ import annotations

import json
import logging
import os
import sys
import types
from typing import Any, Dict, List

from traitlets.config import Config
from traitlets.config.loader import PyFileConfigLoader
from traitlets.utils.importstring import import_item


class Warnings(logging.Handler):
    def __init__(self) -> None:
        super().__init__(logging.WARNING)
        self.seen: List[str] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.seen.append(record.getMessage())


def configuration(request: Dict[str, Any]) -> Config:
    config = Config()
    if request.get("config_file"):
        path = request["config_file"]
        folder, name = path.rsplit("/", 1)
        config.merge(PyFileConfigLoader(name, folder).load_config())
    config.merge(Config(request.get("config") or {}))
    return config


def plain(value: Any) -> Any:
    """JSON for a trait's value: sets sorted, tuples as lists, anything else by its repr."""
    if isinstance(value, (set, frozenset)):
        return sorted(value)
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if value is None or isinstance(value, (str, int, float, bool)):
        return value
    return repr(value)


def traits(request: Dict[str, Any]) -> Dict[str, Any]:
    from course_hub.auth import CourseAuthenticator
    from course_hub.spawner import CourseSpawner

    config = configuration(request)
    answer: Dict[str, Any] = {"jupyterhub": plain(dict(config.get("JupyterHub", {})))}
    try:
        user = types.SimpleNamespace(name=request.get("user", "alice"), id=1, url="/user/x/", server=None)
        hub = types.SimpleNamespace(api_url="http://127.0.0.1:8081/hub/api", url="/hub/", base_url="/")
        spawner = CourseSpawner(config=config, user=user, hub=hub)
        answer["spawner"] = {name: plain(getattr(spawner, name)) for name in request.get("spawner_traits", [])}
        if request.get("authenticator_traits"):
            chosen = request.get("authenticator_class")
            auth = (import_item(chosen) if chosen else CourseAuthenticator)(config=config)
            answer["authenticator"] = {name: plain(getattr(auth, name)) for name in request["authenticator_traits"]}
    except Exception as err:  # a trait's refusal, a bad class list: the test reads it
        answer["error"] = "%s: %s" % (type(err).__name__, err)
    return answer


class Engine:
    """Docker's APIClient as far as the spawner's `prepare` uses it."""

    def __init__(self) -> None:
        self.made: Dict[str, Dict[str, Any]] = {}

    def networks(self, names: List[str]) -> List[Dict[str, str]]:
        return [{"Name": n} for n in names if n in self.made]

    def create_network(self, name: str, **options: Any) -> None:
        self.made[name] = {"driver": options.get("driver"), "internal": options.get("internal")}

    def inspect_network(self, name: str) -> Dict[str, Any]:
        return {"IPAM": {"Config": [{"Gateway": "10.89.7.1"}]}}


def spawn(request: Dict[str, Any]) -> Dict[str, Any]:
    from course_hub import disks
    from course_hub.spawner import CourseSpawner

    asked: List[Any] = []
    disks.ensure = lambda place, size, uid: asked.append([place.home, size, uid])
    engine = Engine()

    class Probe(CourseSpawner):
        client = engine  # in place of DockerSpawner's client of the engine

    user = types.SimpleNamespace(name=request.get("user", "alice"), id=1, url="/user/x/", server=None)
    spawner = Probe(config=configuration(request), user=user)
    return {"gateway": spawner.prepare(), "disks": asked, "networks": engine.made}


def prepare(request: Dict[str, Any]) -> Dict[str, Any]:
    from course_hub import runner
    return {"lines": runner.prepare(request["config_file"], rounds=4)}


def answer(request: Dict[str, Any], warnings: Warnings) -> Dict[str, Any]:
    warnings.seen = []
    made = {"traits": traits, "spawn": spawn, "prepare": prepare}[request["action"]](request)
    made["warnings"] = warnings.seen
    return made


def with_env(env: Dict[str, str]) -> None:
    """The process's environment as a request's own: the HUB_* variables the config file reads are
    the request's alone."""
    for key in [k for k in os.environ if k.startswith("HUB_")]:
        del os.environ[key]
    os.environ.update(env)


def main() -> int:
    warnings = Warnings()
    logging.getLogger().addHandler(warnings)
    if "--serve" not in sys.argv[1:]:
        json.dump(answer(json.load(sys.stdin), warnings), sys.stdout)
        return 0
    for line in sys.stdin:
        message = json.loads(line)
        with_env(message.get("env") or {})
        try:
            made = answer(message["request"], warnings)
        except Exception as err:  # noqa: BLE001 - told to the test, which fails with it
            made = {"crash": "%s: %s" % (type(err).__name__, err)}
        sys.stdout.write(json.dumps(made) + "\n")
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
