"""MORSE's Python names, for MORSE users' files: a thin façade over morsec.

- `morse.builder` (and `morse.builder.sensors`, `.actuators`, `.robots`, `.creator`, ...): the builder API,
  `from morse.builder import *`, the names of `morsec.builder`;
- `morse.testing.testing`: `MorseTestCase` and `main`, MORSE's test framework, each case run on `morsec run`.

morsec's own code never imports this package (tests/test_layers.py); it is an edge, like `morsec.builder`.
"""
