"""The model database: `-database NAME` and world `<include><uri>model://NAME</uri>`
resolve to NAME/model.sdf in the directories of GAZEBO_MODEL_PATH, then the models
shipped with this package (coke_can, ground_plane, sun). Nothing is downloaded."""
from __future__ import annotations

import functools
import os
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import List, Optional

PACKAGE = "mujoco_gazebo"


@functools.lru_cache(maxsize=1)
def package_share() -> Path:
    """This package's share folder: the source folder in a devel space, share/mujoco_gazebo in
    an install space (rospkg asks ROS_PACKAGE_PATH, as roslaunch's $(find) does). Without a
    ROS environment, the source tree this module sits in."""
    try:
        import rospkg
        return Path(rospkg.RosPack().get_path(PACKAGE))
    except Exception:  # rospkg missing, or the package not on ROS_PACKAGE_PATH
        return Path(__file__).resolve().parents[3]


def shipped_models() -> Path:
    return package_share() / "models"


class DatabaseError(LookupError):
    """No model of that name in the database."""


def search_path(env: Optional[dict] = None) -> List[Path]:
    env = os.environ if env is None else env
    dirs = [Path(p) for p in env.get("GAZEBO_MODEL_PATH", "").split(":") if p]
    return dirs + [shipped_models()]


def model_names(env: Optional[dict] = None) -> List[str]:
    names = set()
    for d in search_path(env):
        if d.is_dir():
            names.update(p.parent.name for p in d.glob("*/model.sdf"))
    return sorted(names)


def model_file(name: str, env: Optional[dict] = None) -> Path:
    """Path of the model's SDF file (model.config's <sdf> entry, else model.sdf)."""
    if not name or "/" in name or name.startswith("."):
        raise DatabaseError("invalid model database name %r" % name)
    for d in search_path(env):
        folder = d / name
        if not folder.is_dir():
            continue
        sdf_name = "model.sdf"
        config = folder / "model.config"
        if config.is_file():
            try:
                sdf_name = (ET.parse(config).getroot().findtext("sdf") or sdf_name).strip()
            except ET.ParseError:
                pass
        if (folder / sdf_name).is_file():
            return folder / sdf_name
    raise DatabaseError("model [%s] is not in the model database (have: %s)"
                        % (name, ", ".join(model_names(env))))


def model_sdf(name: str, env: Optional[dict] = None) -> str:
    return model_file(name, env).read_text()


def resolve_uri(uri: str, env: Optional[dict] = None) -> str:
    """'model://coke_can' -> SDF text of that database model."""
    prefix = "model://"
    if not uri.startswith(prefix):
        raise DatabaseError("unsupported model uri %r (only model://NAME)" % uri)
    return model_sdf(uri[len(prefix):].strip("/"), env)
