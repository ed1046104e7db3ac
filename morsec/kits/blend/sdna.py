"""The .blend container, read without Blender: a 12-byte header, then blocks (code, size, the address the
block had in Blender's memory, struct index, count, data) up to ENDB. The DNA1 block describes every struct
of the writing Blender (its SDNA: field names, types, sizes), so a field is found by name whatever version
wrote the file; pointers are the old addresses of other blocks. Gzipped files (Blender's "Compress") are read
too; zstd-compressed ones (Blender 3.0 and later) are refused with the reason."""

from __future__ import annotations

import gzip
import re
import struct
from dataclasses import dataclass
from pathlib import Path

import numpy as np

SCALARS = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I", "float": "f",
           "double": "d", "int64_t": "q", "uint64_t": "Q", "int8_t": "b", "uint8_t": "B", "int16_t": "h",
           "uint16_t": "H", "int32_t": "i", "uint32_t": "I", "long": "i", "ulong": "I"}
ZSTD_MAGIC = b"\x28\xb5\x2f\xfd"


class BlendFormatError(Exception):
    """The file is not a .blend this reader understands; the message says why, in one line."""


@dataclass(frozen=True)
class Field:
    type: str
    offset: int
    pointer: bool
    items: int  # array length (1 for a scalar); char[64] has 64
    shape: tuple[int, ...]  # array dimensions, () for a scalar


@dataclass(frozen=True)
class Block:
    code: bytes
    size: int
    address: int
    sdna: int
    count: int
    start: int  # offset of the data in the file's bytes


class BlendFile:
    """The blocks and the SDNA of one .blend file, and typed access to the structs they hold."""

    def __init__(self, path: Path):
        self.path = Path(path)
        try:
            raw = self.path.read_bytes()
        except OSError as err:
            raise BlendFormatError(f"cannot read it: {err.strerror or err}") from None
        if raw[:4] == ZSTD_MAGIC:
            raise BlendFormatError("it is compressed with zstd (Blender 3.0 or later): save it uncompressed "
                                   "(File > Save As, Compress off) to import it")
        if raw[:2] == b"\x1f\x8b":
            try:
                raw = gzip.decompress(raw)
            except (OSError, EOFError) as err:
                raise BlendFormatError(f"a gzip file that does not decompress: {err}") from None
        if raw[:7] != b"BLENDER":
            raise BlendFormatError("not a Blender file (it does not start with 'BLENDER')")
        if raw[7:8] not in (b"_", b"-") or raw[8:9] not in (b"v", b"V") or not raw[9:12].isdigit():
            raise BlendFormatError("a Blender file header this reader does not know (Blender 4.x or later?)")
        self.raw = raw
        self.psize = 8 if raw[7:8] == b"-" else 4
        self.order = "<" if raw[8:9] == b"v" else ">"
        self.version = int(raw[9:12])  # 261 for Blender 2.61
        self.blocks: list[Block] = []
        self.by_address: dict[int, Block] = {}
        self._read_blocks()
        self._read_dna()

    # ---- container

    def _read_blocks(self) -> None:
        raw, order, psize = self.raw, self.order, self.psize
        head = struct.Struct(order + "4si" + ("Q" if psize == 8 else "I") + "ii")
        offset = 12
        while offset + head.size <= len(raw):
            code, size, address, sdna, count = head.unpack_from(raw, offset)
            start = offset + head.size
            if size < 0 or start + size > len(raw):
                raise BlendFormatError(f"truncated or damaged: block {code!r} at byte {offset} runs past the end")
            block = Block(code, size, address, sdna, count, start)
            if code == b"ENDB":
                break
            self.blocks.append(block)
            if address:
                self.by_address[address] = block
            offset = start + size
        else:
            raise BlendFormatError("truncated: no ENDB block at its end")

    def _read_dna(self) -> None:
        found = [b for b in self.blocks if b.code == b"DNA1"]
        if not found:
            raise BlendFormatError("it has no DNA1 block (the description of its data)")
        dna = self.raw[found[0].start:found[0].start + found[0].size]
        order = self.order
        pos = 0

        def expect(tag: bytes) -> None:
            nonlocal pos
            pos = (pos + 3) & ~3
            if dna[pos:pos + 4] != tag:
                raise BlendFormatError(f"its DNA1 block lacks {tag.decode()} where expected")
            pos += 4

        def count() -> int:
            nonlocal pos
            value = struct.unpack_from(order + "i", dna, pos)[0]
            pos += 4
            return value

        def strings(n: int) -> list[str]:
            nonlocal pos
            out = []
            for _ in range(n):
                end = dna.index(b"\0", pos)
                out.append(dna[pos:end].decode("latin1"))
                pos = end + 1
            return out

        expect(b"SDNA")
        expect(b"NAME")
        names = strings(count())
        expect(b"TYPE")
        types = strings(count())
        expect(b"TLEN")
        lengths = struct.unpack_from(order + f"{len(types)}h", dna, pos)
        pos += 2 * len(types)
        expect(b"STRC")
        self.type_sizes = dict(zip(types, lengths))
        self.structs: list[tuple[str, dict[str, Field]]] = []
        for _ in range(count()):
            type_index, nfields = struct.unpack_from(order + "hh", dna, pos)
            pos += 4
            fields: dict[str, Field] = {}
            at = 0
            for _ in range(nfields):
                ftype, fname = struct.unpack_from(order + "hh", dna, pos)
                pos += 4
                name = names[fname]
                shape = tuple(int(d) for d in re.findall(r"\[(\d+)\]", name))
                items = int(np.prod(shape)) if shape else 1
                pointer = name.startswith("*") or name.startswith("(*")
                clean = re.sub(r"[*()]|\[.*", "", name)
                fields[clean] = Field(types[ftype], at, pointer, items, shape)
                at += (self.psize if pointer else lengths[ftype]) * items
            self.structs.append((types[type_index], fields))
        self.struct_index = {name: i for i, (name, _) in enumerate(self.structs)}

    # ---- typed access

    def of_code(self, code: bytes) -> list[Block]:
        return [b for b in self.blocks if b.code == code]

    def has_struct(self, name: str) -> bool:
        return name in self.struct_index

    def fields(self, struct_name: str) -> dict[str, Field]:
        return self.structs[self.struct_index[struct_name]][1]

    def at(self, block: Block, index: int = 0) -> Struct:
        """The `index`-th struct a block holds, as its SDNA describes it."""
        name, _ = self.structs[block.sdna]
        return Struct(self, name, block.start + index * self.type_sizes[name])

    def deref(self, address: int, struct_name: str | None = None) -> Struct | None:
        """The struct at an old address (None for a null pointer or an address no block starts at)."""
        block = self.by_address.get(address)
        if block is None:
            return None
        name = struct_name or self.structs[block.sdna][0]
        return Struct(self, name, block.start)

    def block_at(self, address: int) -> Block | None:
        return self.by_address.get(address)

    def pointers(self, address: int) -> list[int]:
        """An array of pointers (Material **mat ...): the block at `address` read as pointers."""
        block = self.by_address.get(address)
        if block is None:
            return []
        n = block.size // self.psize
        fmt = self.order + ("Q" if self.psize == 8 else "I") * n
        return list(struct.unpack_from(fmt, self.raw, block.start))

    def array(self, address: int, struct_name: str, names: tuple[str, ...]) -> dict[str, np.ndarray]:
        """Fields `names` of the array of `struct_name` at `address` (MVert, MPoly ...), one numpy array each,
        read in one pass: a mesh's vertices are hundreds of thousands of structs."""
        block = self.by_address.get(address)
        if block is None:
            return {n: np.zeros((0,)) for n in names}
        fields = self.fields(struct_name)
        size = self.type_sizes[struct_name]
        count = block.size // size
        layout = {"names": [], "formats": [], "offsets": [], "itemsize": size}
        for n in names:
            f = fields[n]
            code = SCALARS.get(f.type)
            if code is None or f.pointer:
                raise BlendFormatError(f"{struct_name}.{n} is not a number array ({f.type})")
            layout["names"].append(n)
            layout["formats"].append((self.order + code, f.shape) if f.shape else self.order + code)
            layout["offsets"].append(f.offset)
        data = np.frombuffer(self.raw, dtype=np.dtype(layout), count=count, offset=block.start)
        return {n: np.array(data[n]) for n in names}

    def listbase(self, first: int, struct_name: str | None = None) -> list[Struct]:
        """The items of a ListBase, from its `first` pointer along each item's `next` (the first field)."""
        out: list[Struct] = []
        seen: set[int] = set()
        address = first
        while address and address not in seen:
            seen.add(address)
            item = self.deref(address, struct_name)
            if item is None:
                break
            out.append(item)
            address = item.pointer_at(0)
        return out

    def string_at(self, address: int) -> str:
        block = self.by_address.get(address)
        if block is None:
            return ""
        return self.raw[block.start:block.start + block.size].split(b"\0")[0].decode("utf-8", "replace")


