"""A planar laser scanner made of MuJoCo ray casts (one mj_multiRay call per scan)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np


@dataclass
class ScanConfig:
    samples: int = 360
    min_angle: float = 0.0
    max_angle: float = 6.28319
    range_min: float = 0.12
    range_max: float = 3.5

    @property
    def angle_increment(self) -> float:
        return (self.max_angle - self.min_angle) / max(1, self.samples - 1) if self.samples > 1 else 0.0


class Lidar:
    """Rays in the sensor body's x-y plane; misses and hits beyond range_max read +inf,
    hits nearer than range_min read +inf too (what gazebo_ros_laser reports for no return)."""

    def __init__(self, config: ScanConfig) -> None:
        self.config = config
        angles = config.min_angle + np.arange(config.samples) * config.angle_increment
        self._local_dirs = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
        self._geomid = np.zeros(config.samples, dtype=np.int32)
        self._dist = np.zeros(config.samples, dtype=np.float64)

    def scan(self, model: mujoco.MjModel, data: mujoco.MjData, body_id: int) -> np.ndarray:
        origin = data.xpos[body_id].copy()
        rot = data.xmat[body_id].reshape(3, 3)
        dirs = (self._local_dirs @ rot.T).reshape(-1)
        mujoco.mj_multiRay(model, data, origin, dirs, None, 1, body_id, self._geomid, self._dist,
                           self.config.samples, self.config.range_max)
        return self.to_ranges(self._dist)

    def to_ranges(self, dist: np.ndarray) -> np.ndarray:
        ranges = np.asarray(dist, dtype=np.float64).copy()
        bad = (ranges < 0) | (ranges > self.config.range_max) | (ranges < self.config.range_min)
        ranges[bad] = math.inf
        return ranges
