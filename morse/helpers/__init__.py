"""MORSE's `morse.helpers`: the helpers MORSE's components use (`components`, `transformation`, `morse_math`)."""
