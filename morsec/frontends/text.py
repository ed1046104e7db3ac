"""The text front end: YAML and TOML scene files into plain data plus a SourceMap (line, column of every
key and value), and the suffix table of scene formats."""

from __future__ import annotations

import datetime
import re
import tomllib
from pathlib import Path as FilePath
from typing import Any

import yaml

from morsec.constants import MAX_SCENE_BYTES, MAX_SCENE_DEPTH, MAX_SCENE_VALUES
from morsec.errors import SceneError, yaml_path
from morsec.scene.sourcemap import Path, Position, SourceMap
from morsec.scene.validate import describe_value

YAML_SUFFIXES = (".yaml", ".yml")
TOML_SUFFIXES = (".toml",)


SCENE_MAPPING = "a scene must be a mapping with environment, robots, objects and zones"


def read_scene_file(path: FilePath) -> tuple[Any, SourceMap]:
    return read_data_file(path, "scene", SCENE_MAPPING)


def read_data_file(path: FilePath, kind: str, mapping: str) -> tuple[dict, SourceMap]:
    """A YAML or TOML file of `kind` ("scene", "sweep": the word its errors use) as plain data and the position
    of every key and value; a file that is not a mapping is refused with `mapping`, the sentence saying what
    it should be."""
    path = FilePath(path)
    suffix = path.suffix.lower()
    if suffix not in YAML_SUFFIXES + TOML_SUFFIXES:
        if path.is_dir():
            raise SceneError(f"{path}: is a folder, not a {kind} file")
        extra = " or a builder script .py" if kind == "scene" else ""
        raise SceneError(f"{path}: unknown {kind} format {suffix!r}; use .yaml, .yml, .toml{extra}")
    text = _read_text(path, kind)
    if suffix in YAML_SUFFIXES:
        data, smap = parse_yaml(text, str(path))
    else:
        data, smap = parse_toml(text, str(path))
    if not isinstance(data, dict):
        raise SceneError(f"{mapping}, got {describe_value(data)}", str(path), 1, 1)
    return data, smap


def _read_text(path: FilePath, kind: str) -> str:
    """The file's text, refused past MAX_SCENE_BYTES without reading further (a device, a runaway file)."""
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_SCENE_BYTES + 1)
    except FileNotFoundError:
        raise SceneError(f"{path}: no such {kind} file") from None
    except IsADirectoryError:
        raise SceneError(f"{path}: is a folder, not a {kind} file") from None
    except OSError as err:
        raise SceneError(f"{path}: cannot read: {err.strerror or err}") from None
    if len(data) > MAX_SCENE_BYTES:
        raise SceneError(f"{path}: larger than {MAX_SCENE_BYTES} bytes: not a {kind} file")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise SceneError(f"{path}: cannot read: not UTF-8 text ({err.reason} at byte {err.start})") from None
    return text.replace("\r\n", "\n").replace("\r", "\n")  # universal newlines, as text mode reads


# ---------------------------------------------------------------- YAML

_MERGE_TAG = "tag:yaml.org,2002:merge"
_TIMESTAMP_TAG = "tag:yaml.org,2002:timestamp"
_SCALARS = (str, bool, int, float, type(None))  # what a scene holds, with lists and mappings


def parse_yaml(text: str, file: str) -> tuple[Any, SourceMap]:
    smap = SourceMap(file)
    try:
        loader = _BoundedLoader(text, file)  # its reader checks the characters at once
        try:
            node = loader.get_single_node()
        finally:
            loader.dispose()
    except yaml.YAMLError as err:
        raise _yaml_error(err, file, "YAML syntax error") from None
    if node is None:
        return {}, smap
    try:
        return _YamlReader(smap).read(node, (), 0), smap
    except yaml.YAMLError as err:  # a scalar that cannot be constructed: unknown tag ...
        raise _yaml_error(err, file, "YAML error") from None


