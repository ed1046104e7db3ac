"""Shared fixtures: the source tree, and building a scene written inline as YAML."""

from __future__ import annotations

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="session")
def repo_root() -> Path:
    return REPO


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
