"""Timing side by side, for the benchmarks: batches of the two things compared are interleaved so that
both see the same machine load, and the best batch of each is kept."""

from __future__ import annotations

import time


def batch(fn, calls: int) -> float:
    """Mean time of one call over a batch of `calls`, in seconds."""
    start = time.perf_counter()
    for _ in range(calls):
        fn()
    return (time.perf_counter() - start) / calls


def compare(a, b, calls: int, repeats: int) -> tuple[float, float]:
    """Best batch time of `a` and of `b`, batches interleaved."""
    best_a = best_b = float("inf")
    for _ in range(repeats):
        best_a = min(best_a, batch(a, calls))
        best_b = min(best_b, batch(b, calls))
    return best_a, best_b
