"""MORSE's middlewares that morsec refuses, each with why (one line) and what to use instead: a scene that
names one (`add_stream('yarp')`, `streams: [moos]` ...) is refused with that line rather than a list of the
middlewares morsec has. docs/coming-from-morse.md shows the same table (a test keeps them together)."""

from __future__ import annotations

from dataclasses import dataclass

DOCS = "docs/coming-from-morse.md#middlewares-morsec-refuses"


@dataclass(frozen=True)
class Refused:
    name: str  # as MORSE scripts name it
    reason: str
    instead: str


REFUSED = {r.name: r for r in (
    Refused("yarp", "YARP and its Python bindings are neither on PyPI nor in Debian, so morsec can neither install "
            "nor test them", "use ros (YARP reads and writes ROS topics) or socket (MORSE's protocol)"),
    Refused("moos", "MOOS (MOOSDB, pymoos) is neither on PyPI nor in Debian, so morsec can neither install nor "
            "test it", "use ros (through a MOOS-ROS bridge) or socket (MORSE's protocol)"),
    Refused("pocolibs", "pocolibs (GenoM 2's posters) comes only from LAAS's robotpkg, neither on PyPI nor in "
            "Debian", "use ros (GenoM 3 generates ROS components) or socket (MORSE's protocol)"),
    Refused("hla", "HLA needs an RTI (CERTI), neither on PyPI nor in Debian (MORSE used it to split one "
            "simulation across machines)",
            "use socket; to split one world across processes, configure_multinode(protocol='socket') "
            "(docs/multinode.md)"),
)}


def refusal(name: str) -> str | None:
    """The one line refusing MORSE's middleware `name`, or None if morsec does not refuse it."""
    refused = REFUSED.get(str(name).lower())
    if refused is None:
        return None
    return f"MORSE's {refused.name} middleware is not in morsec: {refused.reason}; {refused.instead} ({DOCS})"
