"""Shared fixtures: the source tree, and building a scene written inline as YAML."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="session")
def repo_root() -> Path:
    return REPO


@pytest.fixture(scope="session", autouse=True)
def private_build_cache(tmp_path_factory):
    """The stamps of up-to-date builds (morsec.app.buildcache) go to a folder of the test session, not the
    user's cache; `morsec` processes the tests start inherit it."""
    import os
    previous = os.environ.get("XDG_CACHE_HOME")
    os.environ["XDG_CACHE_HOME"] = str(tmp_path_factory.mktemp("cache"))
    yield
    if previous is None:
        os.environ.pop("XDG_CACHE_HOME", None)
    else:
        os.environ["XDG_CACHE_HOME"] = previous


@pytest.fixture
def build_yaml(tmp_path):
    """`build_yaml(text, name="scene")`: write `text` to tmp_path/<name>.yaml, build it with the real
    compiler into tmp_path/<name>.build and return that folder."""
    from morsec.app.project import build_scene

    def build(text: str, name: str = "scene") -> Path:
        source = tmp_path / f"{name}.yaml"
        source.write_text(text, encoding="utf-8")
        return build_scene(source, tmp_path / f"{name}.build")

    return build


@pytest.fixture(scope="session")
def node_packages(repo_root) -> Path:
    """tests/node with Foxglove's JavaScript installed from its lock file (.ci/run does it first; a fresh
    checkout gets it here): its WebSocket client and its MCAP reader."""
    folder = repo_root / "tests" / "node"
    if not (folder / "node_modules" / "@mcap" / "core").is_dir() or \
            not (folder / "node_modules" / "@foxglove" / "ws-protocol").is_dir():
        subprocess.run(["npm", "ci", "--no-audit", "--no-fund"], cwd=folder, check=True, capture_output=True,
                       timeout=300)
    return folder