class _BoundedLoader(yaml.SafeLoader):
    """PyYAML's safe loader, refusing nodes nested deeper than MAX_SCENE_DEPTH: its composer recurses,
    and would run out of Python's stack first."""

    def __init__(self, text: str, file: str):
        super().__init__(text)
        self.file = file
        self.depth = 0

    def compose_node(self, parent, index):
        self.depth += 1
        try:
            if self.depth > MAX_SCENE_DEPTH:
                mark = self.peek_event().start_mark
                raise SceneError(f"YAML error: mappings and lists nested deeper than {MAX_SCENE_DEPTH} levels",
                                 self.file, mark.line + 1, mark.column + 1)
            return super().compose_node(parent, index)
        finally:
            self.depth -= 1


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


class _YamlReader:
    """Composed YAML nodes -> plain data (str, bool, int, float, None, lists, dicts), recording positions.

    Aliases and merge keys are followed, within bounds: at most MAX_SCENE_VALUES values once expanded
    (an alias bomb's few lines stand for billions) and MAX_SCENE_DEPTH levels (an alias may refer to its
    own ancestor)."""

    def __init__(self, smap: SourceMap):
        self.smap = smap
        self.constructor = yaml.SafeLoader("")
        self.values = 0

    def error(self, message: str, node: yaml.Node) -> SceneError:
        return SceneError(f"YAML error: {message}", self.smap.file, *_at(node))

    def count(self, node: yaml.Node, n: int = 1) -> None:
        self.values += n
        if self.values > MAX_SCENE_VALUES:
            raise self.error(f"the scene holds more than {MAX_SCENE_VALUES} values once its aliases are expanded",
                             node)

    def deeper(self, node: yaml.Node, depth: int) -> int:
        if depth >= MAX_SCENE_DEPTH:
            raise self.error(f"mappings and lists nested deeper than {MAX_SCENE_DEPTH} levels (through aliases)",
                             node)
        return depth + 1

    def read(self, node: yaml.Node, path: Path, depth: int) -> Any:
        self.count(node)
        self.smap.values.setdefault(path, _at(node))
        if isinstance(node, yaml.MappingNode):
            return self.mapping(node, path, self.deeper(node, depth))
        if isinstance(node, yaml.SequenceNode):
            inner = self.deeper(node, depth)
            return [self.read(item, path + (i,), inner) for i, item in enumerate(node.value)]
        return self.scalar(node)

    def mapping(self, node: yaml.MappingNode, path: Path, depth: int) -> dict:
        out: dict[Any, Any] = {}
        explicit, merged = self.pairs(node, depth)
        merged_keys = {id(k) for k, _ in merged}
        for key_node, value_node in explicit + merged:
            if not isinstance(key_node, yaml.ScalarNode):
                raise SceneError("a mapping key must be a plain word", self.smap.file, *_at(key_node))
            key = self.scalar(key_node)
            if key in out:
                if id(key_node) in merged_keys:
                    continue  # merged keys never override what is written
                where = yaml_path(path + (key,))
                raise SceneError(f"{where}: duplicate key {key!r}: each key may appear once in a mapping",
                                 self.smap.file, *_at(key_node))
            child = path + (key,)
            self.smap.keys[child] = _at(key_node)
            self.smap.values[child] = _at(value_node)
            out[key] = self.read(value_node, child, depth)
        return out

    def pairs(self, node: yaml.MappingNode, depth: int) -> tuple[list, list]:
        """(explicit pairs, pairs merged in with `<<: *anchor`); explicit keys win, earlier merges win."""
        explicit, merged = [], []
        for key_node, value_node in node.value:
            if key_node.tag != _MERGE_TAG:
                explicit.append((key_node, value_node))
                continue
            sources = value_node.value if isinstance(value_node, yaml.SequenceNode) else [value_node]
            for source in sources:
                if not isinstance(source, yaml.MappingNode):
                    raise self.error("'<<' merges mappings only (<<: *anchor or <<: [*a, *b])", source)
                inner_explicit, inner_merged = self.pairs(source, self.deeper(source, depth))
                self.count(source, len(inner_explicit) + len(inner_merged))
                merged.extend(inner_explicit + inner_merged)
        return explicit, merged

    def scalar(self, node: yaml.ScalarNode) -> Any:
        if node.tag == _TIMESTAMP_TAG:
            return node.value  # a date stays the text written (YAML would make a datetime of it)
        try:
            value = self.constructor.construct_object(node, deep=True)
        except yaml.YAMLError:
            raise
        except Exception as err:  # PyYAML's constructors fail in many ways: !!int abc, an empty !!float ...
            raise self.error(f"cannot read {_shorten(node.value)!r} as {_tag(node.tag)}: {err}", node) from None
        if not isinstance(value, _SCALARS):
            raise self.error(f"{_tag(node.tag)} values have no place in a scene: use strings, numbers, booleans, "
                             "lists and mappings", node)
        if isinstance(value, str):
            try:
                value.encode("utf-8")
            except UnicodeEncodeError:
                raise self.error(f"{_shorten(value)!r} is not valid text (a lone surrogate escape)", node) from None
        return value


