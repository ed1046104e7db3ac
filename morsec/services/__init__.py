"""Services: the request manager (sync/async, cancel, preemption) and the pseudo-components
`simulation`, `time` and `communication`."""
