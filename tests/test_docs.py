"""docs/: the generated pages are fresh, `morsec docs` writes them, and every page is linked and links well."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from morsec.app.docsgen import GENERATED_PAGES, REGENERATE, generate
from morsec.component.catalogue import load_catalogue
from morsec.scene import models

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
HAND_WRITTEN = ("index.md", "getting-started.md", "errors.md")


@pytest.fixture(autouse=True)
def _builtin_catalogue(monkeypatch):
    monkeypatch.delenv("MORSEC_COMPONENTS", raising=False)


@pytest.fixture(scope="module")
def fresh() -> dict[str, str]:
    return generate(load_catalogue(ROOT), DOCS)


def test_gallery_pages_are_fresh_and_have_their_pictures(fresh):
    """docs/components/<kind>/<id>.md for every catalogue component, each with its rendered picture."""
    gallery = {page for page in fresh if page.startswith("components/")}
    cat = load_catalogue(ROOT)
    assert len(gallery) == 1 + sum(len(cat.ids(kind)) for kind in ("robots", "sensors", "actuators",
                                                                   "environments", "props"))
    stale = [page for page in sorted(gallery) if not (DOCS / page).is_file()
             or (DOCS / page).read_text(encoding="utf-8") != fresh[page]]
    assert not stale, f"gallery pages {stale[:5]} are stale: run `morsec docs -o docs --pictures`"
    for page in gallery:
        for image in re.findall(r"!\[[^]]*\]\(([^)]+\.png)\)", fresh[page]):
            assert ((DOCS / page).parent / image).resolve().is_file(), f"{page}: missing picture {image}: " \
                "run `morsec docs -o docs --pictures`"
    extra = {str(p.relative_to(DOCS)) for p in (DOCS / "components").rglob("*.md")} - gallery
    assert not extra, f"gallery pages of components that no longer exist: {sorted(extra)}"


@pytest.mark.parametrize("page", GENERATED_PAGES)
def test_generated_page_is_fresh(fresh, page):
    path = DOCS / page
    checked_in = path.read_text(encoding="utf-8") if path.is_file() else ""
    assert checked_in == fresh[page], (f"docs/{page} is stale (the scene models or the component catalogue "
                                       f"changed): run `{REGENERATE}` from the repository root")


def test_morsec_docs_writes_the_generated_pages(tmp_path):
    out = tmp_path / "docs"
    result = subprocess.run([sys.executable, "-c", "from morsec.cli import main; main()", "docs", "-o", str(out)],
                            cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    expected = generate(load_catalogue(ROOT), out)
    assert sorted(str(p.relative_to(out)) for p in out.rglob("*.md")) == sorted(expected)
    for page in expected:
        assert (out / page).read_text(encoding="utf-8") == expected[page]


def test_scene_format_documents_every_field(fresh):
    page = fresh["scene-format.md"]
    for model in (models.EnvironmentBase, models.TimeSpec, models.CameraSpec, models.ViewportSpec,
                  models.StreamManagerSpec, models.MultinodeSpec, models.RobotBase, models.ComponentBase,
                  models.StreamSpec, models.ModifierSpec, models.OverlaySpec, models.ObjectSpec, models.ZoneSpec):
        for name, info in model.model_fields.items():
            row = re.search(rf"^\| `{re.escape(name)}` \|[^\n]*$", page, re.M)
            assert row, f"{model.__name__}.{name} is not in scene-format.md"
            if info.description:
                assert any(info.description.replace("|", "\\|") in line
                           for line in page.splitlines() if line.startswith(f"| `{name}` |")), name
    for section in ("environment", "time", "camera", "robots", "components", "streams", "modifiers",
                    "objects", "zones", "multinode"):
        assert f'<a id="{section}"></a>' in page


def test_components_page_lists_the_catalogue(fresh):
    page = fresh["components.md"]
    cat = load_catalogue(ROOT)
    for cls in cat.all():
        row = re.search(rf"^\| \[`{re.escape(cls.id)}`\]\(#[^)]*\) \| `{re.escape(cls.builder_name)}` \|", page, re.M)
        assert row, f"{cls.kind} {cls.id} is missing from components.md"


def test_index_links_every_page():
    index = (DOCS / "index.md").read_text(encoding="utf-8")
    pages = sorted(p.name for p in DOCS.glob("*.md") if p.name != "index.md")
    assert set(HAND_WRITTEN + GENERATED_PAGES) <= {p.name for p in DOCS.glob("*.md")}
    for page in pages:
        assert f"]({page})" in index, f"docs/index.md does not link {page}"


def _anchors(text: str) -> set[str]:
    ids = set(re.findall(r'<a id="([^"]+)"></a>', text))
    for heading in re.findall(r"^#+ (.+)$", text, re.M):
        slug = re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")
        ids.add(slug)
    return ids


@pytest.mark.parametrize("page", sorted(p.name for p in DOCS.glob("*.md")))
def test_relative_links_resolve(page):
    text = (DOCS / page).read_text(encoding="utf-8")
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"^[a-z]+:", target):
            continue
        file, _, anchor = target.partition("#")
        path = (DOCS / file) if file else DOCS / page
        assert path.exists(), f"docs/{page} links to {target}, which does not exist"
        if anchor and path.suffix == ".md":
            assert anchor in _anchors(path.read_text(encoding="utf-8")), f"docs/{page}: no anchor for {target}"


def test_getting_started_names_the_commands():
    text = (DOCS / "getting-started.md").read_text(encoding="utf-8")
    for command in ("python3 -m pip install -e '.[test]'", "morsec build scenes/tutorial.yaml -o build/tutorial",
                    "python -m mujoco.viewer --mjcf build/tutorial/scene.xml", "morsec check scenes/*.yaml",
                    "morsec schema > my-editor-schema.json", "# yaml-language-server: $schema="):
        assert command in text, command
