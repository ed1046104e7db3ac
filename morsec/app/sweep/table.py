"""The sweep's table: one row per finished run, in `runs.parquet` and `runs.csv` of the output folder, both
written as each run finishes, so that a sweep killed at any moment keeps what it did. The CSV gets the row
appended (rewritten whole only when a row brings a new column); the Parquet file is written whole each time,
to a temporary file put in place at once, so it is always complete: `--resume` reads it.

Columns: run, variant, seed, the variant's scene paths, status, reason, the metrics (morsec's, then the
client's), sim_time, wall_time, rtf, host, log. A column's Parquet type follows its values: booleans,
integers, numbers (integers and floats together), else text."""

from __future__ import annotations

import csv
import json
import os
from pathlib import Path
from typing import Any

from morsec.app.sweep.execute import HEAD, MIDDLE, TAIL
from morsec.errors import MorsecError

PARQUET = "runs.parquet"
CSV = "runs.csv"
LOGS = "logs"


class Table:
    def __init__(self, out: Path, parameters: list[str], rows: list[dict[str, Any]] | None = None):
        self.out = Path(out)
        self.parameters = list(parameters)
        self.rows: list[dict[str, Any]] = list(rows or [])
        self.columns = self._columns(self.rows)
        self._write_csv()
        if self.rows:
            self._write_parquet()

    @classmethod
    def resume(cls, out: Path, parameters: list[str]) -> Table:
        """The table of an earlier sweep in `out` (its Parquet file), to continue."""
        import pyarrow.parquet as pq
        path = Path(out) / PARQUET
        if not path.is_file():
            return cls(out, parameters)
        try:
            rows = pq.read_table(path).to_pylist()
        except Exception as err:  # pyarrow's errors: ArrowInvalid, OSError ...
            raise MorsecError(f"{path}: cannot read the results of the earlier sweep: {err}") from None
        return cls(out, parameters, rows)

    def done(self) -> set[str]:
        return {row["run"] for row in self.rows}

    def add(self, row: dict[str, Any]) -> None:
        self.rows.append(row)
        columns = self._columns(self.rows)
        if columns != self.columns:
            self.columns = columns
            self._write_csv()
        else:
            with open(self.out / CSV, "a", newline="", encoding="utf-8") as f:
                csv.writer(f).writerow([_csv_cell(row.get(c)) for c in self.columns])
        self._write_parquet()

    def _columns(self, rows: list[dict[str, Any]]) -> list[str]:
        fixed = set(HEAD) | set(MIDDLE) | set(TAIL) | set(self.parameters)
        extra: dict[str, None] = {}
        for row in rows:
            extra.update((k, None) for k in row if k not in fixed)
        present = {k for row in rows for k in row}
        params = [p for p in self.parameters if p in present or not rows]
        return [*HEAD, *params, *MIDDLE, *extra, *TAIL]

    def _write_csv(self) -> None:
        tmp = self.out / f".{CSV}.tmp"
        with open(tmp, "w", newline="", encoding="utf-8") as f:
            writer = csv.writer(f)
            writer.writerow(self.columns)
            writer.writerows([_csv_cell(row.get(c)) for c in self.columns] for row in self.rows)
        os.replace(tmp, self.out / CSV)

    def _write_parquet(self) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq
        arrays = {column: _array(pa, [row.get(column) for row in self.rows]) for column in self.columns}
        tmp = self.out / f".{PARQUET}.tmp"
        pq.write_table(pa.table(arrays), tmp)
        os.replace(tmp, self.out / PARQUET)


def _array(pa, values: list[Any]):
    present = [v for v in values if v is not None]
    if present and all(isinstance(v, bool) for v in present):
        return pa.array(values, pa.bool_())
    if present and all(isinstance(v, int) and not isinstance(v, bool) for v in present):
        return pa.array(values, pa.int64())
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in present):
        return pa.array([None if v is None else float(v) for v in values], pa.float64())
    return pa.array([v if v is None or isinstance(v, str) else json.dumps(v) for v in values], pa.string())


def _csv_cell(value: Any) -> Any:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    return value
