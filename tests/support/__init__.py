"""Test support: verification shapes and solver edge cases (never imported by the library)."""
