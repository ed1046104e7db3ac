"""Where each part of a scene came from: a map from key paths to (line, column) in the scene file.

Paths are tuples of keys and list indices, e.g. ('robots', 0, 'components', 1, 'type').
`keys[path]` is where the key itself is written, `values[path]` where its value starts.
Lines and columns count from 1. Front ends fill it; the IR's errors read it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

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
