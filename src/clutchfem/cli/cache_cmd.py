"""``clutchfem cache``: show the mesh cache (folder, entries, size, bound) and clear it."""

from __future__ import annotations

import time

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError
from . import options as O
from .common import console, err, fail


@O.takes("json_")
def cache(
    o,
    clear: bool = typer.Option(False, "--clear", help="delete every cached mesh (they are rebuilt when needed)"),
):
    """The mesh cache: its folder ($CLUTCHFEM_CACHE, else the platform's cache folder, e.g.
    ~/.cache/clutchfem or $XDG_CACHE_HOME/clutchfem), entries, size and bound
    ($CLUTCHFEM_CACHE_SIZE, default 1 GB; the least recently used meshes are evicted)."""
    from .. import cache_dir, cache_entries, cache_foreign_files, cache_limit, clear_cache, dumps

    try:
        d = cache_dir()
        limit = cache_limit()
        if clear:
            n, freed = clear_cache(d)
            err.print(escape(f"deleted {n} cached meshes ({freed / 1e6:.1f} MB) from {d}"), soft_wrap=True)
        entries = cache_entries(d)
        size = sum(e.size for e in entries)
        others = cache_foreign_files(d)
        if clear and others:
            err.print(escape(f"kept {len(others)} file(s) the cache did not write: " + ", ".join(p.name for p in others[:5])
                             + (", ..." if len(others) > 5 else "")), soft_wrap=True)
        info = {"folder": str(d), "entries": len(entries), "size_bytes": size, "limit_bytes": limit,
                "other_files": len(others),
                "oldest_use": entries[0].used if entries else None, "newest_use": entries[-1].used if entries else None}
        if o.json_:
            print(dumps(info))
            return
        t = Table(title="mesh cache")
        t.add_column("quantity")
        t.add_column("value")
        when = (lambda x: time.strftime("%Y-%m-%d %H:%M", time.localtime(x)) if x else "-")
        for q, v in (("folder (CLUTCHFEM_CACHE)", str(d)), ("cached meshes", f"{len(entries)}"),
                     ("size", f"{size / 1e6:.1f} MB"),
                     ("other files (not the cache's: never deleted)", f"{len(others)}"),
                     ("bound (CLUTCHFEM_CACHE_SIZE)", f"{limit / 1e6:.0f} MB (least recently used meshes evicted)"),
                     ("least / most recently used", f"{when(info['oldest_use'])} / {when(info['newest_use'])}")):
            t.add_row(escape(q), escape(v))
        console.print(t)
    except ClutchfemError as exc:
        fail(exc)