def _tag(tag: str) -> str:
    return tag.replace("tag:yaml.org,2002:", "!!")


def _shorten(text: str, limit: int = 40) -> str:
    return text if len(text) <= limit else text[:limit - 3] + "..."


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
    tokens = _toml_tokens(text)
    _check_toml_nesting(tokens, file)  # tomllib recurses into arrays and inline tables
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise _toml_error(str(err), text, file) from None
    smap = SourceMap(file)
    try:
        _TomlLocator(tokens, smap).run()
    except Exception:  # positions are a courtesy: a file tomllib accepted must still load
        pass
    return _plain_toml(data, smap), smap


def _check_toml_nesting(tokens: list, file: str) -> None:
    depth = 0
    for kind, text, line, col in tokens:
        if kind != "punct":
            continue
        if text in ("[", "[[", "{"):
            depth += len(text) if text != "{" else 1
            if depth > MAX_SCENE_DEPTH:
                raise SceneError(f"TOML error: arrays and tables nested deeper than {MAX_SCENE_DEPTH} levels",
                                 file, line, col)
        elif text in ("]", "]]", "}"):
            depth = max(0, depth - (len(text) if text != "}" else 1))


def _plain_toml(data: dict, smap: SourceMap) -> dict:
    """Bound the depth (dotted keys and table headers nest too) and make dates and times the text
    written (tomllib's datetime objects have no place in a scene's plain data). Iterative."""
    stack = [(data, ())]
    while stack:
        node, path = stack.pop()
        if len(path) > MAX_SCENE_DEPTH:
            line, col = smap.find(path) or (None, None)
            raise SceneError(f"TOML error: keys nested deeper than {MAX_SCENE_DEPTH} levels", smap.file, line, col)
        items = node.items() if isinstance(node, dict) else enumerate(node)
        for key, value in list(items):
            if isinstance(value, (dict, list)):
                stack.append((value, path + (key,)))
            elif isinstance(value, (datetime.date, datetime.time)):  # datetime is a date
                node[key] = value.isoformat()
    return data


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


def _toml_tokens(text: str) -> list[tuple[str, str, int, int]]:
    """(kind, text, line, column) of every token but blanks and comments."""
    tokens = []
    line, line_start = 1, 0
    for m in _TOKEN.finditer(text):
        kind = m.lastgroup
        col = m.start() - line_start + 1
        if kind not in ("ws", "comment"):
            tokens.append((kind, m.group(), line, col))
        newlines = m.group().count("\n")
        if newlines:
            line += newlines
            line_start = m.start() + m.group().rfind("\n") + 1
    return tokens


class _TomlLocator:
    """A small TOML reader that only records where keys and values are; tomllib already checked the syntax.

    Handles tables, arrays of tables (nested too), dotted keys, inline tables and (multi-line) arrays.
    """

    def __init__(self, tokens: list[tuple[str, str, int, int]], smap: SourceMap):
        self.tokens = list(tokens)  # a copy: `value` and `_close_bracket` split tokens in place
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
