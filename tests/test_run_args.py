"""`morsec run`'s command line read without typer (morsec.cli.run_args): whatever it reads, typer reads to the
same values; what it does not read, typer does (its help, its errors); the usual command lines are read."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import morsec.cli.run_scene as run_scene_module
from morsec.cli.assemble import make_app
from morsec.cli.run_args import TABLE, describe_run, parse_run_args, run_args_json

REPO = Path(__file__).resolve().parent.parent
PARAMETERS = json.loads(TABLE.read_text())["parameters"].values()
OPTIONS = [opt for p in PARAMETERS for opt in p.get("opts", ())]
FLAGS = {opt for p in PARAMETERS if p["type"] == "flag" for opt in p["opts"]}
VALUES = ["0", "7", "-1", "007", "+5", "1.5", "-2.25", "1e3", "1E-2", ".5", "5.", "1_0", " 5", "0x10", "inf", "nan",
          "99999999999999999999", "abc", "", "-", "--", "fixed_step", "best_effort", "FIXED_STEP", "web", "native",
          "build", "scene.yaml", "a b", "-o", "--help", "--duration"]


def typer_reads(args: list[str]) -> dict | None:
    """The keyword arguments typer's `run` passes to run_scene for `morsec run ARGS`, or None when it refuses them."""
    seen: list[dict] = []
    original = run_scene_module.run_scene
    run_scene_module.run_scene = lambda scene, **kwargs: seen.append({"scene": scene, **kwargs})
    try:
        make_app("run")(args=["run", *args], prog_name="morsec", standalone_mode=False)
    except Exception:  # click's usage errors, typer's bad parameters
        return None
    finally:
        run_scene_module.run_scene = original
    return seen[0] if seen else None


def typed(kwargs: dict) -> dict:
    return {name: (type(value), value) for name, value in kwargs.items()}


def test_the_table_is_what_typer_makes_of_run():
    assert json.loads(TABLE.read_text()) == describe_run()
    assert TABLE.read_text() == run_args_json(), "run `python -m morsec.cli.run_args > morsec/cli/run_args.json`"


@pytest.mark.parametrize("args", [
    ["build/scene", "--time-strategy", "fixed_step", "--port-base", "0", "--service-port", "0", "--duration", "0.5"],
    ["scene.yaml"],
    ["--duration=2", "scene.yaml", "-o", "out", "--view", "web", "--foxglove", "--seed", "3", "--bind", "0.0.0.0"],
    ["sim", "--record", "r.mcap", "--record-services", "--wait-for-client", "--name", "node1", "--time-scale", "1e-1"],
    ["scene.yaml", "--output-dir", "logs", "--view-port", "9000", "--foxglove-port", "0", "--node", "n"],
])
def test_usual_command_lines_are_read_as_typer_reads_them(args):
    ours = parse_run_args(args)
    assert ours is not None
    assert typed(ours) == typed(typer_reads(args))


@pytest.mark.parametrize("args", [
    ["--help"], ["scene.yaml", "--help"], [], ["a", "b"], ["scene.yaml", "--bogus", "1"], ["scene.yaml", "--"],
    ["scene.yaml", "--seed", "1", "--seed", "2"], ["scene.yaml", "--foxglove=yes"], ["scene.yaml", "-oout"],
    ["scene.yaml", "--duration", "abc"], ["scene.yaml", "--view", "WEB"], ["scene.yaml", "--duration"],
])
def test_anything_else_is_left_to_typer(args):
    assert parse_run_args(args) is None


def command_line(scene: str, options: list[tuple[str, str, bool]]) -> list[str]:
    """SCENE and options: each `--opt value` or `--opt=value` (a flag alone), the scene among them."""
    args = [token for opt, value, joined in options
            for token in ([opt] if opt in FLAGS else [f"{opt}={value}"] if joined else [opt, value])]
    return [*args[:len(args) // 2], scene, *args[len(args) // 2:]]


ANY_TOKENS = st.lists(st.one_of(st.sampled_from(OPTIONS + ["--help", "-x", "--bogus"]), st.sampled_from(VALUES),
                                st.builds(lambda o, v: f"{o}={v}", st.sampled_from(OPTIONS), st.sampled_from(VALUES))),
                      max_size=6)
COMMAND_LINES = st.builds(command_line, st.sampled_from(VALUES),
                          st.lists(st.tuples(st.sampled_from(OPTIONS), st.sampled_from(VALUES), st.booleans()),
                                   max_size=5))


@settings(max_examples=600, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(ANY_TOKENS, COMMAND_LINES))
def test_whatever_is_read_typer_reads_the_same(args):
    ours = parse_run_args(args)
    if ours is not None:
        theirs = typer_reads(args)
        assert theirs is not None, f"typer refuses {args}"
        assert typed(ours) == typed(theirs)


def test_a_mistake_gets_typers_message(tmp_path):
    env = dict(os.environ, PYTHONPATH=str(REPO))
    result = subprocess.run([sys.executable, "-m", "morsec", "run", "build/x", "--duration", "abc"],
                            capture_output=True, text=True, env=env, cwd=tmp_path, timeout=60)
    assert result.returncode == 2
    assert "--duration" in result.stderr and "valid number" in result.stderr
    result = subprocess.run([sys.executable, "-m", "morsec", "run", "--help"], capture_output=True, text=True,
                            env=env, cwd=tmp_path, timeout=60)
    assert result.returncode == 0 and "--time-strategy" in result.stdout


def test_an_error_of_a_run_read_without_typer_is_one_line_and_exit_code_2(tmp_path):
    env = dict(os.environ, PYTHONPATH=str(REPO))
    result = subprocess.run([sys.executable, "-m", "morsec", "run", "nowhere", "--seed", "-1"],
                            capture_output=True, text=True, env=env, cwd=tmp_path, timeout=60)
    assert result.returncode == 2
    assert result.stderr == "error: --seed must be 0 or more, got -1\n"
