"""Middlewares: MORSE's socket protocol (streams, services, lockstep) and text files."""
