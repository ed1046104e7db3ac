"""`morsec import-blend` and $MORSE_ROOT: MORSE's own .blend files (../shared/morse-assets, unmodified, read at
run time: fixtures the project does not ship) read without Blender, imported as component folders, and scenes
built and run on them."""

from __future__ import annotations

import gzip
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from morsec.app.blend import import_blend_file, list_blend
from morsec.app.scaffold import create_project
from morsec.errors import MorsecError
from morsec.kits.blend.scene import read_blend
from morsec.kits.blend.sdna import BlendFile, BlendFormatError
from morsec.kits.convex import convex_pieces
from morsec.testing import simulate

REPO = Path(__file__).resolve().parents[1]
ASSETS = Path(os.environ.get("MORSE_ASSETS", REPO.parent / "shared" / "morse-assets"))
MORSEC = Path(sys.executable).with_name("morsec")
needs_assets = pytest.mark.skipif(not ASSETS.is_dir(), reason=f"MORSE's .blend fixtures are not at {ASSETS} "
                                  "(../shared/morse-assets beside the checkout, or $MORSE_ASSETS)")

# file: (Blender version, objects read: an environment's visible layers, a props file's every object)
FILES = {
    "environments/apartment.blend": ("2.65", 39),
    "environments/empty.blend": ("2.62", 2),
    "environments/human_tut/tutorial_scene.blend": ("2.60", 29),
    "environments/indoors-1/boxes.blend": ("2.66", 9),
    "environments/indoors-1/indoor-1.blend": ("2.61", 23),
    "environments/sandbox.blend": ("2.74", 59),
    "environments/water-1/deep_water.blend": ("2.66", 2),
    "props/animated_water.blend": ("2.61", 3),
    "props/basics.blend": ("2.66", 9),
    "props/computer_parts.blend": ("2.61", 4),
    "props/crates.blend": ("2.62", 19),
    "props/misc_objects.blend": ("2.60", 10),
    "props/objects.blend": ("2.61", 34),
}
ENVIRONMENTS = [f for f in FILES if f.startswith("environments/")]
PROPS = [f for f in FILES if f.startswith("props/")]


def world_box(obj) -> tuple[np.ndarray, np.ndarray]:
    points = obj.mesh.vertices @ obj.matrix[:3, :3].T + obj.matrix[:3, 3]
    return points.min(axis=0), points.max(axis=0)


def env_id(relative: str) -> str:
    """The id the tests import an environment under: MORSE's names, below `morse/` (the catalogue has its own
    `empty`, `sandbox` and `indoors-1/boxes`)."""
    return "morse/" + relative.removeprefix("environments/").removesuffix(".blend")


# ---------------------------------------------------------------- reading

@needs_assets
@pytest.mark.parametrize("relative", FILES)
def test_reads_every_morse_file(relative):
    version, count = FILES[relative]
    scene = read_blend(ASSETS / relative, every_layer=relative.startswith("props/"))
    assert (scene.version, len(scene.objects)) == (version, count)
    assert len({o.name for o in scene.objects}) == count
    for obj in scene.objects:
        if obj.mesh is not None and len(obj.mesh.triangles):
            assert obj.mesh.triangles.max() < len(obj.mesh.vertices)
            assert np.isfinite(obj.matrix).all()


