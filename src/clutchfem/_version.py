"""The package's version: one place, read by the build (pyproject.toml) and by every module
that records it (mesh cache keys, design records, exported files, the command line)."""

__version__ = "0.3.0"