class Struct:
    """One struct in the file: `s["loc"]`, `s["id"]["name"]` (a nested struct), `s.has("body_type")`."""

    __slots__ = ("file", "name", "offset")

    def __init__(self, file: BlendFile, name: str, offset: int):
        self.file = file
        self.name = name
        self.offset = offset

    def has(self, field: str) -> bool:
        return field in self.file.fields(self.name)

    def field(self, field: str) -> Field:
        try:
            return self.file.fields(self.name)[field]
        except KeyError:
            raise BlendFormatError(f"its {self.name} structs have no field {field!r} (a Blender version this "
                                   "reader does not know)") from None

    def get(self, field: str, default=None):
        return self[field] if self.has(field) else default

    def __getitem__(self, field: str):
        f = self.field(field)
        f_file = self.file
        start = self.offset + f.offset
        if f.pointer:
            if f.items > 1:
                return [self.pointer_at(f.offset + i * f_file.psize) for i in range(f.items)]
            return self.pointer_at(f.offset)
        if f.type in f_file.struct_index:
            return Struct(f_file, f.type, start)
        code = SCALARS.get(f.type)
        if code is None:
            raise BlendFormatError(f"field {self.name}.{field} has a type this reader does not read ({f.type})")
        if f.type == "char" and f.items > 1:
            return f_file.raw[start:start + f.items].split(b"\0")[0].decode("utf-8", "replace")
        values = struct.unpack_from(f_file.order + code * f.items, f_file.raw, start)
        if f.items == 1:
            return values[0]
        array = np.array(values)
        return array.reshape(f.shape) if len(f.shape) > 1 else array

    def pointer_at(self, relative: int) -> int:
        file = self.file
        return struct.unpack_from(file.order + ("Q" if file.psize == 8 else "I"), file.raw,
                                  self.offset + relative)[0]
