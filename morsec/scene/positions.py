"""Read YAML and TOML into plain data plus a map from each key path to its (line, column) in the file.

Paths are tuples of keys and list indices, e.g. ('robots', 0, 'components', 1, 'type').
`keys[path]` is where the key itself is written, `values[path]` where its value starts.
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from typing import Any

import yaml

from morsec.errors import SceneError

Path = tuple
Position = tuple[int, int]


@dataclass
class SourceMap:
    file: str
    keys: dict[Path, Position] = field(default_factory=dict)
    values: dict[Path, Position] = field(default_factory=dict)

    def find(self, path: Path, *, key: bool = False) -> Position | None:
        """The position of `path`, or of its nearest ancestor that has one."""
        path = tuple(path)
        while True:
            table = (self.keys, self.values) if key else (self.values, self.keys)
            for t in table:
                if path in t:
                    return t[path]
            if not path:
                return None
            path = path[:-1]


# ---------------------------------------------------------------- YAML

def parse_yaml(text: str, file: str) -> tuple[Any, SourceMap]:
    smap = SourceMap(file)
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as err:
        mark = getattr(err, "problem_mark", None) or getattr(err, "context_mark", None)
        problem = getattr(err, "problem", None) or str(err).splitlines()[0]
        line, col = (mark.line + 1, mark.column + 1) if mark else (None, None)
        raise SceneError(f"YAML syntax error: {problem}", file, line, col) from None
    if node is None:
        return {}, smap
    constructor = yaml.SafeLoader("")
    return _yaml_node(node, (), smap, constructor), smap


def _yaml_node(node: yaml.Node, path: Path, smap: SourceMap, constructor: yaml.SafeLoader) -> Any:
    smap.values.setdefault(path, (node.start_mark.line + 1, node.start_mark.column + 1))
    if isinstance(node, yaml.MappingNode):
        out: dict[Any, Any] = {}
        for key_node, value_node in node.value:
            key = constructor.construct_object(key_node, deep=True)
            if isinstance(key, (list, dict)):
                raise SceneError("a mapping key must be a plain word", smap.file,
                                 key_node.start_mark.line + 1, key_node.start_mark.column + 1)
            if key in out:
                raise SceneError(f"duplicate key {key!r}", smap.file,
                                 key_node.start_mark.line + 1, key_node.start_mark.column + 1)
            child = path + (key,)
            smap.keys[child] = (key_node.start_mark.line + 1, key_node.start_mark.column + 1)
            smap.values[child] = (value_node.start_mark.line + 1, value_node.start_mark.column + 1)
            out[key] = _yaml_node(value_node, child, smap, constructor)
        return out
    if isinstance(node, yaml.SequenceNode):
        return [_yaml_node(item, path + (i,), smap, constructor) for i, item in enumerate(node.value)]
    return constructor.construct_object(node, deep=True)


# ---------------------------------------------------------------- TOML

_TOML_ERROR_AT = re.compile(r"^(.*?)\s*\(at line (\d+), column (\d+)\)\s*$")


def parse_toml(text: str, file: str) -> tuple[Any, SourceMap]:
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        msg = str(err)
        m = _TOML_ERROR_AT.match(msg)
        if m:
            raise SceneError(f"TOML syntax error: {m.group(1)}", file, int(m.group(2)), int(m.group(3))) from None
        raise SceneError(f"TOML syntax error: {msg}", file) from None
    smap = SourceMap(file)
    try:
        _TomlLocator(text, smap).run()
    except Exception:  # positions are a courtesy: a file tomllib accepted must still load
        pass
    return data, smap


_TOKEN = re.compile(
    r'(?P<ws>[ \t]+)|(?P<comment>#[^\n]*)|(?P<nl>\r?\n)'
    r'|(?P<mstr>"""(?:\\.|[^\\])*?"""|\'\'\'.*?\'\'\')'
    r'|(?P<str>"(?:\\.|[^"\\\n])*"|\'[^\'\n]*\')'
    r'|(?P<punct>\[\[|\]\]|[\[\]{}=,.])'
    r'|(?P<word>[^\s\[\]{}=,#"\']+)',
    re.S,
)


class _TomlLocator:
    """A small TOML reader that only records where keys and values are; tomllib already checked the syntax."""

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

    def dotted_key(self, stop: set[str]) -> list[tuple[str, int, int]]:
        parts = []
        while self.peek()[1] not in stop and self.peek()[0] not in ("eof", "nl"):
            kind, text, line, col = self.take()
            if text == ".":
                continue
            if kind == "str":
                text = text[1:-1]
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
                table = self.resolve(parts, array=(text == "[["))
                continue
            self.key_value(table)

    def resolve(self, parts, array: bool) -> Path:
        path: Path = ()
        for n, (name, line, col) in enumerate(parts):
            path = path + (name,)
            last = n == len(parts) - 1
            if path in self.array_counts and not (last and array):
                path = path + (self.array_counts[path] - 1,)
        if array:
            index = self.array_counts.get(path, 0)
            self.array_counts[path] = index + 1
            self.smap.keys.setdefault(path, parts[-1][1:])
            path = path + (index,)
        self.smap.keys.setdefault(path, parts[-1][1:])
        self.smap.values.setdefault(path, parts[-1][1:])
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
        while self.peek()[0] == "nl":
            self.take()
        kind, text, line, col = self.peek()
        self.smap.values.setdefault(path, (line, col))
        if text == "{":
            self.take()
            while self.peek()[1] != "}" and self.peek()[0] != "eof":
                if self.peek()[1] == ",":
                    self.take()
                    continue
                self.key_value(path)
            self.take()
        elif text == "[":
            self.take()
            index = 0
            while True:
                while self.peek()[0] == "nl" or self.peek()[1] == ",":
                    self.take()
                if self.peek()[1] == "]" or self.peek()[0] == "eof":
                    self.take()
                    break
                self.value(path + (index,))
                index += 1
        else:
            self.take()
