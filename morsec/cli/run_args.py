"""`morsec run`'s command line read without typer: a start pays neither for importing typer nor for its
adapters (pydantic TypeAdapters built for each of run's parameters at every call), a tenth of a start.

The parameters are declared once, by morsec.cli.running.run for typer; `run_args.json` is what typer makes of
them (`describe_run`; tests/test_run_args.py keeps it fresh). A command line is read here only when every token
is plainly one typer reads the same way: the scene, known options with a value (`--opt value`, `--opt=value`),
flags. Anything else — `--help`, a mistake, `--`, an option given twice, a value that might mean something
else — returns None, and typer reads it (its usage, its errors). tests/test_run_args.py checks that whatever is
read here, typer reads to the same values.

    python -m morsec.cli.run_args > morsec/cli/run_args.json
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from typing import Any

TABLE = Path(__file__).with_name("run_args.json")
INT = re.compile(r"-?(0|[1-9][0-9]{0,17})")
FLOAT = re.compile(r"-?(0|[1-9][0-9]{0,17})(\.[0-9]{1,17})?([eE]-?[0-9]{1,2})?")
NUMBER_TYPES = ("int", "float")


def parse_run_args(args: list[str]) -> dict[str, Any] | None:
    """run_scene's keyword arguments from the command line after `run`, or None: typer is to read it."""
    if any(k.startswith("_") and k.endswith("_COMPLETE") for k in os.environ):  # shell completion: typer's
        return None
    table = json.loads(TABLE.read_text(encoding="utf-8"))
    params = table["parameters"]
    by_opt = {opt: name for name, p in params.items() for opt in (*p.get("opts", ()), *p.get("off", ()))}
    given: dict[str, Any] = {}
    positional: list[str] = []
    rest = list(args)
    while rest:
        token = rest.pop(0)
        if not token.startswith("-"):
            positional.append(token)
            continue
        opt, eq, value = token.partition("=")
        name = by_opt.get(opt)
        if name is None or name in given or (eq and not opt.startswith("--")):
            return None
        param = params[name]
        if param["type"] == "flag":
            if eq:
                return None
            given[name] = opt in param["opts"]
            continue
        if not eq:
            if not rest:
                return None
            value = rest.pop(0)
        converted = _value(param, value)
        if converted is None:
            return None
        given[name] = converted
    if len(positional) != len(table["arguments"]):
        return None
    for name, value in zip(table["arguments"], positional, strict=True):
        converted = _value(params[name], value)
        if converted is None:
            return None
        given[name] = converted
    return {name: given.get(name, p.get("default")) for name, p in params.items()}


def _value(param: dict, text: str) -> Any:
    """A value as typer converts it, or None when it might convert it otherwise (or refuse it)."""
    kind = param["type"]
    if not text or "\0" in text or (text.startswith("-") and kind not in NUMBER_TYPES):
        return None
    if kind == "int":
        return int(text) if INT.fullmatch(text) else None
    if kind == "float":
        return float(text) if FLOAT.fullmatch(text) else None
    if kind == "choice":
        return text if text in param["choices"] else None
    if kind == "str":
        return text
    if kind == "path":  # typer refuses a path that exists and cannot be read
        return Path(text) if not os.path.exists(text) or os.access(text, os.R_OK) else None
    raise ValueError(f"run_args.json: unknown type {kind!r}")


def describe_run() -> dict[str, Any]:
    """run_args.json: each parameter of `morsec run` as typer reads it (its options, type, default). A feature
    of typer this module does not mirror (a callback, an environment variable, bounds, ...) is refused."""
    import inspect
    import typing
    from types import NoneType, UnionType

    import typer.main

    from morsec.cli import running
    from morsec.cli.assemble import make_app

    command = typer.main.get_command(make_app("run")).commands["run"]  # type: ignore[attr-defined]
    hints = typing.get_type_hints(running.run, include_extras=True)
    defaults = {name: p.default for name, p in inspect.signature(running.run).parameters.items()}
    plain = {"argument": typer.Argument(), "option": typer.Option()}
    checked = ("callback", "envvar", "is_eager", "expose_value", "count", "prompt", "parser", "click_type", "min",
               "max", "clamp", "case_sensitive", "exists", "file_okay", "dir_okay", "writable", "readable",
               "resolve_path", "allow_dash", "path_type", "formats", "autocompletion")
    arguments: list[str] = []
    parameters: dict[str, Any] = {}
    for param in command.params:
        name = param.name
        info = hints[name].__metadata__[0]
        odd = [a for a in checked if getattr(info, a, None) != getattr(plain[param.param_type_name], a, None)]
        if odd or param.multiple or param.nargs != 1:
            raise ValueError(f"run's {name}: {odd or 'several values'} is not read by morsec.cli.run_args")
        annotation = typing.get_args(hints[name])[0]
        args = typing.get_args(annotation)
        if typing.get_origin(annotation) in (UnionType, typing.Union) and len(args) == 2 and args[1] is NoneType:
            annotation = args[0]
        entry: dict[str, Any]
        if annotation is bool:
            entry = {"type": "flag", "opts": list(param.opts), "off": list(param.secondary_opts)}
        elif typing.get_origin(annotation) is typing.Literal:
            entry = {"type": "choice", "choices": list(typing.get_args(annotation))}
        else:
            kinds = {Path: "path", int: "int", float: "float", str: "str"}
            if annotation not in kinds:
                raise ValueError(f"run's {name}: type {annotation} is not read by morsec.cli.run_args")
            entry = {"type": kinds[annotation]}
        if param.param_type_name == "argument":
            arguments.append(name)
        else:
            entry = {"opts": list(param.opts), **entry, "default": defaults[name]}
            json.dumps(entry["default"])  # a default JSON keeps as it is
        parameters[name] = entry
    return {"$comment": "generated by `python -m morsec.cli.run_args` from morsec.cli.running.run; do not edit",
            "arguments": arguments, "parameters": parameters}


def run_args_json() -> str:
    """run_args.json's text: a parameter a line."""
    table = describe_run()
    params = ",\n".join(f"  {json.dumps(name)}: {json.dumps(p)}" for name, p in table["parameters"].items())
    return (f'{{\n "$comment": {json.dumps(table["$comment"])},\n "arguments": {json.dumps(table["arguments"])},\n'
            f' "parameters": {{\n{params}\n }}\n}}\n')


if __name__ == "__main__":
    print(run_args_json(), end="")
