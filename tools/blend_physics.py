"""Print the game-engine physics settings MORSE's .blend files give their objects (mass, Damping, Rotation
Damping, physics type, collision bounds, material friction), read without Blender.

    apt-get download morse-simulator-data && dpkg-deb -x morse-simulator-data_*.deb morse-data
    python tools/blend_physics.py morse-data/usr/share/morse/data/robots/morsy.blend

A .blend file is a header, then blocks (code, size, address, struct index, count, data); the DNA1 block
describes every struct (Blender's SDNA), so a field is found by name whatever Blender version wrote the file.
Gzipped files (Blender's "compress") are read too. Where a robot's numbers in morsec come from a .blend,
its component says so (components/robots/morsy: 15 kg, Damping 0.493, Rotation Damping 0.658).
"""

from __future__ import annotations

import argparse
import gzip
import re
import struct
import sys
from pathlib import Path

PHYSICS_TYPES = {0: "no collision", 1: "static", 2: "dynamic", 3: "rigid body", 4: "soft body", 5: "occluder",
                 6: "sensor", 7: "navmesh", 8: "character"}
BOUNDS = {0: "box", 1: "sphere", 2: "cylinder", 3: "cone", 4: "triangle mesh", 5: "convex hull", 7: "capsule"}
OBJECT_FIELDS = ("mass", "damping", "rdamping", "body_type", "collision_boundtype", "margin", "gameflag")
SCALARS = {"float": "f", "double": "d", "int": "i", "short": "h", "char": "b", "uchar": "B", "ushort": "H"}


class Blend:
    def __init__(self, path: Path):
        raw = path.read_bytes()
        if raw[:2] == b"\x1f\x8b":
            raw = gzip.decompress(raw)
        if raw[:7] != b"BLENDER":
            raise ValueError(f"{path}: not a .blend file")
        self.raw = raw
        self.psize = 8 if raw[7:8] == b"-" else 4
        self.order = "<" if raw[8:9] == b"v" else ">"
        self.blocks = []  # (code, size, struct index, data offset)
        offset = 12
        while offset < len(raw):
            code = raw[offset:offset + 4]
            size, = struct.unpack(self.order + "i", raw[offset + 4:offset + 8])
            head = offset + 8 + self.psize
            sdna, _count = struct.unpack(self.order + "ii", raw[head:head + 8])
            self.blocks.append((code, size, sdna, head + 8))
            offset = head + 8 + size
            if code == b"ENDB":
                break
        self._read_dna()

    def _read_dna(self) -> None:
        _, size, _, offset = next(b for b in self.blocks if b[0] == b"DNA1")
        dna = self.raw[offset:offset + size]
        pos = 8  # "SDNA" "NAME"

        def count() -> int:
            nonlocal pos
            value, = struct.unpack(self.order + "i", dna[pos:pos + 4])
            pos += 4
            return value

        def strings(n: int) -> list[str]:
            nonlocal pos
            out = []
            for _ in range(n):
                end = dna.index(b"\0", pos)
                out.append(dna[pos:end].decode("latin1"))
                pos = end + 1
            pos = (pos + 3) & ~3
            return out

        names = strings(count())
        pos += 4  # "TYPE"
        types = strings(count())
        pos += 4  # "TLEN"
        lengths = struct.unpack(self.order + f"{len(types)}h", dna[pos:pos + 2 * len(types)])
        pos = (pos + 2 * len(types) + 3) & ~3
        pos += 4  # "STRC"
        self.structs = []  # (type name, {field name: (type, offset, pointer, items)})
        for _ in range(count()):
            type_index, nfields = struct.unpack(self.order + "hh", dna[pos:pos + 4])
            pos += 4
            fields, at = {}, 0
            for _ in range(nfields):
                ftype, fname = struct.unpack(self.order + "hh", dna[pos:pos + 4])
                pos += 4
                name = names[fname]
                items = 1
                for dim in re.findall(r"\[(\d+)\]", name):
                    items *= int(dim)
                pointer = name.startswith("*") or name.startswith("(*")
                fields[re.sub(r"[*()]|\[.*", "", name)] = (types[ftype], at, pointer, items)
                at += (self.psize if pointer else lengths[ftype]) * items
            self.structs.append((types[type_index], fields))
        self.struct_by_name = {name: fields for name, fields in self.structs}

    def value(self, sdna: int, offset: int, path: str):
        fields = self.structs[sdna][1]
        *outer, last = path.split(".")
        for name in outer:
            ftype, at, _, _ = fields[name]
            offset += at
            fields = self.struct_by_name[ftype]
        ftype, at, pointer, items = fields[last]
        data = self.raw[offset + at:]
        if pointer:
            return int.from_bytes(data[:self.psize], "little" if self.order == "<" else "big")
        if ftype == "char" and items > 1:
            return data[:items].split(b"\0")[0].decode("latin1")
        values = struct.unpack(self.order + SCALARS[ftype] * items, data[:struct.calcsize(SCALARS[ftype]) * items])
        return values[0] if items == 1 else values

    def of_code(self, code: bytes):
        return [b for b in self.blocks if b[0] == code]


def report(path: Path) -> None:
    blend = Blend(path)
    print(path)
    for _, _, sdna, offset in blend.of_code(b"OB\0\0"):
        name = blend.value(sdna, offset, "id.name")[2:]
        v = {f: blend.value(sdna, offset, f) for f in OBJECT_FIELDS}
        physics = PHYSICS_TYPES.get(v["body_type"], v["body_type"])
        bounds = BOUNDS.get(v["collision_boundtype"], v["collision_boundtype"])
        print(f"  object {name}: {physics}, mass {v['mass']:.4g} kg, damping {v['damping']:.4g}, rotation damping "
              f"{v['rdamping']:.4g}, bounds {bounds}, margin {v['margin']:.4g}, gameflag {v['gameflag']:#x}")
    for _, _, sdna, offset in blend.of_code(b"MA\0\0"):
        print(f"  material {blend.value(sdna, offset, 'id.name')[2:]}: friction "
              f"{blend.value(sdna, offset, 'friction'):.4g}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+", type=Path)
    args = parser.parse_args(argv)
    for path in args.files:
        try:
            report(path)
        except (OSError, ValueError) as err:
            print(f"error: {err}", file=sys.stderr)
            return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
