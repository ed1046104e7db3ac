"""The wheel's first build hook (pyproject.toml): before mypyc compiles morsec/runtime/trim.py, C compilers are
told not to fuse a multiplication and an addition into one instruction. GCC does by default where the CPU has
one (aarch64; x86-64 with -march=native), clang too: the result is rounded once instead of twice, and the
compiled trim would no longer give the interpreter's floats to the bit (docs/architecture.md#compiled-module)."""

from __future__ import annotations

import os
import sys

from hatchling.builders.hooks.plugin.interface import BuildHookInterface

NO_FUSED_MULTIPLY_ADD = "-ffp-contract=off"  # GCC's and clang's spelling


class CompilerFlags(BuildHookInterface):
    PLUGIN_NAME = "custom"

    def initialize(self, version: str, build_data: dict) -> None:
        if sys.platform == "win32":  # MSVC does not read CFLAGS, and contracts only with /fp:fast
            return
        flags = os.environ.get("CFLAGS", "")
        if NO_FUSED_MULTIPLY_ADD not in flags.split():
            os.environ["CFLAGS"] = f"{flags} {NO_FUSED_MULTIPLY_ADD}".strip()
