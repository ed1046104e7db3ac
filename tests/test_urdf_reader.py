"""The compiler reads URDF with its own small reader (morsec.compiler.urdf.read_urdf, on the standard library's
XML parser), not yourdfpy, whose import (trimesh, scipy, networkx) cost a build more than half of its time.
The reader must see every catalogue xacro exactly as yourdfpy does: same links, joints, origins, inertias,
geometries and colours, to the last bit and the same number types, so that the compiled scene is the same."""

from __future__ import annotations

import io
import subprocess
import sys
from dataclasses import fields
from pathlib import Path

import numpy as np
import pytest
import yourdfpy

from morsec.compiler.urdf import Link, expand_xacro, link_tree, read_urdf
from morsec.component.catalogue import load_catalogue
from morsec.errors import SceneError

CATALOGUE = load_catalogue(Path(__file__).parent)
XACROS = sorted({str(Path(cls.folder) / cls.xacro) for cls in CATALOGUE.all() if getattr(cls, "xacro", None)
                 and (Path(cls.folder) / cls.xacro).is_file()})


def with_yourdfpy(text: str, source: str) -> Link:
    urdf = yourdfpy.URDF.load(io.StringIO(text), build_scene_graph=False, build_collision_scene_graph=False,
                              load_meshes=False, load_collision_meshes=False)
    return link_tree(urdf.robot, source)


def exactly(value):
    """A value with its type, its array dtype and its bits (-0.0 is not 0.0)."""
    if isinstance(value, np.ndarray):
        return ("array", value.dtype.str, value.shape, value.tobytes())
    if isinstance(value, (list, tuple)):
        return (type(value).__name__, [exactly(v) for v in value])
    if isinstance(value, dict):
        return ("dict", sorted((k, exactly(v)) for k, v in value.items()))
    if isinstance(value, (float, np.floating)):
        return (type(value).__name__, np.float64(value).tobytes())
    if isinstance(value, (Link,)) or hasattr(value, "__dataclass_fields__"):
        return (type(value).__name__, [(f.name, exactly(getattr(value, f.name))) for f in fields(value)])
    return (type(value).__name__, value)


def test_there_are_xacros_to_compare():
    assert len(XACROS) >= 10


@pytest.mark.parametrize("path", XACROS, ids=lambda p: str(Path(p).parent.relative_to(Path(p).parents[2])))
def test_reader_sees_what_yourdfpy_sees(path):
    text = expand_xacro(Path(path), {"name": "r"})
    assert exactly(read_urdf(text, path)) == exactly(with_yourdfpy(text, path))


def test_origins_rotations_inertias_and_colours_to_the_last_bit():
    text = """<robot name="r">
      <material name="blue"><color rgba="0.1 0.2 0.3 1"/></material>
      <link name="base">
        <inertial><origin xyz="0.1 -0.2 0.3" rpy="0.3 -1.2 2.9"/><mass value="2.5"/>
          <inertia ixx="0.1" ixy="0.01" ixz="-0.02" iyy="0.2" iyz="0.03" izz="0.3"/></inertial>
        <visual><origin xyz="1 2 3" rpy="-0.0 3.14159 -1.5707963"/><geometry><box size="0.1,0.2,0.3"/></geometry>
          <material name="blue"/></visual>
        <collision><origin rpy="0.7 0.1 -0.4"/><geometry><cylinder radius="0.1" length="0.5"/></geometry></collision>
      </link>
      <link name="arm"><visual><geometry><mesh filename="m.stl" scale="1 2 3"/></geometry>
        <material name="red"><color rgba="1 0 0 0.5"/></material></visual>
        <collision><geometry><sphere radius="0.2"/></geometry></collision></link>
      <link name="tip"/>
      <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/>
        <origin xyz="0 0 0.5" rpy="1e-3 -2.2 0.25"/><axis xyz="0 1 0"/>
        <limit lower="-1" upper="1.5" effort="1" velocity="1"/><dynamics damping="0.5" friction="0.1"/></joint>
      <joint name="j2" type="prismatic"><parent link="arm"/><child link="tip"/><axis xyz="0 0 -1"/>
        <limit lower="0" upper="0.2"/></joint>
    </robot>"""
    assert exactly(read_urdf(text, "t.urdf")) == exactly(with_yourdfpy(text, "t.urdf"))


@pytest.mark.parametrize("text, says", [
    ("<robot name='r'><link name='a'></robot>", "invalid URDF"),
    ("<robot name='r'><link name='a'><visual><geometry><cone/></geometry></visual></link></robot>", "cone"),
    ("<robot name='r'><link name='a'><inertial><mass value='heavy'/></inertial></link></robot>", "heavy"),
    ("<robot name='r'><link name='a'/><link name='b'/></robot>", "exactly one root link"),
])
def test_a_bad_urdf_is_one_error(text, says):
    with pytest.raises(SceneError, match=says):
        read_urdf(text, "bad.urdf")


def test_building_does_not_import_yourdfpy(tmp_path):
    """A build of a scene with a robot reads its URDF without yourdfpy, trimesh or scipy."""
    scene = tmp_path / "s.yaml"
    scene.write_text("environment: {name: empty}\nrobots:\n  - {name: r, type: atrv}\n")
    code = ("import sys\nfrom pathlib import Path\nfrom morsec.app.project import build_scene\n"
            f"build_scene(Path({str(scene)!r}), Path({str(tmp_path / 'build')!r}))\n"
            "print(sorted(m for m in ('yourdfpy', 'trimesh', 'scipy', 'networkx') if m in sys.modules))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "[]"
