"""Meshes in component folders (the seed's append_meshes): copied or converted into the build, resolved
from a robot's URDF, and a clear error listing the paths searched when a file is missing."""

import pytest
import trimesh

from morsec.app.project import build_scene
from morsec.errors import SceneError

URDF = """<?xml version="1.0"?>
<robot name="$(arg name)" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:arg name="name" default="m"/>
<link name="base_link"><inertial><mass value="1"/><inertia ixx="0.04" ixy="0" ixz="0" iyy="0.04" iyz="0" izz="0.04"/></inertial>
<visual><geometry><mesh filename="package://meshbot/shell.obj" scale="2 2 2"/></geometry></visual>
<collision><geometry><sphere radius="0.3"/></geometry></collision></link></robot>"""


@pytest.fixture
def project(tmp_path, monkeypatch):
    root = tmp_path / "proj"
    sensor, robot = root / "components/sensors/blob", root / "components/robots/meshbot"
    sensor.mkdir(parents=True)
    robot.mkdir(parents=True)
    (root / "morsec.toml").write_text('[project]\nname = "m"\ncomponents = ["components"]\n')
    trimesh.creation.box((0.2, 0.1, 0.05)).export(sensor / "body.ply")
    trimesh.creation.icosphere(radius=0.15).export(robot / "shell.obj")
    (sensor / "component.py").write_text("from morsec.component import Sensor\n\n\nclass Blob(Sensor):\n"
                                         "    short_descr = 'a blob'\n\n\nCOMPONENT = Blob\n")
    (sensor / "assets.xml.j2").write_text('<mesh name="{{ id }}/body" file="{{ asset_dir }}/body.stl"/>\n')
    (sensor / "model.xml.j2").write_text('<geom type="mesh" mesh="blob/body" rgba="1 0 0 1"/>\n')
    (robot / "component.py").write_text("from morsec.component import Robot\n\n\nclass Meshbot(Robot):\n"
                                        "    short_descr = 'a ball'\n    spawn_height = 0.3\n\n\nCOMPONENT = Meshbot\n")
    (robot / "robot.urdf.xacro").write_text(URDF)
    (root / "s.yaml").write_text("robots:\n  - name: r\n    type: meshbot\n    components:\n"
                                 "      - {name: b, type: blob}\n")
    monkeypatch.chdir(root)
    return root


def test_meshes_are_copied_converted_and_declared(project):
    import mujoco
    out = build_scene(project / "s.yaml", project / "b")
    converted = trimesh.load(out / "assets/sensors/blob/body.stl")  # the PLY, converted to STL
    assert converted.extents == pytest.approx([0.2, 0.1, 0.05])
    assert (out / "assets/robots/meshbot/shell.obj").read_bytes() == (project / "components/robots/meshbot/shell.obj").read_bytes()
    model = mujoco.MjModel.from_xml_path(str(out / "scene.xml"))
    names = [model.mesh(i).name for i in range(model.nmesh)]
    assert sorted(names) == ["blob/body", "meshbot/shell@2x2x2"]
    shell = model.mesh("meshbot/shell@2x2x2")
    verts = model.mesh_vert[shell.vertadr[0]:shell.vertadr[0] + shell.vertnum[0]]
    assert abs((verts.max(axis=0) - verts.min(axis=0)).max() - 0.6) < 0.02  # 0.15 m radius, scaled by 2


def test_missing_mesh_lists_the_paths_searched(project, monkeypatch):
    (project / "components/robots/meshbot/shell.obj").unlink()
    monkeypatch.setenv("MORSE_RESOURCE_PATH", str(project / "data"))
    with pytest.raises(SceneError) as err:
        build_scene(project / "s.yaml", project / "b")
    message = str(err.value)
    assert message.startswith(f"{project / 's.yaml'}:3:11: robots[0].type: robot 'meshbot': asset file "
                              "'package://meshbot/shell.obj' not found; searched: ")
    assert str(project / "components/robots/meshbot/shell.obj") in message
    assert str(project / "data/shell.obj") in message
    assert not (project / "b").exists()
