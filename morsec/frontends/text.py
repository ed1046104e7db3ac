"""The text front end: YAML and TOML scene files into plain data plus a SourceMap (line, column of every
key and value), and the suffix table of scene formats."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path as FilePath
from typing import Any

import yaml

from morsec.errors import SceneError, yaml_path
from morsec.scene.sourcemap import Path, Position, SourceMap
from morsec.scene.validate import describe_value

YAML_SUFFIXES = (".yaml", ".yml")
TOML_SUFFIXES = (".toml",)


def read_scene_file(path: FilePath) -> tuple[Any, SourceMap]:
    path = FilePath(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneError(f"{path}: no such scene file") from None
    except IsADirectoryError:
        raise SceneError(f"{path}: is a folder, not a scene file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise SceneError(f"{path}: cannot read: {err}") from None
    suffix = path.suffix.lower()
    if suffix in YAML_SUFFIXES:
        data, smap = parse_yaml(text, str(path))
    elif suffix in TOML_SUFFIXES:
        data, smap = parse_toml(text, str(path))
    else:
        raise SceneError(f"{path}: unknown scene format {suffix!r}; use .yaml, .yml, .toml or a builder script .py")
    if not isinstance(data, dict):
        raise SceneError(f"a scene must be a mapping with environment, robots, objects and zones, got "
                         f"{describe_value(data)}", str(path), 1, 1)
    return data, smap


# ---------------------------------------------------------------- YAML

_MERGE_TAG = "tag:yaml.org,2002:merge"


def parse_yaml(text: str, file: str) -> tuple[Any, SourceMap]:
    smap = SourceMap(file)
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as err:
        raise _yaml_error(err, file, "YAML syntax error") from None
    if node is None:
        return {}, smap
    constructor = yaml.SafeLoader("")
    try:
        return _yaml_node(node, (), smap, constructor), smap
    except yaml.YAMLError as err:  # a scalar that cannot be constructed: unknown tag, bad timestamp ...
        raise _yaml_error(err, file, "YAML error") from None


def _yaml_error(err: yaml.YAMLError, file: str, what: str) -> SceneError:
    mark = getattr(err, "problem_mark", None) or getattr(err, "context_mark", None)
    problem = getattr(err, "problem", None) or str(err).splitlines()[0]
    context = getattr(err, "context", None)
    if context and not context.startswith("while") and problem.startswith("but "):
        problem = f"{context}, {problem}"  # "expected a single document in the stream, but found another document"
    line, col = (mark.line + 1, mark.column + 1) if mark else (None, None)
    start = getattr(err, "context_mark", None)
    elsewhere = start is not None and (start.line + 1, start.column + 1) != (line, col)
    if context and context.startswith("while") and elsewhere:
        opened = re.sub(r"^while (parsing|scanning) ", "", context)
        problem = f"{problem} ({opened} started at line {start.line + 1}, column {start.column + 1})"
    return SceneError(f"{what}: {problem}", file, line, col)


def _at(node: yaml.Node) -> Position:
    return node.start_mark.line + 1, node.start_mark.column + 1


def _mapping_pairs(node: yaml.MappingNode, smap: SourceMap) -> tuple[list, list]:
    """(explicit pairs, pairs merged in with `<<: *anchor`); explicit keys win, earlier merges win."""
    explicit, merged = [], []
    for key_node, value_node in node.value:
        if key_node.tag != _MERGE_TAG:
            explicit.append((key_node, value_node))
            continue
        sources = value_node.value if isinstance(value_node, yaml.SequenceNode) else [value_node]
        for source in sources:
            if not isinstance(source, yaml.MappingNode):
                raise SceneError("YAML error: '<<' merges mappings only (<<: *anchor or <<: [*a, *b])",
                                 smap.file, *_at(source))
            inner_explicit, inner_merged = _mapping_pairs(source, smap)
            merged.extend(inner_explicit + inner_merged)
    return explicit, merged


def _yaml_node(node: yaml.Node, path: Path, smap: SourceMap, constructor: yaml.SafeLoader) -> Any:
    smap.values.setdefault(path, _at(node))
    if isinstance(node, yaml.MappingNode):
        out: dict[Any, Any] = {}
        explicit, merged = _mapping_pairs(node, smap)
        for key_node, value_node in explicit + merged:
            key = constructor.construct_object(key_node, deep=True)
            if isinstance(key, (list, dict)):
                raise SceneError("a mapping key must be a plain word", smap.file, *_at(key_node))
            if key in out:
                if any(key_node is k for k, _ in merged):
                    continue  # merged keys never override what is written
                where = yaml_path(path + (key,))
                raise SceneError(f"{where}: duplicate key {key!r}: each key may appear once in a mapping",
                                 smap.file, *_at(key_node))
            child = path + (key,)
            smap.keys[child] = _at(key_node)
            smap.values[child] = _at(value_node)
            out[key] = _yaml_node(value_node, child, smap, constructor)
        return out
    if isinstance(node, yaml.SequenceNode):
        return [_yaml_node(item, path + (i,), smap, constructor) for i, item in enumerate(node.value)]
    return constructor.construct_object(node, deep=True)


# ---------------------------------------------------------------- TOML

_TOML_ERROR_AT = re.compile(r"^(.*?)\s*\(at line (\d+), column (\d+)\)\s*$")
_TOML_ERROR_AT_END = re.compile(r"^(.*?)\s*\(at end of document\)\s*$")
_TOML_HINTS = {
    "Cannot overwrite a value": "a key is written twice",
    "Unclosed array": "a '[' has no matching ']'",
    "Unterminated string": "a string has no closing quote",
    "Invalid value": "strings need quotes; numbers, true, false, inf and nan do not",
}


def parse_toml(text: str, file: str) -> tuple[Any, SourceMap]:
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise _toml_error(str(err), text, file) from None
    smap = SourceMap(file)
    try:
        _TomlLocator(text, smap).run()
    except Exception:  # positions are a courtesy: a file tomllib accepted must still load
        pass
    return data, smap


def _toml_error(msg: str, text: str, file: str) -> SceneError:
    line = col = None
    m = _TOML_ERROR_AT.match(msg)
    if m:
        msg, line, col = m.group(1), int(m.group(2)), int(m.group(3))
    else:
        m = _TOML_ERROR_AT_END.match(msg)
        if m:
            lines = text.split("\n")
            msg, line, col = m.group(1), len(lines), len(lines[-1]) + 1
    hint = _TOML_HINTS.get(msg)
    return SceneError(f"TOML syntax error: {msg}" + (f" ({hint})" if hint else ""), file, line, col)


_TOKEN = re.compile(
    r'(?P<ws>[ \t]+)|(?P<comment>#[^\n]*)|(?P<nl>\r?\n)'
    r'|(?P<mstr>"""(?:\\.|[^\\])*?"""+|\'\'\'.*?\'\'\'+)'
    r'|(?P<str>"(?:\\.|[^"\\\n])*"|\'[^\'\n]*\')'
    r'|(?P<punct>\[\[|\]\]|[\[\]{}=,.])'
    r'|(?P<word>[^\s\[\]{}=,#"\']+)',
    re.S,
)


class _TomlLocator:
    """A small TOML reader that only records where keys and values are; tomllib already checked the syntax.

    Handles tables, arrays of tables (nested too), dotted keys, inline tables and (multi-line) arrays.
    """

    def __init__(self, text: str, smap: SourceMap):
        self.tokens: list[tuple[str, str, int, int]] = []
        line, line_start = 1, 0
        for m in _TOKEN.finditer(text):
            kind = m.lastgroup
            col = m.start() - line_start + 1
            if kind not in ("ws", "comment"):
                self.tokens.append((kind, m.group(), line, col))
            newlines = m.group().count("\n")
            if newlines:
                line += newlines
                line_start = m.start() + m.group().rfind("\n") + 1
        self.i = 0
        self.smap = smap
        self.array_counts: dict[Path, int] = {}

    def peek(self):
        return self.tokens[self.i] if self.i < len(self.tokens) else ("eof", "", 0, 0)

    def take(self):
        tok = self.peek()
        self.i += 1
        return tok

    def skip_newlines(self):
        while self.peek()[0] == "nl":
            self.i += 1

    def skip_to(self, stops: set[str], newline: bool) -> None:
        """Skip what this reader does not understand (e.g. a date with a space) up to the next separator."""
        while True:
            kind, text, _, _ = self.peek()
            if kind == "eof" or text in stops or (newline and kind == "nl"):
                return
            self.i += 1

    def dotted_key(self, stop: set[str]) -> list[tuple[str, int, int]]:
        parts = []
        while self.peek()[1] not in stop and self.peek()[0] not in ("eof", "nl"):
            kind, text, line, col = self.take()
            if text == ".":
                continue
            if kind == "str":
                parts.append((_unquote(text), line, col))
            elif kind == "word":  # a bare dotted key is one word: robots.components
                offset = 0
                for piece in text.split("."):
                    if piece:
                        parts.append((piece, line, col + offset))
                    offset += len(piece) + 1
            else:
                parts.append((text, line, col))
        return parts

    def run(self):
        table: Path = ()
        while self.peek()[0] != "eof":
            self.skip_newlines()
            kind, text, line, col = self.peek()
            if kind == "eof":
                break
            if text in ("[[", "["):
                self.take()
                parts = self.dotted_key({"]]", "]"})
                self.take()
                table = self.resolve(parts, array=(text == "[["), at=(line, col))
                self.skip_to(set(), newline=True)
                continue
            self.key_value(table)
            self.skip_to(set(), newline=True)

    def resolve(self, parts, array: bool, at: Position) -> Path:
        """The data path of a [table] or [[array.of.tables]] header; arrays of tables extend the last entry."""
        path: Path = ()
        for n, (name, line, col) in enumerate(parts):
            path = path + (name,)
            self.smap.keys.setdefault(path, (line, col))
            last = n == len(parts) - 1
            if path in self.array_counts and not (last and array):
                path = path + (self.array_counts[path] - 1,)
        if array:
            index = self.array_counts.get(path, 0)
            self.array_counts[path] = index + 1
            self.smap.values.setdefault(path, at)
            path = path + (index,)
        self.smap.keys.setdefault(path, at)
        self.smap.values.setdefault(path, at)
        return path

    def key_value(self, table: Path):
        parts = self.dotted_key({"="})
        self.take()  # '='
        path = table
        for name, line, col in parts:
            path = path + (name,)
            self.smap.keys.setdefault(path, (line, col))
        self.value(path)

    def value(self, path: Path):
        self.skip_newlines()
        kind, text, line, col = self.peek()
        self.smap.values.setdefault(path, (line, col))
        if text == "{":
            self.take()
            while self.peek()[1] != "}" and self.peek()[0] != "eof":
                if self.peek()[1] == "," or self.peek()[0] == "nl":
                    self.take()
                    continue
                self.key_value(path)
                self.skip_to({",", "}"}, newline=False)
            self.take()
        elif text in ("[", "[["):
            if text == "[[":  # `[[1, 2], [3]]`: open the outer array, leave '[' for the first item
                self.tokens[self.i] = ("punct", "[", line, col + 1)
            else:
                self.take()
            index = 0
            while True:
                while self.peek()[0] == "nl" or self.peek()[1] == ",":
                    self.take()
                if self.peek()[1] in ("]", "]]") or self.peek()[0] == "eof":
                    self._close_bracket()
                    break
                self.value(path + (index,))
                self.skip_to({",", "]", "]]"}, newline=False)
                index += 1
        else:
            self.take()

    def _close_bracket(self):
        kind, text, line, col = self.peek()
        if text == "]]":  # `[[1, 2]]` closes two arrays with one token: leave one ']' for the outer array
            self.tokens[self.i] = ("punct", "]", line, col + 1)
        else:
            self.take()


def _unquote(text: str) -> str:
    if text.startswith('"'):
        try:
            return tomllib.loads(f"k = {text}")["k"]
        except tomllib.TOMLDecodeError:
            return text[1:-1]
    return text[1:-1]
