"""No scene file can hang the compiler, crash it or make it write outside its build: alias bombs, deep
nesting, scalars PyYAML cannot construct, devices, text stream files that escape, names that are not
markup, builds killed half-way. Each bad file is one located error line (exit 2) within seconds; a fuzz of
the loader (hypothesis) finds no other outcome."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from runtime_helpers import wait_until

from morsec.app.project import build_scene
from morsec.component.catalogue import load_catalogue
from morsec.constants import MAX_SCENE_BYTES, MAX_SCENE_DEPTH, MAX_SCENE_VALUES
from morsec.errors import SceneError
from morsec.frontends import load_scene

ROOT = Path(__file__).resolve().parent.parent
TUTORIAL = ROOT / "scenes" / "tutorial.yaml"
FAST = 30.0  # s: "within seconds" on a loaded machine; the bombs ran for minutes


@pytest.fixture(autouse=True)
def _builtin_catalogue(monkeypatch):
    monkeypatch.delenv("MORSEC_COMPONENTS", raising=False)


@pytest.fixture(scope="module")
def catalogue():
    return load_catalogue(ROOT)


def morsec(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "MORSEC_COMPONENTS"}
    return subprocess.run([sys.executable, "-c", "from morsec.cli import main; main()", *args],
                          capture_output=True, text=True, cwd=cwd or ROOT, env=env, timeout=300)


def laughs(levels: int, width: int = 10, indent: str = "") -> str:
    """Billion laughs: each level a list of `width` aliases of the level below."""
    lines = [f"{indent}l0: &l0 [{', '.join(['lol'] * width)}]"]
    for n in range(1, levels):
        lines.append(f"{indent}l{n}: &l{n} [{', '.join([f'*l{n - 1}'] * width)}]")
    return "\n".join(lines) + "\n"


# name -> (file text, line, column, message regex)
BAD_FILES = {
    "billion_laughs.yaml": (
        "environment:\n  morse_only:\n" + laughs(9, indent="    "), None, None,
        rf"YAML error: the scene holds more than {MAX_SCENE_VALUES} values once its aliases are expanded"),
    "bomb_under_a_rejected_key.yaml": (
        "x: &a [_, _, _, _, _, _, _, _, _]\n" + "".join(
            f"x{n}: &{chr(98 + n)} [{', '.join([f'*{chr(97 + n)}'] * 9)}]\n" for n in range(8))
        + "robots: [{type: atrv, translte: *i}]\n", None, None,
        rf"YAML error: the scene holds more than {MAX_SCENE_VALUES} values once its aliases are expanded"),
    "recursive_alias.yaml": ("environment:\n  morse_only: &a {x: [*a]}\n", None, None,
                             rf"YAML error: mappings and lists nested deeper than {MAX_SCENE_DEPTH} levels "
                             r"\(through aliases\)"),
    "recursive_merge.yaml": ("environment:\n  morse_only: &a {<<: *a}\n", None, None,
                             rf"YAML error: mappings and lists nested deeper than {MAX_SCENE_DEPTH} levels "
                             r"\(through aliases\)"),
    "deep.yaml": ("robots: " + "[" * 500 + "]" * 500 + "\n", 1, 8 + MAX_SCENE_DEPTH,
                  rf"YAML error: mappings and lists nested deeper than {MAX_SCENE_DEPTH} levels"),
    "deep_morse_only.yaml": ("environment:\n  morse_only: " + "{a: " * 300 + "1" + "}" * 300 + "\n", 2, None,
                             rf"YAML error: mappings and lists nested deeper than {MAX_SCENE_DEPTH} levels"),
    "deep_arrays.toml": ("x = " + "[" * 500 + "]" * 500 + "\n", 1, 5 + MAX_SCENE_DEPTH,
                         rf"TOML error: arrays and tables nested deeper than {MAX_SCENE_DEPTH} levels"),
    "deep_tables.toml": ("x = " + "{a = " * 500 + "1" + "}" * 500 + "\n", 1, None,
                         rf"TOML error: arrays and tables nested deeper than {MAX_SCENE_DEPTH} levels"),
    "deep_keys.toml": ("[" + ".".join(["a"] * 500) + "]\n", 1, None,
                       rf"TOML error: keys nested deeper than {MAX_SCENE_DEPTH} levels"),
    "int_tag.yaml": ("robots:\n  - type: !!int abc\n", 2, 11,
                     r"YAML error: cannot read 'abc' as !!int: invalid literal for int\(\) .*"),
    "empty_float.yaml": ("robots:\n  - type: !!float\n", 2, 11, r"YAML error: cannot read '' as !!float: .*"),
    "bad_date.yaml": ("robots:\n  - type: 2001-13-40\n", 2, 11,
                      r"robots\[0\]\.type: unknown robot type '2001-13-40' .*"),
    "binary.yaml": ("robots:\n  - type: !!binary /w==\n", 2, 11,
                    r"YAML error: !!binary values have no place in a scene: use strings, numbers, booleans, "
                    r"lists and mappings"),
    "surrogate.yaml": ('robots:\n  - {type: atrv, name: "r\\ud800"}\n', 2, 24,
                       r"YAML error: 'r\\ud800' is not valid text \(a lone surrogate escape\)"),
    "set_key.yaml": ("robots:\n  ? !!set {a}\n  : 1\n", 2, 5, r"a mapping key must be a plain word"),
    "time_scale.yaml": ("environment:\n  time: {scale: 1.0e-300}\n", 2, 17,
                        r"environment\.time\.scale: must be at least 0\.001, got 1e-300"),
}

TEXT_FILE_ERROR = (r"robots\[0\]\.components\[0\]\.streams\[0\]\.file: a text stream's file must be a relative path "
                   r"inside the run's output folder \(not absolute, no '\.\.'\); choose the folder with morsec run "
                   r"--output-dir, got ")
BAD_TEXT_FILES = {
    "absolute": ("/tmp/escaped.txt", TEXT_FILE_ERROR + r"'/tmp/escaped\.txt'"),
    "dotdot": ("logs/../../escaped.txt", TEXT_FILE_ERROR + r"'logs/\.\./\.\./escaped\.txt'"),
    "nul": ("a\\0b", r".*file: a text stream's file cannot contain control characters, got 'a\\x00b'"),
    "folder": ("logs/", r".*file: a text stream's file must name a file inside the run's output folder, got 'logs/'"),
}


def text_stream_scene(file: str) -> str:
    return ('robots:\n  - type: atrv\n    components:\n'
            f'      - {{type: pose, streams: [{{middleware: text, file: "{file}"}}]}}\n')


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("name", sorted(BAD_FILES))
def test_bad_scene_file_is_one_located_error(tmp_path, catalogue, name):
    text, line, column, message = BAD_FILES[name]
    path = write(tmp_path, name, text)
    start = time.monotonic()
    with pytest.raises(SceneError) as info:
        load_scene(path, catalogue)
    assert time.monotonic() - start < FAST
    err = info.value
    assert err.file == str(path) and err.line is not None, str(err)
    assert (line is None or err.line == line) and (column is None or err.column == column), str(err)
    assert re.fullmatch(message, err.message), err.message


@pytest.mark.parametrize("case", sorted(BAD_TEXT_FILES))
def test_text_stream_file_must_stay_in_the_output_folder(tmp_path, catalogue, case):
    file, message = BAD_TEXT_FILES[case]
    path = write(tmp_path, "scene.yaml", text_stream_scene(file))
    with pytest.raises(SceneError) as info:
        load_scene(path, catalogue)
    assert (info.value.line, info.value.column) == (4, 57), str(info.value)
    assert re.fullmatch(message, info.value.message), info.value.message


def test_cli_check_and_build_refuse_the_bad_files(tmp_path):
    """One `morsec check` of every bad file: one error line each, exit 2, in seconds, no traceback; `morsec
    build` of a scene whose text stream escapes writes nothing."""
    paths = [write(tmp_path, name, text) for name, (text, *_) in sorted(BAD_FILES.items())]
    paths += [write(tmp_path, f"text_{case}.yaml", text_stream_scene(file))
              for case, (file, _) in sorted(BAD_TEXT_FILES.items())]
    start = time.monotonic()
    result = morsec("check", *map(str, paths))
    assert time.monotonic() - start < 4 * FAST
    assert result.returncode == 2 and result.stdout == "", result.stdout + result.stderr
    lines = result.stderr.splitlines()
    assert len(lines) == len(paths), result.stderr
    for path, line in zip(paths, lines):
        assert line.startswith(f"error: {path}:"), line

    before = sorted(tmp_path.iterdir())
    result = morsec("build", str(tmp_path / "text_absolute.yaml"), "-o", str(tmp_path / "out"))
    assert result.returncode == 2 and "output folder" in result.stderr and len(result.stderr.splitlines()) == 1
    assert sorted(tmp_path.iterdir()) == before
    assert not Path("/tmp/escaped.txt").exists()


def test_devices_and_huge_files_are_not_read_whole(tmp_path):
    (tmp_path / "zero.yaml").symlink_to("/dev/zero")
    start = time.monotonic()
    result = morsec("check", "/dev/zero", str(tmp_path / "zero.yaml"))
    assert time.monotonic() - start < FAST
    assert result.returncode == 2
    assert result.stderr.splitlines() == [
        "error: /dev/zero: unknown scene format ''; use .yaml, .yml, .toml or a builder script .py",
        f"error: {tmp_path / 'zero.yaml'}: larger than {MAX_SCENE_BYTES} bytes: not a scene file"]


def test_a_name_with_two_dashes_builds(tmp_path):
    """Names go into XML comments too, where '--' is not allowed: it comes out unchanged everywhere."""
    path = write(tmp_path, "dashes.yaml", "robots:\n  - {name: a--b, type: atrv, components: [{name: c--d, type: pose}]}\n")
    out = build_scene(path, tmp_path / "out")
    names = {body.get("name") for body in ET.parse(out / "scene.xml").getroot().iter("body")}
    assert {"a--b", "a--b.c--d"} <= names


def test_a_build_killed_while_writing_is_cleaned_up_by_the_next(tmp_path):
    out = tmp_path / "b"
    script = ("from pathlib import Path\nfrom morsec.compiler.build import write_build\n"
              f"write_build({{f'f{{i}}.txt': 'x' for i in range(20000)}}, Path({str(out)!r}))\n")
    child = subprocess.Popen([sys.executable, "-c", script])
    try:
        wait_until(lambda: [p for p in tmp_path.glob(".b.*") if next(p.iterdir(), None)], timeout=120,
                   interval=0.005, message="the build writing its files")
    finally:
        child.kill()
        child.wait()
    assert [p for p in tmp_path.glob(".b.*")] and not out.exists(), "the build finished before it was killed"
    running = tmp_path / f".b.partial-{os.getpid()}-running"  # a build of this process, still writing
    running.mkdir()
    build_scene(TUTORIAL, out)
    assert sorted(p.name for p in tmp_path.iterdir()) == [running.name, "b"]


# ---------------------------------------------------------------- fuzz: the loader never crashes

KEYS = ["environment", "robots", "objects", "zones", "name", "type", "translate", "rotate", "components",
        "streams", "middleware", "file", "time", "scale", "frequency", "morse_only", "properties", "size",
        "seed", "<<", "atrv", "pose", "box"]
TAGS = ["", "", "", "!!int ", "!!float ", "!!str ", "!!bool ", "!!null ", "!!binary ", "!!timestamp ",
        "!!set ", "!!omap ", "!!pairs ", "!!seq ", "!!map ", "!custom ", "!!python/none ", "!!merge "]
WORDS = ["atrv", "pose", "box", "socket", "text", "2001-13-40", "2001-12-14", "", "~", ".inf", "-.nan", "0x1F",
         "0o17", "1e400", "-", "1_000", "yes", "No", "12:30:00", "/w==", "a--b", "../x", "/etc/passwd", "=",
         "<<", "&", "*"]
QUOTED = ['"\\ud800"', '"\\0"', '"\\x85"', '"\\U0001F600"', "''", '"a\\tb"']


def yaml_values():
    word = st.one_of(st.sampled_from(WORDS), st.sampled_from(QUOTED),
                     st.text(st.characters(codec="utf-8", exclude_characters=",[]{}:#&*!|>'\"%@`\n\r"),
                             max_size=6),
                     st.floats(allow_nan=True, allow_infinity=True).map(repr),
                     st.integers(min_value=-10**30, max_value=10**30).map(str))
    scalar = st.tuples(st.sampled_from(TAGS), word).map("".join)
    return st.recursive(
        scalar,
        lambda inner: st.one_of(
            st.lists(inner, max_size=4).map(lambda items: "[" + ", ".join(items) + "]"),
            st.lists(st.tuples(st.sampled_from(KEYS), inner), max_size=4).map(
                lambda pairs: "{" + ", ".join(f"{k}: {v}" for k, v in pairs) + "}"),
            st.tuples(st.sampled_from(TAGS), inner).map("".join),
            inner.map(lambda v: f"&a {v}"),
            st.just("*a"),
        ),
        max_leaves=25)


def toml_values():
    scalar = st.one_of(st.sampled_from(['"atrv"', '"pose"', "1979-05-27T07:32:00Z", "1979-05-27", "07:32:00",
                                        "inf", "nan", "0x1F", "1e400", "true", '"a\\u0000b"', '"../x"']),
                       st.integers(min_value=-10**20, max_value=10**20).map(str),
                       st.floats(allow_nan=False, allow_infinity=False).map(repr))
    return st.recursive(
        scalar,
        lambda inner: st.one_of(
            st.lists(inner, max_size=4).map(lambda items: "[" + ", ".join(items) + "]"),
            st.lists(st.tuples(st.sampled_from(KEYS[:-3]), inner), max_size=4, unique_by=lambda p: p[0]).map(
                lambda pairs: "{" + ", ".join(f'"{k}" = {v}' for k, v in pairs) + "}"),
        ),
        max_leaves=25)


@pytest.fixture(scope="module")
def fuzz_folder():
    with tempfile.TemporaryDirectory() as folder:
        yield Path(folder)


def loads_or_scene_error(folder: Path, name: str, text: str, catalogue) -> None:
    path = folder / name
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    start = time.monotonic()
    try:
        load_scene(path, catalogue)
    except SceneError as err:
        assert err.file == str(path) and err.message.count("\n") <= 1, str(err)
    assert time.monotonic() - start < FAST, text


FUZZ = settings(max_examples=150, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


@FUZZ
@given(st.lists(st.tuples(st.sampled_from(KEYS[:4]), yaml_values()), min_size=1, max_size=4))
def test_fuzz_yaml_loader(fuzz_folder, catalogue, entries):
    text = "".join(f"{key}: {value}\n" for key, value in entries)
    loads_or_scene_error(fuzz_folder, "fuzz.yaml", text, catalogue)


@FUZZ
@given(st.lists(st.tuples(st.sampled_from(KEYS[:4]), toml_values()), min_size=1, max_size=4,
                unique_by=lambda entry: entry[0]))
def test_fuzz_toml_loader(fuzz_folder, catalogue, entries):
    text = "".join(f"{key} = {value}\n" for key, value in entries)
    loads_or_scene_error(fuzz_folder, "fuzz.toml", text, catalogue)
