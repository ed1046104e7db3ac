"""MORSE's `morse.core.status`: the statuses a service ends with (morsec's own, the same words)."""

from morsec.component.services import FAILED, PREEMPTED, SUCCESS

__all__ = ["FAILED", "PREEMPTED", "SUCCESS"]
