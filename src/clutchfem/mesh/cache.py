"""The on-disk mesh cache: where it lives, its size bound with least-recently-used eviction,
and what ``clutchfem cache`` shows and clears.

* **Where.** ``$CLUTCHFEM_CACHE/meshes`` if the variable is set, else the platform's user
  cache folder from ``platformdirs`` (Linux: ``$XDG_CACHE_HOME/clutchfem``, by default
  ``~/.cache/clutchfem``; macOS ``~/Library/Caches/clutchfem``; Windows
  ``%LOCALAPPDATA%\\clutchfem\\Cache``) plus ``meshes``.  A variable that points to a file
  (or a folder that cannot be made) is refused naming the variable.
* **Entries.** One per cache key: ``<concept>-<key>.msh`` (read back), ``.json`` (its
  side-car) and ``.groups.msh`` (the named groups, for the user), ``<key>`` 24 hex digits.  An entry's last use is
  its side-car's modification time, touched on every cache hit (access times are not
  reliable: many file systems are mounted ``noatime``).
* **Bound.** ``$CLUTCHFEM_CACHE_SIZE`` (``"500MB"``, ``"2GB"``; default :data:`DEFAULT_SIZE`
  = 1 GB, ASSUMED: ~1400 one-sector concept meshes at the default size, ~0.7 MB each;
  the cache held 287 MB after one test run and a few commands and grew without bound).
  After a new entry is written, if the folder holds more, the least recently used entries
  are deleted until it holds 80 % of the bound; an entry used in the last
  :data:`KEEP_RECENT_S` seconds is never evicted (a study's other worker processes may be
  reading it).
* **Only what it wrote.** The folder carries a marker (:data:`MARKER`) written when the
  cache first uses it; a folder without the marker that holds files the cache did not write
  (anything but entries, lock files and its own temporary files) is refused, naming them,
  before anything is written or deleted.  Eviction and ``clutchfem cache --clear`` delete
  entries only (files named as above), never another file put there later.
* **Concurrent writers.** Processes that mesh the same design at once (a study's workers,
  the test suite's xdist workers sharing one cache) take the entry's lock
  (:func:`entry_lock`, a ``flock`` on ``.locks/<entry>.lock``): the first meshes, the
  others wait and read its files.  Every file is written to a temporary file of its own and
  renamed into place, so a reader sees a whole file or none, also where there is no
  ``fcntl`` (Windows: no lock, two processes may then mesh the same design twice).
* **Why not diskcache.** It keeps values in its own SQLite and file names; meshio and the
  user (``geometry --out`` copies the ``.groups.msh``) need the ``.msh`` files themselves
  on disk, and the eviction needed here is a few lines over ``os.scandir``.
"""

from __future__ import annotations

import contextlib
import os
import re
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import platformdirs

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows: no entry lock (module docstring)
    fcntl = None

from ..core import InputError

__all__ = ["DEFAULT_SIZE", "KEEP_RECENT_S", "MARKER", "CacheEntry", "cache_dir", "cache_entries", "cache_limit",
           "clear_cache", "entry_lock", "evict", "cache_foreign_files", "touch"]

#: default bound of the mesh cache [bytes] (module docstring)
DEFAULT_SIZE = 1_000_000_000
#: an entry used this recently [s] is never evicted
KEEP_RECENT_S = 600.0
#: the folder of the entries' lock files, inside the cache folder
LOCKS = ".locks"
#: the marker file of a folder the cache owns (module docstring)
MARKER = ".clutchfem-mesh-cache"
#: the prefix of the cache's temporary files (a write interrupted leaves one: the cache's own)
TMP_PREFIX = ".clutchfem-tmp-"
#: a file of a cache entry: ``<concept>-<24 hex>`` and one of its suffixes
_ENTRY = re.compile(r"(?P<name>[A-Za-z0-9_.+]+-[0-9a-f]{24})(?P<suffix>\.groups\.msh|\.msh|\.json)")
_UNITS = {"": 1, "b": 1, "kb": 1e3, "mb": 1e6, "gb": 1e9, "tb": 1e12, "kib": 1024, "mib": 1024 ** 2,
          "gib": 1024 ** 3}


@dataclass(frozen=True)
class CacheEntry:
    """One cached mesh: its name (``<concept>-<key>``), files, total size [bytes] and last
    use (Unix time)."""

    name: str
    files: tuple[Path, ...]
    size: int
    used: float