@needs_assets
def test_names_extents_physics_and_properties_as_blender_saved_them():
    tutorial = read_blend(ASSETS / "environments/human_tut/tutorial_scene.blend").by_name()
    low, high = world_box(tutorial["Walls"])  # the room: 8 x 12 m, 2.5 m high, 1 cm thick walls
    assert np.allclose(low, [-4.01, -6.01, 0.0], atol=0.005) and np.allclose(high, [4.01, 6.01, 2.5], atol=0.005)
    cup = tutorial["CubeSelect"]
    assert cup.properties == {"Object": True, "Description": "Cup", "Label": "Cup", "Type": "", "Graspable": True}
    assert (cup.physics, cup.bounds, cup.mass) == ("rigid_body", "cylinder", 1.0)
    assert tutorial["Walls"].physics == "static" and tutorial["Walls"].bounds == "triangle_mesh"
    assert tutorial["Shelf_COLLISION"].invisible and tutorial["TUT_Script_Holder"].kind == "empty"
    table = tutorial["Table"]  # a Mirror modifier on x and y: a quarter of the table and its three images
    assert len(table.mesh.vertices) == 4 * 28
    local = table.mesh.vertices
    assert np.isclose(local[:, 0].min(), -local[:, 0].max()) and np.isclose(local[:, 1].min(), -local[:, 1].max())

    indoor = read_blend(ASSETS / "environments/indoors-1/indoor-1.blend").by_name()
    low, high = world_box(indoor["Ground"])
    assert np.allclose(low, [-19.6, -15.0, 0.0], atol=0.01) and np.allclose(high, [19.6, 15.0, 0.0], atol=0.01)
    assert indoor["YellowBox"].properties == {"Object": "Box"} and indoor["RedBox"].mass == 5.0
    assert indoor["Lamp.002"].lamp.kind == "spot"
    assert [m.name for m in indoor["RedBox"].materials] == ["Material"]
    assert np.allclose(indoor["RedBox"].materials[0].color, [0.952, 0.115, 0.049, 1.0], atol=0.001)

    objects = read_blend(ASSETS / "props/objects.blend", every_layer=True).by_name()
    chair = objects["RollingChair"]
    assert chair.kind == "empty" and chair.compound and chair.physics == "rigid_body"
    parts = [o for o in objects.values() if o.parent == "RollingChair"]
    assert sorted(o.name for o in parts) == ["RollingChair_bb_1", "RollingChair_bb_2", "RollingChair_bb_3",
                                             "RollingChair_bb_4", "RollingChair_mesh"]
    assert all(o.bounds == "box" and o.invisible for o in parts if "_bb_" in o.name)

    parts = read_blend(ASSETS / "props/computer_parts.blend", every_layer=True).by_name()
    assert len(parts["cpu"].mesh.vertices) == 995  # its Array modifier is switched off: not applied
    assert any("Subsurf" in n for n in parts["keyboard"].notes)


@needs_assets
def test_applies_an_array_modifier_that_is_switched_on(tmp_path):
    path, raw, blend = blend_copy(tmp_path, "props/computer_parts.blend")
    cpu = next(blend.at(b) for b in blend.of_code(b"OB\0\0") if blend.at(b)["id"]["name"] == "OBcpu")
    array = blend.listbase(cpu["modifiers"]["first"])[0]
    mode = array.offset + array.field("modifier").offset + blend.fields("ModifierData")["mode"].offset
    raw[mode] = 1  # on in the viewport (and the game): 3 copies, each 4 widths from the last
    path.write_bytes(raw)
    vertices = read_blend(path, every_layer=True).by_name()["cpu"].mesh.vertices
    assert len(vertices) == 3 * 995
    width = np.ptp(vertices[:995, 0])
    assert np.ptp(vertices[:, 0]) == pytest.approx(9 * width, rel=1e-4)


def blend_copy(tmp_path, relative="environments/indoors-1/boxes.blend") -> tuple[Path, bytearray, BlendFile]:
    path = tmp_path / "copy.blend"
    shutil.copyfile(ASSETS / relative, path)
    return path, bytearray(path.read_bytes()), BlendFile(path)


def test_refuses_what_is_not_a_blend_file(tmp_path):
    cases = {
        "text.blend": (b"solid cube\n", "not a Blender file"),
        "zstd.blend": (b"\x28\xb5\x2f\xfd" + bytes(64), "compressed with zstd (Blender 3.0 or later)"),
        "new.blend": (b"BLENDER17-01v0401" + bytes(64), "header this reader does not know"),
        "cut.blend": (b"BLENDER-v266" + b"REND" + (400).to_bytes(4, "little") + bytes(20), "truncated"),
        "broken.blend": (gzip.compress(b"BLENDER-v266")[:20], "gzip file that does not decompress"),
    }
    for name, (data, message) in cases.items():
        (tmp_path / name).write_bytes(data)
        with pytest.raises(BlendFormatError, match=message.replace("(", r"\(").replace(")", r"\)")):
            read_blend(tmp_path / name)


