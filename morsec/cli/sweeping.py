"""The sweep command: many runs of a scene over seeds and parameters, locally or on a Dask cluster."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Annotated, Any

import typer

from morsec.cli.common import console, fail, on_terminal
from morsec.errors import MorsecError


def sweep(
    sweep_file: Annotated[Path, typer.Argument(help="sweep file (.yaml, .yml, .toml)")],
    out: Annotated[Path | None, typer.Option(
        "-o", "--out", help="results folder: runs.parquet, runs.csv, logs/, summary.csv (default: "
        "results/<sweep name>)")] = None,
    resume: Annotated[bool, typer.Option(
        "--resume", help="run only what the results folder does not hold yet")] = False,
    scheduler: Annotated[str | None, typer.Option(
        "--scheduler", help="a Dask scheduler's address (tcp://host:8786): run on its cluster instead of here")] = None,
    workers: Annotated[int | None, typer.Option(
        min=1, help="runs at once on this machine (default: one per core)")] = None,
    plot: Annotated[bool, typer.Option("--plot", help="draw the summary: summary.png in the results folder")] = False,
) -> None:
    """Run a scene over seeds and parameters, one row per run (status, metrics, times, log) in a table, and
    summarize: exit 0 when every run ended ok, 1 when some did not, 2 for a mistake in the sweep."""
    from morsec.app.sweep.driver import run_sweep
    from morsec.app.sweep.summary import counts, format_summary
    if scheduler and workers:
        fail(MorsecError("--workers is for this machine: a Dask cluster has its own (dask worker --nthreads N)"))
    results = out or Path("results") / sweep_file.stem
    reporter = Bar() if on_terminal() else Lines()
    try:
        outcome = run_sweep(sweep_file, results, reporter, resume=resume, scheduler=scheduler, workers=workers,
                            plot=plot)
    except MorsecError as err:
        reporter.stop()
        fail(err)
    except KeyboardInterrupt:
        reporter.stop()
        typer.echo(f"interrupted: the finished runs are in {results}; add --resume to continue", err=True)
        raise typer.Exit(130) from None
    reporter.stop()
    failed = sum(row["status"] != "ok" for row in outcome.rows)
    typer.echo(f"{counts(outcome.rows)} ({outcome.ran} run now) -> {results}")
    text = format_summary(outcome.groups)
    if text:
        typer.echo("")
        typer.echo(text)
    typer.echo("")
    for path in [*outcome.files, *([outcome.plot] if outcome.plot else [])]:
        typer.echo(f"wrote {path}")
    if failed:
        raise typer.Exit(1)


class Lines:
    """Progress without a terminal: a line per finished run."""

    def __init__(self):
        self.total = self.count = 0

    def start(self, total: int, done: int, workers: int) -> None:
        self.total, self.count = total, done
        typer.echo(f"{total - done} runs to do ({done} done before), {workers} at a time")

    def row(self, row: dict[str, Any]) -> None:
        self.count += 1
        line = f"[{self.count}/{self.total}] {row['run']} {row['status']} {row.get('wall_time', 0.0):.1f} s"
        if row["status"] != "ok":
            line += f": {row['reason']} (log: {row['log']})"
        typer.echo(line)

    def stop(self) -> None:
        pass


class Bar:
    """On a terminal: a progress bar with the count, the failures and the time left; failed runs are printed
    above it as they come."""

    def __init__(self):
        self.progress = None
        self.task = None
        self.failed = 0
        self.started = time.monotonic()

    def start(self, total: int, done: int, workers: int) -> None:
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )
        self.progress = Progress(TextColumn("sweep"), BarColumn(), MofNCompleteColumn(),
                                 TextColumn("[red]{task.fields[failed]} failed"), TimeElapsedColumn(),
                                 TextColumn("left"), TimeRemainingColumn(), console=console(), transient=True)
        self.progress.start()
        self.task = self.progress.add_task("sweep", total=total, completed=done, failed=0)
        console().print(f"{total - done} runs to do ({done} done before), {workers} at a time")

    def row(self, row: dict[str, Any]) -> None:
        assert self.progress is not None
        if row["status"] != "ok":
            self.failed += 1
            self.progress.console.print(f"[red]{row['status']}[/red] {row['run']}: {row['reason']} "
                                        f"(log: {row['log']})", markup=True, highlight=False)
        self.progress.update(self.task, advance=1, failed=self.failed)

    def stop(self) -> None:
        if self.progress is not None:
            self.progress.stop()
            self.progress = None
