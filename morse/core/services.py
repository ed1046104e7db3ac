"""MORSE's `morse.core.services`: `@service`, `@async_service`, `@interruptible`, `@noninterruptible` on a
component's methods. Each marks the method with morsec's service declaration (`morsec.component.services`), so
that the request manager serves it on every middleware as it serves morsec's own components' services: a
synchronous service answers with its return value; an asynchronous one is started by the call and answered when
the component calls `self.completed(status, result)`; a second call while one runs preempts it (interruptible),
fails (noninterruptible or no policy, MORSE's default)."""

from __future__ import annotations

import dataclasses
from functools import partial

from morse.core.emulation import not_emulated
from morsec.component.services import ServiceInfo

__all__ = ["async_service", "interruptible", "noninterruptible", "service"]


def _mark(fn, name, asynchronous):
    fn._morse_service = True
    fn._morse_service_name = name
    fn._morse_service_is_async = asynchronous
    policy = getattr(fn, "_morse_service_interruptible", None)
    fn._morsec_service = ServiceInfo(name or fn.__name__, asynchronous, policy if asynchronous else None)
    return fn


def service(fn=None, component=None, name=None, asynchronous=False, **kwargs):
    """A service of the component's class (MORSE's `component=` for a free function is not emulated)."""
    asynchronous = asynchronous or kwargs.pop("async", False)
    if component is not None:
        not_emulated("@service(component=...) on a free function (a service of a component's class is)")
    if callable(fn):
        return _mark(fn, name, asynchronous)
    return partial(service, name=name, asynchronous=asynchronous)


def async_service(fn=None, component=None, name=None):
    """An asynchronous service: the call starts it, `self.completed(status, result)` answers it."""
    return service(fn, component, name, asynchronous=True)


def _policy(fn, interruptible: bool):
    fn._morse_service_interruptible = interruptible
    info = getattr(fn, "_morsec_service", None)
    if info is not None and info.asynchronous:
        fn._morsec_service = dataclasses.replace(info, interruptible=interruptible)
    return fn


def interruptible(fn):
    """A new request preempts this running asynchronous service (its client is answered PREEMPTED)."""
    return _policy(fn, True)


def noninterruptible(fn):
    """A new request fails while this asynchronous service runs."""
    return _policy(fn, False)
