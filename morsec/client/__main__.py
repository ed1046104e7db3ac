"""`python -m morsec.client SCRIPT [ARGS...]`: run a pymorse script unchanged on `morsec.client`.

In this process only, `import pymorse` (and `pymorse.pymorse`) gives `morsec.client`; pymorse itself,
installed or not, is neither imported nor changed. For scripts written for pymorse on Python 3.12+
(where pymorse cannot be imported) or to avoid pymorse 1.4's `close()` defect without patching."""

from __future__ import annotations

import runpy
import sys
from pathlib import Path

USAGE = "usage: python -m morsec.client SCRIPT [ARGS...]   (runs SCRIPT with `import pymorse` bound to morsec.client)"


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in ("-h", "--help"):
        print(USAGE, file=sys.stderr if not argv else sys.stdout)
        return 2 if not argv else 0
    script = Path(argv[0])
    if not script.is_file():
        print(f"{script}: no such file\n{USAGE}", file=sys.stderr)
        return 2
    import morsec.client as client

    sys.modules["pymorse"] = client
    sys.modules["pymorse.pymorse"] = client
    sys.argv = argv
    sys.path.insert(0, str(script.resolve().parent))
    runpy.run_path(str(script), run_name="__main__")
    return 0


if __name__ == "__main__":
    sys.exit(main())
