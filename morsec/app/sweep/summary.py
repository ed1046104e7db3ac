"""The end of a sweep: for each parameter and each of its values, the runs, how many failed, and each metric's
mean, standard deviation, minimum and maximum over the runs that ended ok (all other parameters and the seeds
pooled). Printed as a text table, written as `summary.csv`, and drawn (`--plot`) as `summary.png`: one panel
per metric and parameter, the mean with its spread as an error bar over every run's value."""

from __future__ import annotations

import csv
import math
import statistics
from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from morsec.app.sweep.execute import HEAD, MIDDLE, OK, STATUSES, TAIL

ALL = "(all runs)"
SUMMARY_CSV = "summary.csv"
SUMMARY_PNG = "summary.png"


@dataclass
class Stat:
    n: int
    mean: float
    std: float
    min: float
    max: float

    def text(self) -> str:
        return f"{_g(self.mean)} ± {_g(self.std)}"


@dataclass
class Group:
    parameter: str
    value: Any
    runs: int
    failed: int
    stats: dict[str, Stat | None]
    values: dict[str, list[float]]  # each ok run's value, for the plot


def metric_columns(rows: list[dict], parameters: list[str]) -> list[str]:
    fixed = set(HEAD) | set(MIDDLE) | set(TAIL) | set(parameters)
    seen: dict[str, None] = {}
    for row in rows:
        for key, value in row.items():
            if key not in fixed and isinstance(value, (int, float)):  # a boolean's mean is how often it is true
                seen[key] = None
    return list(seen)


def summarize(rows: list[dict], parameters: list[str], order: dict[str, list] | None = None) -> list[Group]:
    """`order`: each parameter's values in the sweep file's order (the rows come in the order runs finished)."""
    metrics = metric_columns(rows, parameters)
    groups = []
    for parameter in parameters or [ALL]:
        by_value: dict[Any, list[dict]] = {}
        for row in rows:
            by_value.setdefault(row.get(parameter) if parameter != ALL else ALL, []).append(row)
        for value in _ordered(list(by_value), (order or {}).get(parameter, [])):
            members = by_value[value]
            ok = [r for r in members if r.get("status") == OK]
            values = {m: [float(r[m]) for r in ok if _number(r.get(m)) or isinstance(r.get(m), bool)]
                      for m in metrics}
            groups.append(Group(parameter, value, len(members), len(members) - len(ok),
                                {m: _stat(v) for m, v in values.items()}, values))
    return groups


def counts(rows: list[dict]) -> str:
    by_status = Counter(row.get("status") for row in rows)
    parts = [f"{by_status[s]} {s}" for s in STATUSES if by_status[s]]
    return f"{len(rows)} runs: {', '.join(parts) or 'none'}"


def format_summary(groups: list[Group]) -> str:
    """Text tables, one per parameter: value, runs, failed, then each metric's mean ± standard deviation."""
    blocks = []
    for parameter in dict.fromkeys(g.parameter for g in groups):
        mine = [g for g in groups if g.parameter == parameter]
        metrics = list(mine[0].stats)
        header = [parameter, "runs", "failed", *metrics]
        table = [header] + [[_show(g.value), str(g.runs), str(g.failed),
                             *((g.stats[m].text() if g.stats[m] else "-") for m in metrics)] for g in mine]
        widths = [max(len(r[i]) for r in table) for i in range(len(header))]
        lines = ["  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in enumerate(zip(r, widths))).rstrip()
                 for r in table]
        blocks.append("\n".join(lines))
    return "\n\n".join(blocks)


def write_summary(groups: list[Group], out: Path) -> Path:
    path = Path(out) / SUMMARY_CSV
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(["parameter", "value", "runs", "failed", "metric", "n", "mean", "std", "min", "max"])
        for g in groups:
            for metric, stat in g.stats.items():
                writer.writerow([g.parameter, _show(g.value), g.runs, g.failed, metric,
                                 *((stat.n, stat.mean, stat.std, stat.min, stat.max) if stat else (0, "", "", "", ""))])
            if not g.stats:
                writer.writerow([g.parameter, _show(g.value), g.runs, g.failed, "", "", "", "", "", ""])
    return path


def plot_summary(groups: list[Group], out: Path, title: str) -> Path:
    """summary.png: a panel per (metric, parameter); without metrics, the failures per value."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    parameters = list(dict.fromkeys(g.parameter for g in groups))
    metrics = list(groups[0].stats) if groups else []
    rows = metrics or ["failed runs"]
    fig, axes = plt.subplots(len(rows), len(parameters), squeeze=False,
                             figsize=(4.2 * len(parameters) + 0.6, 3.0 * len(rows) + 0.8))
    for col, parameter in enumerate(parameters):
        mine = [g for g in groups if g.parameter == parameter]
        labels = [_show(g.value) for g in mine]
        numeric = all(_number(g.value) for g in mine)
        xs = [float(g.value) for g in mine] if numeric else list(range(len(mine)))
        for row, metric in enumerate(rows):
            ax = axes[row][col]
            if metrics:
                for x, g in zip(xs, mine):
                    ax.scatter([x] * len(g.values[metric]), g.values[metric], s=10, alpha=0.35, color="tab:blue")
                points = [(x, g.stats[metric]) for x, g in zip(xs, mine) if g.stats[metric]]
                ax.errorbar([x for x, _ in points], [s.mean for _, s in points], yerr=[s.std for _, s in points],
                            fmt="o-" if numeric else "o", color="tab:red", capsize=4, label="mean ± std")
                ax.set_ylabel(metric)
            else:
                ax.bar(xs, [g.failed for g in mine], color="tab:red")
                ax.set_ylabel("failed runs")
            if not numeric:
                ax.set_xticks(xs, [_short(label) for label in labels], rotation=15, fontsize=7)
                ax.set_xlim(-0.5, len(xs) - 0.5)
            ax.set_xlabel(parameter if parameter != ALL else "")
            ax.grid(alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0, 1, 0.98))
    path = Path(out) / SUMMARY_PNG
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def _stat(values: list[float]) -> Stat | None:
    if not values:
        return None
    std = statistics.stdev(values) if len(values) > 1 else 0.0
    return Stat(len(values), statistics.fmean(values), std, min(values), max(values))


def _number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _ordered(values: list[Any], written: list[Any]) -> list[Any]:
    rank = {v: i for i, v in enumerate(written) if isinstance(v, (str, int, float, bool))}
    return sorted(values, key=lambda v: rank.get(v, len(rank)) if isinstance(v, (str, int, float, bool)) else len(rank))


def _show(value: Any) -> str:
    return "-" if value is None else str(value)


def _short(label: str, limit: int = 32) -> str:
    return label if len(label) <= limit else label[:limit - 3] + "..."


def _g(x: float) -> str:
    return f"{x:.4g}"
