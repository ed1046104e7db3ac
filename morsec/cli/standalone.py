"""`python mysim.py`: a builder script run as plain Python hands its scene to the `morsec` command line."""

from __future__ import annotations

import sys

from morsec.cli import main as morsec_main
from morsec.errors import MorsecError
from morsec.frontends.builder.script import preload
from morsec.frontends.builder.session import Session


def morsec_args(argv: list[str], script: str) -> list[str]:
    """`python mysim.py -- run --fast` -> ['run', 'mysim.py', '--fast']; nothing after `--` -> build."""
    rest = argv[argv.index("--") + 1:] if "--" in argv else []
    if not rest or rest[0].startswith("-"):
        rest = ["build", *rest]
    return [rest[0], script, *rest[1:]]


def standalone_main(session: Session) -> None:
    """The script ran as plain Python: hand its recording to the `morsec` command line (exits)."""
    main = sys.modules.get("__main__")
    namespace = getattr(main, "__dict__", None)
    script = session.script
    if script is None:
        sys.stderr.write("error: cannot tell which script is running; use `morsec build SCRIPT`\n")
        raise SystemExit(2)
    try:
        session.end_of_script(namespace)
        preload(script, session.recording())
    except MorsecError as err:
        sys.stderr.write(f"error: {err}\n")
        raise SystemExit(err.exit_code) from None
    morsec_main(morsec_args(sys.argv[1:], str(script)), prog_name="morsec")
