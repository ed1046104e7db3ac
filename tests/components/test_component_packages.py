"""A component folder is a package: component.py imports the modules beside it (`from . import helpers`,
`from .maths.scale import double`), each folder its own (two projects may have the same helper names), and
a preset of it (component_class) reuses the loaded module."""

from __future__ import annotations

from pathlib import Path

import pytest

from morsec.component.catalogue import load_catalogue
from morsec.errors import MorsecError
from morsec.testing import simulate

RANGER = '''from morsec.component import DataField, Sensor

from . import helpers
from .maths.scale import double


class Ranger(Sensor):
    """Reads a range its helper modules compute."""

    data = (DataField("range", 0.0, "float", "m"), DataField("label", "", "str", "from helpers.py"))

    def default_action(self):
        self.local_data["range"] = double(helpers.BASE)
        self.local_data["label"] = helpers.label()


COMPONENT = Ranger
'''

HELPERS = '''from .maths import scale

BASE = {base}


def label():
    return "{label}" + str(scale.FACTOR)
'''

PRESET = '''from pathlib import Path

from morsec.component import component_class

Ranger = component_class("sensors", "ranger", Path(__file__).parent)


class RangerLong(Ranger):
    """A ranger reading farther."""

    builder_name = "RangerLong"

    def default_action(self):
        super().default_action()
        self.local_data["range"] *= 10
'''


def make_project(root: Path, base: float, label: str) -> Path:
    root.mkdir(parents=True, exist_ok=True)
    (root / "morsec.toml").write_text('[project]\nname = "p"\ncomponents = ["components"]\n')
    folder = root / "components" / "sensors" / "ranger"
    (folder / "maths").mkdir(parents=True)
    (folder / "component.py").write_text(RANGER)
    (folder / "helpers.py").write_text(HELPERS.format(base=base, label=label))
    (folder / "maths" / "__init__.py").write_text("FACTOR = 2\n")
    (folder / "maths" / "scale.py").write_text("from . import FACTOR\n\n\ndef double(x):\n    return FACTOR * x\n")
    preset = root / "components" / "sensors" / "ranger_long"
    preset.mkdir()
    (preset / "component.py").write_text(PRESET + "\n\nCOMPONENT = RangerLong\n")
    return root


SCENE = """environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    components: [{name: ranger, type: ranger}, {name: far, type: ranger_long}]
"""


def test_component_py_imports_the_modules_of_its_folder(tmp_path):
    project = make_project(tmp_path / "a", 1.5, "a")
    with simulate(SCENE, tmp_path, project=project) as h:
        h.step()
        assert h.data("r.ranger")["range"] == 3.0
        assert h.data("r.ranger")["label"] == "a2"
        assert h.data("r.far")["range"] == 30.0
    cat = load_catalogue(project)
    ranger = cat.get("sensors", "ranger")
    assert ranger.__module__.endswith(".component")
    assert issubclass(cat.get("sensors", "ranger_long"), ranger)  # the preset reused the loaded module


def test_two_projects_with_the_same_helper_names_keep_their_own(tmp_path):
    first = make_project(tmp_path / "a", 1.0, "a")
    second = make_project(tmp_path / "b", 4.0, "b")
    with simulate(SCENE, tmp_path / "a", project=first) as a, simulate(SCENE, tmp_path / "b", project=second) as b:
        a.step()
        b.step()
        assert (a.data("r.ranger")["range"], a.data("r.ranger")["label"]) == (2.0, "a2")
        assert (b.data("r.ranger")["range"], b.data("r.ranger")["label"]) == (8.0, "b2")


def test_a_missing_helper_names_the_component_file(tmp_path):
    project = make_project(tmp_path, 1.0, "a")
    (project / "components" / "sensors" / "ranger" / "helpers.py").unlink()
    with pytest.raises(MorsecError, match=r"ranger/component\.py: cannot load component: ImportError: .*helpers"):
        load_catalogue(project)
