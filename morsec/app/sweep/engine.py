"""Where the runs execute. No scheduler of morsec's own:

- locally (the default), a pool of threads, as many as cores: each run is a `morsec run` process (and its
  client's), so the machine runs one simulation per core, with no cluster to start;
- with `--scheduler ADDRESS`, a Dask distributed cluster (`distributed.Client`): Dask places the runs on its
  workers' threads (start workers with `--nthreads` = their cores), redoes the runs of a worker that is lost,
  and retries a run whose task failed. Each build travels once to every worker (scattered to all, so that a
  lost worker loses no build) and is written in their temporary folder; each row comes back with its log's
  text.

Both yield rows as the runs finish."""

from __future__ import annotations

import os
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor, as_completed
from pathlib import Path
from typing import Any

from morsec.app.sweep import execute
from morsec.app.sweep.plan import RunTask
from morsec.errors import RuntimeFailure

CONNECT_TIMEOUT = 30  # s to reach a Dask scheduler
RETRIES = 2  # a run whose task raised (not a run that failed: that is a row) is tried again, on any worker


def cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


class LocalEngine:
    def __init__(self, workers: int | None = None):
        self.workers = workers or cores()

    def run(self, tasks: list[RunTask]) -> Iterator[dict[str, Any]]:
        execute.cancelled.clear()
        pool = ThreadPoolExecutor(self.workers, thread_name_prefix="morsec-sweep")
        try:
            futures = [pool.submit(execute.execute_run, task) for task in tasks]
            for future in as_completed(futures):
                yield future.result()
        finally:
            execute.stop_everything()  # an interrupted sweep: the runs still going are stopped
            pool.shutdown(wait=True, cancel_futures=True)

    def close(self) -> None:
        pass


class DaskEngine:
    def __init__(self, address: str):
        from distributed import Client
        try:
            self.client = Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
        except (OSError, TimeoutError) as err:
            raise RuntimeFailure(f"cannot reach the Dask scheduler at {address}: {err}") from None
        self.workers = max(1, sum(self.client.nthreads().values()))

    def run(self, tasks: list[RunTask]) -> Iterator[dict[str, Any]]:
        from distributed import as_completed as dask_completed
        builds = {}
        for task in tasks:
            if task.build_key not in builds:
                files = execute.read_build(Path(task.build_dir))
                builds[task.build_key] = self.client.scatter([files], hash=False, broadcast=True)[0]
        futures = {}
        for task in tasks:
            future = self.client.submit(execute.execute_run, task, builds[task.build_key], pure=False,
                                        retries=RETRIES, key=f"morsec-run-{task.run}-{os.urandom(4).hex()}")
            futures[future] = task
        try:
            for future in dask_completed(list(futures), loop=self.client.loop):
                task = futures.pop(future)
                try:
                    row = future.result()
                except Exception as err:  # the task could not be run (its worker was lost too often ...)
                    row = execute.run_row(task, execute.SIMULATION_FAILED,
                                          f"Dask could not run it: {type(err).__name__}: {err}")
                    row["_log"] = f"Dask: {type(err).__name__}: {err}\n"
                future.release()  # its row is here: a worker lost later does not make Dask run it again
                yield row
        finally:
            self.client.cancel(list(futures))

    def close(self) -> None:
        self.client.close()