@needs_assets
def test_refuses_linked_libraries_and_newer_mesh_layouts(tmp_path):
    path, raw, blend = blend_copy(tmp_path)
    ob = blend.at(blend.of_code(b"OB\0\0")[0])
    lib = ob.offset + ob.field("id").offset + blend.fields("ID")["lib"].offset
    raw[lib:lib + 8] = blend.of_code(b"DNA1")[0].address.to_bytes(8, "little")  # any block's address
    path.write_bytes(raw)
    with pytest.raises(BlendFormatError, match=r"is linked from the library .*Make Local"):
        read_blend(path)

    path, raw, blend = blend_copy(tmp_path)
    me = blend.at(blend.of_code(b"ME\0\0")[0])
    mvert = me.offset + me.field("mvert").offset
    raw[mvert:mvert + 8] = bytes(8)  # Blender 3.5+ keeps vertices as attributes: no MVert array
    path.write_bytes(raw)
    with pytest.raises(BlendFormatError, match=r"keeps its vertices as attributes \(Blender 3.5 or later\)"):
        read_blend(path)


def test_convex_pieces_keep_a_room_hollow_and_a_box_whole():
    box = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    outward = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))])
    assert len(convex_pieces(box, outward)) == 1  # closed and convex: its hull
    assert len(convex_pieces(box, outward[:, ::-1])) == 1  # faces looking inwards, as many meshes' do
    room = box * [8, 12, 2.5]
    open_room = outward[:, ::-1][2:10]  # floor and walls seen from inside, no ceiling
    pieces = convex_pieces(room, open_room)
    assert 5 <= len(pieces) <= 10
    centre = np.array([4, 6, 1.25])
    for piece in pieces:  # each a slab behind the floor or a wall (outside the room): none reaches its middle
        extent = piece.points.max(axis=0) - piece.points.min(axis=0)
        assert sorted(extent)[0] <= 0.021
        assert (piece.points.min(axis=0) <= [0, 0, 0]).any() or (piece.points.max(axis=0) >= [8, 12, 2.5]).any()
        assert np.abs(piece.points - centre).min(axis=0).max() >= 1.25  # all its points beyond a face


# ---------------------------------------------------------------- importing

@pytest.fixture(scope="module")
def project(tmp_path_factory):
    """A project with every fixture imported (environments under morse/, props files by name)."""
    if not ASSETS.is_dir():
        pytest.skip(f"MORSE's .blend fixtures are not at {ASSETS}")
    root = create_project("blendsim", tmp_path_factory.mktemp("projects"))
    for relative in ENVIRONMENTS:
        import_blend_file(ASSETS / relative, root / "components", "environment", env_id(relative))
    for relative in PROPS:
        import_blend_file(ASSETS / relative, root / "components", "props")
    return root


@needs_assets
def test_imports_write_component_folders_scenes_name(project):
    from morsec.component.catalogue import load_catalogue
    cat = load_catalogue(project)
    for relative in ENVIRONMENTS:
        cls = cat.get("environments", env_id(relative))
        assert Path(cls.folder).is_relative_to(project / "components")
    indoor = cat.get("environments", "morse/indoors-1/indoor-1")
    assert sorted(o["name"] for o in indoor.objects) == ["Bottle1", "GreenBox", "PinkBox", "RedBox", "YellowBox"]
    red = next(o for o in indoor.objects if o["name"] == "RedBox")
    assert np.allclose(red["translate"], [-1.47, 1.69, 0.51], atol=0.01)
    box = cat.get("props", red["type"])
    assert box.defaults["dynamic"] and box.defaults["mass"] == 5.0 and box.defaults["properties"] == {"Object": True}
    assert np.allclose(box.defaults["size"], [1.0, 1.0, 1.0], atol=0.01)
    tutorial = cat.get("environments", "morse/human_tut/tutorial_scene")
    names = {o["name"] for o in tutorial.objects}  # Blender's "Drawers_Drawer.004": '.' joins scene names
    assert {"CubeSelect", "Drawers_Drawer_004", "Shelf_UpperDoor_L"} <= names
    chair = cat.get("props", "objects/RollingChair")
    assert chair.defaults["size"] == pytest.approx([0.6, 0.63, 0.93], abs=0.01) and chair.defaults["mass"] == 1.0
    assert sorted(p.id for p in cat.by_kind["props"].values() if p.id.startswith("objects/")) == [
        "objects/BlackVideotape", "objects/BlueToyTrashbin", "objects/BoxStand", "objects/Cube", "objects/Desk",
        "objects/GreyVideotape", "objects/IKEAShelf", "objects/PinkToyTrashbin", "objects/RollingChair",
        "objects/SmallTable", "objects/WhiteVideotape"]
    text = (project / "scene.schema.json").read_text()
    assert '"objects/RollingChair"' in text or "objects/RollingChair" in text


