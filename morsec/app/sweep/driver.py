"""`morsec sweep` end to end: the sweep file read and checked, its variants built, the runs not done yet
handed to the engine, each row written as it comes (its log beside the table), then the summary."""

from __future__ import annotations

import importlib.util
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

from morsec.app.sweep.execute import cell
from morsec.app.sweep.plan import RunTask, plan
from morsec.app.sweep.spec import Sweep, load_sweep
from morsec.app.sweep.summary import Group, plot_summary, summarize, write_summary
from morsec.app.sweep.table import CSV, LOGS, PARQUET, Table
from morsec.errors import MorsecError

INSTALL = "pip install 'morsec[sweep]'"
RECORD = "sweep.json"  # what the rows of the output folder were run with, for --resume to compare


class Reporter(Protocol):
    def start(self, total: int, done: int, workers: int) -> None: ...

    def row(self, row: dict[str, Any]) -> None: ...


@dataclass
class Outcome:
    out: Path
    rows: list[dict[str, Any]]  # the sweep's rows (earlier ones too, with --resume), in the order they finished
    groups: list[Group]
    ran: int  # runs executed this time
    plot: Path | None = None
    files: list[Path] = field(default_factory=list)


def require(module: str, why: str) -> None:
    if importlib.util.find_spec(module) is None:
        raise MorsecError(f"morsec sweep needs {why}, which is not installed: {INSTALL}")


def run_sweep(path: Path, out: Path, report: Reporter, resume: bool = False, scheduler: str | None = None,
              workers: int | None = None, plot: bool = False) -> Outcome:
    require("pyarrow", "pyarrow (the Parquet table)")
    if scheduler:
        require("distributed", "dask.distributed (--scheduler)")
    if plot:
        require("matplotlib", "matplotlib (--plot)")
    sweep = load_sweep(path)
    out = Path(out)
    _claim(sweep, out, resume)
    _variants, tasks = plan(sweep, out)
    parameters = list(dict.fromkeys(key for task in tasks for key in task.values))
    table = Table.resume(out, parameters) if resume else Table(out, parameters)
    done = table.done()
    todo = [task for task in tasks if task.run not in done]
    from morsec.app.sweep.engine import DaskEngine, LocalEngine
    engine = DaskEngine(scheduler) if scheduler else LocalEngine(workers)
    try:
        report.start(len(tasks), len(tasks) - len(todo), engine.workers)
        (out / LOGS).mkdir(exist_ok=True)
        for row in engine.run(todo):
            _finish(row, out, table)
            report.row(row)
    finally:
        engine.close()
    runs = {task.run for task in tasks}
    rows = [row for row in table.rows if row["run"] in runs]
    order = {p: list(dict.fromkeys(cell(t.values[p]) for t in tasks if p in t.values)) for p in parameters}
    groups = summarize(rows, parameters, order)
    outcome = Outcome(out, rows, groups, len(todo), files=[out / PARQUET, out / CSV, write_summary(groups, out)])
    if plot:
        outcome.plot = plot_summary(groups, out, f"{sweep.path.name}: {len(rows)} runs")
    return outcome


def _claim(sweep: Sweep, out: Path, resume: bool) -> None:
    """`out` for this sweep: new, or (--resume) holding the results of the same sweep."""
    record = {"scene": str(sweep.scene), "duration": sweep.spec.duration, "client": sweep.spec.client,
              "metrics": [m.model_dump() for m in sweep.spec.metrics]}
    recorded = out / RECORD
    if out.exists() and not out.is_dir():
        raise MorsecError(f"{out}: exists and is not a folder; choose another with -o")
    if not resume and (out / PARQUET).exists():
        raise MorsecError(f"{out} holds the results of a sweep already: add --resume to continue it, or choose "
                          "another folder with -o")
    if resume and recorded.exists():
        try:
            before = json.loads(recorded.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            before = record
        changed = [key for key in record if before.get(key) != record[key]]
        if changed:
            raise MorsecError(f"{out} holds a sweep with another {', '.join(changed)}: its rows would not compare "
                              "with these; choose another folder with -o")
    out.mkdir(parents=True, exist_ok=True)
    recorded.write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")


def _finish(row: dict[str, Any], out: Path, table: Table) -> None:
    log = out / LOGS / f"{row['run']}.log"
    log.write_text(row.pop("_log", ""), encoding="utf-8")
    row["log"] = str(log)
    table.add(row)


__all__ = ["Outcome", "Reporter", "RunTask", "run_sweep"]
