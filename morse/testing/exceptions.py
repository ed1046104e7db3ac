"""MORSE's `morse.testing.exceptions`."""


class MorseTestingError(Exception):
    """The simulation of a MorseTestCase could not be built or did not start (the message says where)."""
