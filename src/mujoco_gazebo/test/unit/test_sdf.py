import math

import mujoco
import numpy as np
import pytest

from mujoco_gazebo.engine import database
from mujoco_gazebo.engine.sdf import SdfError, parse_pose, parse_world, sdf_to_mjcf

BOX = """<sdf version="1.6"><model name="m"><pose>0 0 1 0 0 0</pose>
<link name="base"><pose>1 0 0 0 0 1.5707963</pose>
<inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.2</iyy><izz>0.3</izz></inertia></inertial>
<collision name="c"><geometry><box><size>0.2 0.4 0.6</size></box></geometry></collision></link>
<link name="top"><pose>1 0.5 0.5 0 0 0</pose><collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry></collision></link>
</model></sdf>"""


def test_box_model_converts_with_sizes_mass_and_pose():
    m = sdf_to_mjcf(BOX)
    assert not m.static and m.name == "m" and np.allclose(m.pose.position, [0, 0, 1])
    model = mujoco.MjSpec.from_string(m.mjcf).compile()
    base = model.body("base")
    assert math.isclose(base.mass[0], 2.0)
    assert np.allclose(model.geom_size[0], [0.1, 0.2, 0.3])
    assert np.allclose(model.body("top").pos, [0.5, 0.0, 0.5], atol=1e-6)  # link pose relative to base (yawed 90 deg)


def test_database_models_convert():
    can = sdf_to_mjcf(database.model_sdf("coke_can"))
    assert not can.static
    ground = sdf_to_mjcf(database.model_sdf("ground_plane"))
    assert ground.static


@pytest.mark.parametrize("text", ["<sdf><model name='x'></model></sdf>", "<sdf><model", "<sdf/>",
                                  "<sdf><model name='x'><link name='l'><collision name='c'><geometry><mesh><uri>a</uri></mesh></geometry></collision></link></model></sdf>"])
def test_bad_sdf_is_refused(text):
    with pytest.raises(SdfError):
        sdf_to_mjcf(text)


def test_pose_needs_six_finite_numbers():
    with pytest.raises(SdfError):
        parse_pose("1 2 3")
    with pytest.raises(SdfError):
        parse_pose("nan 0 0 0 0 0")


def test_world_file_includes_and_physics():
    w = parse_world(open(database.package_share() / "worlds" / "empty.world").read())
    assert [i.uri for i in w.includes] == ["model://sun", "model://ground_plane"]
    assert w.max_step_size == 0.001 and w.real_time_factor == 1


def test_unknown_database_model():
    with pytest.raises(database.DatabaseError):
        database.model_sdf("no_such_model")