def cache_dir() -> Path:
    """The mesh cache folder (module docstring), created on first use.

    Returns
    -------
    Path
        ``$CLUTCHFEM_CACHE/meshes``, else the platform's user cache folder plus ``meshes``;
        an unusable folder is refused naming the variable (:class:`~clutchfem.InputError`).

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.cache_dir()
    >>> d.name, d.is_dir()
    ('meshes', True)
    """
    env = os.environ.get("CLUTCHFEM_CACHE")
    root = Path(env) if env else Path(platformdirs.user_cache_dir("clutchfem", appauthor=False))
    where = f"CLUTCHFEM_CACHE={env}" if env else f"the cache folder {root}"
    d = root / "meshes"
    if root.exists() and not root.is_dir():
        raise InputError(f"{where}: is a file, not a folder; point CLUTCHFEM_CACHE to a folder (or unset it: the "
                         "default is the platform's cache folder, ~/.cache/clutchfem on Linux)")
    try:
        d.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"{where}: cannot make the mesh cache {d} ({exc.strerror or exc}); point CLUTCHFEM_CACHE "
                         "to a folder you can write") from None
    if not os.access(d, os.W_OK | os.X_OK):
        raise InputError(f"{where}: no permission to write in {d}; point CLUTCHFEM_CACHE to a folder you can write")
    if not (d / MARKER).is_file():
        others = cache_foreign_files(d)
        if others:
            names = ", ".join(p.name for p in others[:4]) + (", ..." if len(others) > 4 else "")
            raise InputError(f"{where}: {d} holds {len(others)} file(s) the mesh cache did not write ({names}); "
                             "the cache deletes what it wrote and shares its folder with nothing: point "
                             "CLUTCHFEM_CACHE to a folder of its own, or move those files")
        try:
            (d / MARKER).write_text("clutchfem mesh cache: clutchfem deletes the cached meshes in this folder (and "
                                    "nothing else); see clutchfem cache\n")
        except OSError as exc:
            raise InputError(f"{where}: cannot write in {d} ({exc.strerror or exc}); point CLUTCHFEM_CACHE to a "
                             "folder you can write") from None
    return d


def _own(name: str) -> bool:
    """Whether a file name is one the cache writes (an entry's, its marker, a temporary file)."""
    return bool(_ENTRY.fullmatch(name)) or name in (MARKER, LOCKS) or name.startswith(TMP_PREFIX)


def cache_foreign_files(d: Path) -> list[Path]:
    """The files and folders of ``d`` the mesh cache did not write (sorted).

    Parameters
    ----------
    d : Path
        The cache's mesh folder.

    Returns
    -------
    list of Path
        Every entry whose name is not one the cache writes (``<concept>-<24 hex>.<ext>`` and
        its marker): the cache neither deletes nor evicts these and refuses to share the folder.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from clutchfem.mesh.cache import cache_foreign_files
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> for f in ("concept4-0123456789abcdef01234567.msh", "my notes.txt"):
    ...     _ = (d / f).write_text("x")
    >>> [p.name for p in cache_foreign_files(d)]
    ['my notes.txt']
    """
    return sorted(Path(e.path) for e in os.scandir(d) if not _own(e.name))


def cache_limit() -> int:
    """The cache bound [bytes]: ``$CLUTCHFEM_CACHE_SIZE`` (``"2GB"``) or :data:`DEFAULT_SIZE`.

    Returns
    -------
    int
        Bytes (decimal ``kB``/``MB``/``GB``/``TB`` or binary ``KiB``/``MiB``/``GiB``); a size
        that cannot be read is refused naming the variable (:class:`~clutchfem.InputError`).

    Examples
    --------
    >>> import clutchfem as cf, os
    >>> saved = os.environ.pop("CLUTCHFEM_CACHE_SIZE", None)
    >>> cf.cache_limit()                               # unset: the default bound, 1 GB
    1000000000
    >>> os.environ["CLUTCHFEM_CACHE_SIZE"] = "500MB"
    >>> cf.cache_limit()
    500000000
    >>> if saved is None: del os.environ["CLUTCHFEM_CACHE_SIZE"]
    ... else: os.environ["CLUTCHFEM_CACHE_SIZE"] = saved
    """
    raw = os.environ.get("CLUTCHFEM_CACHE_SIZE")
    if raw is None or not raw.strip():
        return DEFAULT_SIZE
    m = re.fullmatch(r"\s*(\d+(?:\.\d*)?)\s*([A-Za-z]*)\s*", raw)
    if not m or m.group(2).lower() not in _UNITS or float(m.group(1)) <= 0:
        raise InputError(f"CLUTCHFEM_CACHE_SIZE={raw!r}: expected a size > 0 with a unit, e.g. 500MB or 2GB")
    return int(float(m.group(1)) * _UNITS[m.group(2).lower()])