def run_robot(project, tmp_path, environment, seconds, start=(0.0, 0.0, 0.0), drive=None, objects=()):
    scene = {"environment": {"name": environment},
             "robots": [{"name": "robot", "type": "atrv", "translate": list(start),
                         "components": [{"name": "pose", "type": "pose"}, {"name": "motion", "type": "motion_vw"}]}],
             "objects": list(objects)}
    return simulate(scene, tmp_path, project=project)


@needs_assets
@pytest.mark.parametrize("relative", ENVIRONMENTS)
def test_a_robot_stands_in_each_imported_environment(project, tmp_path, relative):
    with run_robot(project, tmp_path, env_id(relative), 1.0) as sim:
        sim.run_for(1.0)
        z = sim.data("robot.pose")["z"]
    if relative.endswith("deep_water.blend"):
        assert z < -1.0  # MORSE's water surface is drawn and collides with nothing: a wheeled robot sinks
    else:
        assert 0.07 < z < 0.11  # on the imported floor (the apartment's is 1.7 cm below 0), not through it


@needs_assets
def test_a_robot_drives_in_the_tutorial_room_and_its_wall_stops_it(project, tmp_path):
    with run_robot(project, tmp_path, env_id("environments/human_tut/tutorial_scene.blend"), 0,
                   start=(0.0, -3.0, 0.0)) as sim:
        sim.command("robot.motion", v=0.5, w=0.0)
        sim.run_for(2.0)
        assert sim.data("robot.pose")["x"] == pytest.approx(0.94, abs=0.03)  # the floor between is clear
        farthest = 0.0
        for _ in range(16):
            sim.run_for(0.5)
            farthest = max(farthest, sim.data("robot.pose")["x"])
    assert 3.4 < farthest < 4.0  # it reached the wall (inner face x = 4.0) and did not pass it


@needs_assets
def test_props_fall_onto_an_imported_floor_and_rest(project, tmp_path):
    objects = [{"name": "chair", "type": "objects/RollingChair", "translate": [2.0, 0.0, 1.0]},
               {"name": "big_chair", "type": "objects/RollingChair", "translate": [-2.0, 0.0, 1.0],
                "size": [1.2, 1.26, 1.86]},
               {"name": "crate", "type": "crates/large_crate", "translate": [-4.0, 3.0, 1.0]},
               {"name": "ball", "type": "morse/sandbox/Ball1", "translate": [0.0, 3.0, 1.0]},
               {"name": "bottle", "type": "misc_objects/Bottle", "translate": [0.0, -3.0, 1.0]}]
    with run_robot(project, tmp_path, env_id("environments/empty.blend"), 0, objects=objects) as sim:
        sim.run_for(0.3)
        assert sim.body_pose("chair")[0][2] < 0.8  # falling
        sim.run_for(2.7)
        rest = {o["name"]: sim.body_pose(o["name"])[0] for o in objects}
        sim.run_for(0.5)
        moved = {name: np.linalg.norm(sim.body_pose(name)[0] - pos) for name, pos in rest.items()}
        import mujoco
        model = sim.sim.model
        boxes = {name: sorted(model.geom_size[g][:3].tolist() for g in range(model.ngeom)
                              if model.geom_bodyid[g] == mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)
                              and model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX)
                 for name in ("chair", "big_chair")}
    assert all(d < 0.005 for d in moved.values()), moved  # at rest
    assert abs(rest["chair"][2]) < 0.02  # its origin is under its column, on the floor
    assert abs(rest["crate"][2]) < 0.02
    assert rest["ball"][2] == pytest.approx(0.248, abs=0.01)  # MORSE's sphere bounds: radius 0.248
    assert 0.1 < rest["bottle"][2] < 0.3
    assert np.allclose(np.array(boxes["big_chair"]), 2 * np.array(boxes["chair"]), rtol=1e-3)  # `size` scales it


