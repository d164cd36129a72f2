"""The environment's folder lists (PATH, ROS_PACKAGE_PATH, PYTHONPATH, ...), where a sourced catkin
workspace leaves its entries, and how to take entries out of them: what a student's process and
terminal may see of other workspaces (the grader's course environment, the workbench's start)."""
from __future__ import annotations

import os
from typing import Callable, Dict, Mapping

FOLDER_LISTS = ("PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH", "PYTHONPATH", "LD_LIBRARY_PATH",
                "PKG_CONFIG_PATH", "ROSLISP_PACKAGE_DIRECTORIES", "CPATH", "CPLUS_INCLUDE_PATH")


def drop_entries(env: Mapping[str, str], unwanted: Callable[[str], bool]) -> Dict[str, str]:
    """`env` with every entry of its folder lists for which `unwanted(entry)` holds dropped, and a
    list left empty unset; other variables as they are."""
    clean = dict(env)
    for var in FOLDER_LISTS:
        if var in clean:
            kept = [p for p in clean[var].split(os.pathsep) if p and not unwanted(p)]
            if kept:
                clean[var] = os.pathsep.join(kept)
            else:
                del clean[var]
    return clean