def cache_entries(d: Path | None = None) -> list[CacheEntry]:
    """Every entry of the cache, least recently used first.

    Parameters
    ----------
    d : Path, optional
        The cache folder (default: :func:`cache_dir`).

    Returns
    -------
    list of CacheEntry
        One per cached mesh: ``name`` (``<concept>-<key>``), ``files``, ``size`` [bytes] and
        ``used`` (the last use, Unix time).

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> for f in ("concept1-ab12ab12ab12ab12ab12ab12.msh", "concept1-ab12ab12ab12ab12ab12ab12.json",
    ...           "concept1-ab12ab12ab12ab12ab12ab12.groups.msh", "mine.msh"):
    ...     _ = (d / f).write_text("x" * 10)
    >>> [(e.name, len(e.files), e.size) for e in cf.cache_entries(d)]   # (not mine.msh: the cache did not write it)
    [('concept1-ab12ab12ab12ab12ab12ab12', 3, 30)]
    """
    d = cache_dir() if d is None else d
    groups: dict[str, list] = {}
    for e in os.scandir(d):
        if not e.is_file():
            continue
        m = _ENTRY.fullmatch(e.name)
        if m is None:  # another file: not the cache's to count or delete
            continue
        name = m.group("name")
        try:
            st = e.stat()
        except OSError:
            continue
        groups.setdefault(name, []).append((Path(e.path), st.st_size, st.st_mtime, e.name.endswith(".json")))
    out = []
    for name, fs in groups.items():
        side = [m for _, _, m, is_side in fs if is_side]
        used = max(side) if side else max(m for _, _, m, _ in fs)
        out.append(CacheEntry(name, tuple(p for p, *_ in fs), sum(s for _, s, _, _ in fs), used))
    return sorted(out, key=lambda x: x.used)


def _entries_size(d: Path) -> int:
    """The total size [bytes] of the entries' files in ``d`` (those :func:`cache_entries`
    counts), without grouping them into entries."""
    total = 0
    with os.scandir(d) as it:
        for e in it:
            if not e.is_file() or _ENTRY.fullmatch(e.name) is None:
                continue
            try:
                total += e.stat().st_size
            except OSError:
                continue
    return total


def touch(side_car: Path) -> None:
    """Mark an entry as used now (its side-car's modification time)."""
    try:
        os.utime(side_car)
    except OSError:
        pass


@contextlib.contextmanager
def entry_lock(d: Path, name: str) -> Iterator[None]:
    """Hold the exclusive lock of entry ``name`` of cache folder ``d`` (module docstring):
    blocks while another process holds it.  Without ``fcntl`` (Windows) it locks nothing."""
    if fcntl is None:  # pragma: no cover - Windows: atomic renames alone keep readers safe
        yield
        return
    locks = d / LOCKS
    locks.mkdir(exist_ok=True)
    fd = os.open(locks / f"{name}.lock", os.O_RDWR | os.O_CREAT, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # releases the lock


def _unlink(files) -> None:
    for f in files:
        try:
            f.unlink()
        except OSError:
            pass


def evict(limit: int | None = None, d: Path | None = None) -> tuple[int, int]:
    """Delete the least recently used entries while the cache holds more than ``limit``
    (default :func:`cache_limit`), down to 80 % of it; entries used in the last
    :data:`KEEP_RECENT_S` stay.  Returns (entries deleted, bytes freed)."""
    limit = cache_limit() if limit is None else limit
    d = cache_dir() if d is None else d
    # it runs after every new mesh and the cache is mostly within its bound: the total of the
    # entries' files first, without grouping them (the same files :func:`cache_entries`
    # counts; a quarter of its cost: 8 against 32 ms of CPU with 600 entries)
    if _entries_size(d) <= limit:
        return 0, 0
    entries = cache_entries(d)
    total = sum(e.size for e in entries)
    if total <= limit:
        return 0, 0
    now, n, freed = time.time(), 0, 0
    for e in entries:
        if total <= 0.8 * limit:
            break
        if now - e.used < KEEP_RECENT_S:
            continue
        _unlink((*e.files, _lock_file(e)))
        total -= e.size
        freed += e.size
        n += 1
    return n, freed


def clear_cache(d: Path | None = None) -> tuple[int, int]:
    """Delete every entry of the cache (``clutchfem cache --clear``): the next design of each
    concept is meshed again.  Only the cache's entries go (module docstring): any other file
    in the folder stays.

    Parameters
    ----------
    d : Path, optional
        The cache folder (default: :func:`cache_dir`).

    Returns
    -------
    tuple of int
        (entries deleted, bytes freed).

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> for f in ("concept4-cd34cd34cd34cd34cd34cd34.msh", "concept4-cd34cd34cd34cd34cd34cd34.json", "mine.txt"):
    ...     _ = (d / f).write_text("x" * 10)
    >>> cf.clear_cache(d), cf.cache_entries(d), [p.name for p in d.iterdir()]
    ((1, 20), [], ['mine.txt'])
    """
    d = cache_dir() if d is None else d
    entries = cache_entries(d)
    for e in entries:
        _unlink((*e.files, _lock_file(e)))
    now = time.time()
    for e in os.scandir(d):  # temporary files of interrupted writes (not of one running now)
        if e.name.startswith(TMP_PREFIX) and e.is_file() and now - e.stat().st_mtime > KEEP_RECENT_S:
            _unlink((Path(e.path),))
    return len(entries), sum(e.size for e in entries)


def _lock_file(e: CacheEntry) -> Path:
    """The lock file of an entry (it may not exist)."""
    return e.files[0].parent / LOCKS / f"{e.name}.lock"