@needs_assets
@pytest.mark.parametrize("relative", PROPS)
def test_every_prop_of_each_props_file_builds_and_runs(project, tmp_path, relative):
    """Each prop of the file 1 m over the imported floor: what moves falls and stays above the floor, what is
    static stays where it is put."""
    from morsec.component.catalogue import load_catalogue
    stem = Path(relative).stem
    cat = load_catalogue(project)
    props = [cls for cid, cls in sorted(cat.by_kind["props"].items()) if cid.startswith(stem + "/")]
    assert props
    objects, x, y, row = [], -19.0, 2.0, 0.0  # side by side, 1 m apart, on the 40 x 40 m floor
    for i, cls in enumerate(props):
        width, depth = (max(cls.defaults["size"][:2]) + 1.0,) * 2
        if x + width > 19.0:
            x, y, row = -19.0, y + row, 0.0
        objects.append({"name": f"p{i}", "type": cls.id, "translate": [x + width / 2, y + depth / 2, 1.0]})
        x, row = x + width, max(row, depth)
    with run_robot(project, tmp_path, env_id("environments/empty.blend"), 0, objects=objects) as sim:
        sim.run_for(2.0)
        heights = {o["name"]: sim.body_pose(o["name"])[0][2] for o in objects}
    for obj, cls in zip(objects, props):
        if cls.defaults["dynamic"]:
            assert -0.05 < heights[obj["name"]] < 0.99, cls.id  # fell, and rests on the floor
        else:
            assert heights[obj["name"]] == pytest.approx(1.0), cls.id


@needs_assets
def test_an_environment_keeps_its_objects_names_properties_and_physics(project, tmp_path):
    with run_robot(project, tmp_path, env_id("environments/indoors-1/indoor-1.blend"), 0) as sim:
        tagged = sorted(o.name for o in sim.sim.objects_with("Object"))
        sim.run_for(2.0)
        red, _ = sim.body_pose("RedBox")
        yellow, _ = sim.body_pose("YellowBox")
    assert tagged == ["Bottle1", "GreenBox", "PinkBox", "RedBox", "YellowBox"]
    assert red[2] == pytest.approx(0.51, abs=0.02)  # MORSE's RedBox, dynamic, rests on the floor
    assert yellow[2] < 1.8  # saved 1.8 m up in the air, it fell onto what is under it


# ---------------------------------------------------------------- the command

