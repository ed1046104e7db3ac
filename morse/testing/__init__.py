"""MORSE's test framework: `from morse.testing.testing import MorseTestCase, main` (see morse.testing.testing)."""
