"""MORSE's `morse.middleware`, for what MORSE's test files import of it: `morse.middleware.ros.tfMessage`."""