def morsec(*args, cwd: Path, env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([str(MORSEC), *args], cwd=cwd, capture_output=True, text=True, timeout=300,
                          env={**os.environ, **(env or {})})


@needs_assets
def test_the_command_imports_and_says_how_to_use_it(tmp_path):
    create_project("sim", tmp_path)
    sim = tmp_path / "sim"
    done = morsec("import-blend", str(ASSETS / "props/objects.blend"), "--kind", "props", cwd=sim)
    assert done.returncode == 0, done.stderr
    assert "PassiveObject('props/objects', 'BlackVideotape')" in done.stdout
    assert (sim / "components/props/objects/RollingChair/component.py").is_file()
    again = morsec("import-blend", str(ASSETS / "props/objects.blend"), "--kind", "props", cwd=sim)
    assert again.returncode == 2 and "already exist" in again.stderr and "--force" in again.stderr
    assert morsec("import-blend", str(ASSETS / "props/objects.blend"), "--kind", "props", "-f", cwd=sim).returncode == 0
    script = sim / "scenes" / "chair.py"
    script.write_text(textwrap.dedent("""\
        from morse.builder import *
        robot = ATRV()
        chair = PassiveObject('props/objects', 'RollingChair')
        chair.translate(2.0, 0.0, 0.0)
        env = Environment('empty')
        """))
    built = morsec("build", "scenes/chair.py", "-o", "build/chair", cwd=sim)
    assert built.returncode == 0, built.stderr
    assert '"type": "objects/RollingChair"' in (sim / "build/chair/manifest.json").read_text()
    listing = morsec("import-blend", str(ASSETS / "props/objects.blend"), "--kind", "props", "--list", cwd=sim)
    assert "RollingChair: empty at" in listing.stdout and "rigid body, mass 1 kg" in listing.stdout


@needs_assets
def test_the_command_refuses_in_one_line_and_writes_nothing(tmp_path):
    create_project("sim", tmp_path)
    sim = tmp_path / "sim"
    (tmp_path / "notes.blend").write_text("not a blend\n")
    cases = [
        (["import-blend", str(tmp_path / "notes.blend")], "cannot import it: not a Blender file"),
        (["import-blend", str(tmp_path / "absent.blend")], "absent.blend: no such file"),
        (["import-blend", str(ASSETS / "environments/empty.blend")],
         "environment 'empty' exists already"),  # the catalogue's: --name gives another id
        (["import-blend", str(ASSETS / "props/crates.blend"), "--kind", "prop"], "--kind 'prop': environment or props"),
    ]
    before = sorted(p.relative_to(sim) for p in sim.rglob("*"))
    for args, message in cases:
        result = morsec(*args, cwd=sim)
        assert result.returncode == 2 and message in result.stderr, result.stderr
        assert len(result.stderr.strip().splitlines()) <= 2 and "Traceback" not in result.stderr
    assert sorted(p.relative_to(sim) for p in sim.rglob("*")) == before
    outside = morsec("import-blend", str(ASSETS / "props/crates.blend"), "--kind", "props", cwd=tmp_path)
    assert outside.returncode == 2 and "not in a morsec project" in outside.stderr


# ---------------------------------------------------------------- $MORSE_ROOT

def morse_root(tmp_path) -> Path:
    """A MORSE installation's data tree made of the fixtures."""
    root = tmp_path / "morse"
    data = root / "share" / "morse" / "data"
    for relative in ("environments/indoors-1/boxes.blend", "environments/indoors-1/indoor-1.blend",
                     "props/objects.blend"):
        (data / relative).parent.mkdir(parents=True, exist_ok=True)
        (data / relative).symlink_to(ASSETS / relative)
    return root


@needs_assets
def test_morse_root_files_take_precedence_only_while_it_is_set(tmp_path, monkeypatch):
    from morsec.component.catalogue import load_catalogue
    from morsec.resources import data_dir
    script = tmp_path / "tutorial.py"
    script.write_text(textwrap.dedent("""\
        from morse.builder import *
        robot = ATRV()
        chair = PassiveObject('props/objects', 'RollingChair')
        chair.translate(2.0, 0.0, 0.0)
        env = Environment('indoors-1/boxes')
        """))
    monkeypatch.delenv("MORSE_ROOT", raising=False)
    cat = load_catalogue(tmp_path)
    builtin = cat.get("environments", "indoors-1/boxes")
    assert Path(builtin.folder).is_relative_to(data_dir("components"))
    from morsec.frontends.load import load_scene
    assert [o.type for o in load_scene(script, cat).objects if o.name == "chair"] == ["RollingChair"]  # the catalogue's

    cache = tmp_path / "cache"
    monkeypatch.setenv("MORSE_ROOT", str(morse_root(tmp_path)))
    monkeypatch.setenv("XDG_CACHE_HOME", str(cache))
    cat = load_catalogue(tmp_path)
    scene = load_scene(script, cat)
    imported = cat.get("environments", "indoors-1/boxes")
    assert Path(imported.folder).is_relative_to(cache) and imported is not builtin
    assert [o.type for o in scene.objects if o.name == "chair"] == ["objects/RollingChair"]
    assert {o.name for o in scene.objects} >= {"RedBox", "GreenBox", "BlueBox", "chair"}
    assert cat.resolve("environments", "indoors-1/indoor-1.blend") == "indoors-1/indoor-1"

    env = {"MORSE_ROOT": os.environ["MORSE_ROOT"], "XDG_CACHE_HOME": str(cache)}
    built = morsec("build", str(script), "-o", str(tmp_path / "build"), cwd=tmp_path, env=env)
    assert built.returncode == 0, built.stderr
    assert "environment 'indoors-1/boxes' is MORSE's" in built.stderr  # the output says where it came from
    assert "props file 'objects' is MORSE's" in built.stderr
    (tmp_path / "run").mkdir()
    with simulate({"environment": {"name": "indoors-1/indoor-1"},
                   "objects": [{"name": "chair", "type": "objects/RollingChair", "translate": [0, 0, 0.5]}]},
                  tmp_path / "run", project=tmp_path) as sim:
        sim.run_for(1.5)
        assert abs(sim.body_pose("chair")[0][2]) < 0.02
        assert sim.body_pose("RedBox")[0][2] == pytest.approx(0.51, abs=0.02)


def test_lists_what_a_file_holds_or_says_why_not(tmp_path):
    (tmp_path / "x.blend").write_bytes(b"BLENDER-v266")
    with pytest.raises(MorsecError, match="x.blend: cannot read it: truncated"):
        list_blend(tmp_path / "x.blend")
