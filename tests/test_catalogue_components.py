"""Every robot and environment of the catalogue, built into a tiny scene with the real compiler and run
in MuJoCo: the URDF is valid for ROS tools, the MJCF loads, and a robot left alone stays where it was put.
These are the checks run over every robot; what is particular to one robot (its MORSE name, its mass,
how it drives) is in tests/components/test_robots_catalogue.py."""

from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import mujoco
import numpy as np
import pytest
import yourdfpy

from morsec.component.catalogue import declaring_folder, load_catalogue

CATALOGUE = load_catalogue(Path(__file__).parent)  # what build_scene sees for a scene outside a project
ROBOTS = CATALOGUE.ids("robots")
ENVIRONMENTS = CATALOGUE.ids("environments")
# robots naming a left and a right drive wheel (MORSE's WheeledRobot properties)
DIFFERENTIAL = [r for r in ROBOTS
                if {"WheelFLName", "WheelFRName"} <= set(CATALOGUE.get("robots", r).Properties.model_fields)]

SETTLE_S = 5.0
MAX_DRIFT_M = 0.01
MAX_TILT = math.radians(3.0)
FLOAT_HEIGHT_M = 2.0  # NoGravity robots start in the air, clear of the ground (the Hummer's wheels reach 1.14 m down)


def robot_scene(robot_id: str, z: float) -> str:
    return f"environment: {{name: empty}}\nrobots:\n  - {{name: r, type: {robot_id}, translate: [0.0, 0.0, {z}]}}\n"


def run(model: mujoco.MjModel, data: mujoco.MjData, seconds: float) -> None:
    mujoco.mj_step(model, data, nstep=round(seconds / model.opt.timestep))
    assert np.isfinite(data.qpos).all()
    warnings = {mujoco.mjtWarning(i).name: w.number for i, w in enumerate(data.warning) if w.number}
    assert not warnings, f"MuJoCo warnings: {warnings}"


def subtree_bodies(model: mujoco.MjModel, root: int) -> list[int]:
    return [b for b in range(model.nbody) if b == root or _has_ancestor(model, b, root)]


def _has_ancestor(model: mujoco.MjModel, body: int, ancestor: int) -> bool:
    while body:
        body = model.body_parentid[body]
        if body == ancestor:
            return True
    return False


def lowest_point(model: mujoco.MjModel, data: mujoco.MjData, geoms: list[int]) -> float:
    """Lowest z of `geoms` (spheres, capsules, cylinders, boxes: another shape must be added here)."""
    low = math.inf
    for g in geoms:
        z, rot, size = data.geom_xpos[g][2], data.geom_xmat[g].reshape(3, 3), model.geom_size[g]
        kind = model.geom_type[g]
        axis_z = abs(rot[2, 2])  # of the geom's z axis (cylinders' and capsules' axis)
        if kind == mujoco.mjtGeom.mjGEOM_SPHERE:
            low = min(low, z - size[0])
        elif kind == mujoco.mjtGeom.mjGEOM_CAPSULE:
            low = min(low, z - axis_z * size[1] - size[0])
        elif kind == mujoco.mjtGeom.mjGEOM_CYLINDER:
            low = min(low, z - axis_z * size[1] - math.sqrt(max(0.0, 1 - axis_z ** 2)) * size[0])
        elif kind == mujoco.mjtGeom.mjGEOM_BOX:
            low = min(low, z - float(np.abs(rot[2]) @ size))
        else:
            raise AssertionError(f"lowest_point: add the {mujoco.mjtGeom(kind).name} of geom {model.geom(g).name!r}")
    return low


def test_catalogue_has_robots_and_environments():
    assert ROBOTS and ENVIRONMENTS


@pytest.mark.parametrize("robot_id", ROBOTS)
def test_robot_folder_documents_itself(robot_id):
    cls = CATALOGUE.get("robots", robot_id)
    assert (cls.folder / "README.md").is_file()
    assert (declaring_folder(cls, "xacro") / cls.xacro).is_file()  # its own, or the model it extends (NavPR2)
    assert cls.doc() and cls.short_descr


@pytest.mark.parametrize("robot_id", ROBOTS)
def test_robot_urdf_is_valid(robot_id, build_yaml):
    cls = CATALOGUE.get("robots", robot_id)
    out = build_yaml(robot_scene(robot_id, 0.0))
    path = out / "robots" / "r.urdf"

    urdf = yourdfpy.URDF.load(str(path), build_scene_graph=True, load_meshes=False, load_collision_meshes=False)
    assert urdf.validate()
    assert urdf.robot.name == "r"
    assert urdf.base_link
    links = {link.name for link in urdf.robot.links}
    # wheel names given as properties (MORSE's WheeledRobot) name links of the robot
    for prop, value in cls.Properties().model_dump().items():
        if prop.endswith("Name") and (prop.startswith("Wheel") or prop == "CasterWheelName"):
            assert value in links, f"{prop}={value!r} is not a link of {robot_id}"

    check_urdf = shutil.which("check_urdf")
    assert check_urdf, "check_urdf (liburdfdom-tools) is required: apt-get install liburdfdom-tools"
    result = subprocess.run([check_urdf, str(path)], capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Successfully Parsed XML" in result.stdout


@pytest.mark.parametrize("robot_id", ROBOTS)
def test_robot_left_alone_stays_put(robot_id, build_yaml):
    cls = CATALOGUE.get("robots", robot_id)
    floats = cls.Properties().NoGravity
    start_z = FLOAT_HEIGHT_M if floats else 0.0
    out = build_yaml(robot_scene(robot_id, start_z))
    urdf = yourdfpy.URDF.load(str(out / "robots" / "r.urdf"), build_scene_graph=False, load_meshes=False,
                              load_collision_meshes=False)
    urdf_mass = sum(link.inertial.mass for link in urdf.robot.links if link.inertial is not None)

    model = mujoco.MjModel.from_xml_path(str(out / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    body = model.body("r").id
    bodies = subtree_bodies(model, body)
    # the robot's own links (`r`, `r/<link>`) weigh what its URDF says; its default components (BasePR2's
    # armatures) add theirs
    own = [b for b in bodies if model.body(b).name == "r" or model.body(b).name.startswith("r/")]
    assert sum(model.body_mass[b] for b in own) == pytest.approx(urdf_mass, rel=1e-9, abs=1e-12)
    if not cls.default_components:
        assert model.body_subtreemass[body] == pytest.approx(urdf_mass, rel=1e-9, abs=1e-12)
    if not cls.collision:
        assert all(model.geom_contype[g] == 0 and model.geom_conaffinity[g] == 0
                   for g in range(model.ngeom) if model.geom_bodyid[g] in bodies)
    start = data.xpos[body].copy()
    # translate z is the origin (MORSE's placement), a robot on the ground stands on it (spawn_height up)
    assert cls.origin_z(start_z, cls.Properties()) == (start_z if floats else cls.spawn_height)
    assert start[2] == pytest.approx(start_z if floats else cls.spawn_height)
    colliding = [g for g in range(model.ngeom) if model.geom_bodyid[g] in bodies
                 and (model.geom_contype[g] or model.geom_conaffinity[g])]
    if colliding:  # spawn_height right: it is how far the origin is above the lowest colliding part
        assert lowest_point(model, data, colliding) == pytest.approx(start[2] - cls.spawn_height, abs=1e-6)

    run(model, data, SETTLE_S)
    moved = data.xpos[body] - start
    z_axis = data.xmat[body].reshape(3, 3)[:, 2]
    tilt = math.acos(min(1.0, float(z_axis[2])))
    if cls.static:
        assert model.body_jntnum[body] == 0 and model.body_dofnum[body] == 0
        assert np.allclose(moved, 0.0) and tilt == 0.0
        return
    assert model.jnt_type[model.body_jntadr[body]] == mujoco.mjtJoint.mjJNT_FREE
    assert math.hypot(moved[0], moved[1]) < MAX_DRIFT_M, f"drifted {moved}"
    # standing on the ground (spawn_height right) or floating: no fall, no jump
    assert abs(moved[2]) < MAX_DRIFT_M, f"moved vertically by {moved[2]:.4f} m"
    assert tilt < MAX_TILT, f"tipped by {math.degrees(tilt):.1f} deg"


MOVABLE = [r for r in ROBOTS if not CATALOGUE.get("robots", r).static]


@pytest.mark.parametrize("robot_id", MOVABLE)
def test_robot_with_no_gravity_floats(robot_id, build_yaml):
    """set NoGravity on any robot: it holds its pose in the air (MORSE's anti-gravity force)."""
    out = build_yaml(f"robots:\n  - {{name: r, type: {robot_id}, translate: [0.0, 0.0, {FLOAT_HEIGHT_M}], "
                     "properties: {NoGravity: true}}\n")
    model = mujoco.MjModel.from_xml_path(str(out / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    body = model.body("r").id
    start = data.xpos[body].copy()
    run(model, data, 2.0)
    assert np.linalg.norm(data.xpos[body] - start) < MAX_DRIFT_M


@pytest.mark.parametrize("robot_id", DIFFERENTIAL)
def test_differential_robot_wheel_joints(robot_id, build_yaml):
    """Robots naming a left and a right wheel (WheelFLName / WheelFRName, MORSE's WheeledRobot) drive
    them through continuous joints wheel_left_joint / wheel_right_joint about y."""
    props = CATALOGUE.get("robots", robot_id).Properties().model_dump()
    model = mujoco.MjModel.from_xml_path(str(build_yaml(robot_scene(robot_id, 0.0)) / "scene.xml"))
    for side, link in (("left", props["WheelFLName"]), ("right", props["WheelFRName"])):
        joint = model.joint(f"r/wheel_{side}_joint")
        assert joint.type[0] == mujoco.mjtJoint.mjJNT_HINGE
        assert np.allclose(joint.axis, [0, 1, 0])
        assert model.body(joint.bodyid[0]).name == f"r/{link}"


FLOORLESS = {"water-1/deep_water"}


@pytest.mark.parametrize("env_id", ENVIRONMENTS)
def test_environment_builds_and_steps(env_id, build_yaml):
    cls = CATALOGUE.get("environments", env_id)
    assert (cls.folder / "README.md").is_file()
    assert (cls.folder / cls.template).is_file()
    probe = 0.2
    out = build_yaml(f"environment: {{name: {env_id}}}\nobjects:\n"
                     f"  - {{name: probe, type: box, translate: [0.0, 0.0, 0.5], size: [{probe}, {probe}, {probe}], "
                     "dynamic: true}\n")
    model = mujoco.MjModel.from_xml_path(str(out / "scene.xml"))
    data = mujoco.MjData(model)
    assert model.nlight >= 1, "an environment is lit"
    world = [g for g in range(model.ngeom) if model.geom_bodyid[g] == 0]
    colliding = [g for g in world if model.geom_contype[g] or model.geom_conaffinity[g]]
    assert all(model.geom_contype[g] and model.geom_conaffinity[g] for g in world if model.geom_group[g] == 0), \
        "environment geoms in group 0 collide"
    if env_id in FLOORLESS:  # open water, as MORSE's: nothing to stand on, a dropped box sinks
        assert not colliding
        run(model, data, 1.0)
        assert data.xpos[model.body("probe").id][2] < -3.0
        return
    assert colliding, "an environment has something to stand on"
    run(model, data, 1.0)
    # a box dropped at the origin lands on the ground at z = 0
    assert data.xpos[model.body("probe").id][2] == pytest.approx(probe / 2, abs=0.005)
