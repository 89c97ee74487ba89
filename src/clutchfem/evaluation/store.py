"""The result store of a study: one SQLite file in WAL mode, one row per finished point.

Why SQLite (and not Parquet parts):

* **a transaction per row**: the client commits each row the moment its point finishes.
  A ``kill -9`` of the study loses at most the points still computing; every committed row
  is in the write-ahead log, which the next open replays.  Parquet has no append: a
  crash-safe Parquet store is a folder of one-row part files (thousands of tiny files for a
  large study, a compaction step, and a torn part file to detect on resume);
* **keyed lookups**: resume asks "which of these (design hash, model version) pairs are
  finished?", a primary-key query; the same store holds several specs' rows and several
  model versions side by side, and rows are replaced (``--retry-failed``) in place;
* **no new dependency**: ``sqlite3`` is in the standard library, and pandas reads it
  (``read_sql``); the study also exports a CSV of its own rows for spreadsheets.

Durability: ``journal_mode=WAL`` with ``synchronous=NORMAL``: a committed row survives the
process being killed (the WAL is in the OS's page cache once ``COMMIT`` returns); on power
loss the last few commits may be lost, which resume then simply recomputes.  Only the
the study's client process writes (workers return rows, they never touch the file), so there
is one writer; readers (a notebook, ``sqlite3`` on the command line) may read while it runs.

A store locked by another program (a database browser with an open write transaction, a
second study writing the same file): every statement is retried for up to
:data:`LOCK_WAIT_S` (said at once on stderr), then :class:`StoreLocked` names the file and
what to do (nothing finished is lost: the rows already committed stay, a rerun resumes).

The table's columns come from the caller (:data:`clutchfem.evaluation.point.COLUMNS`); a store
written by an older version gains any new columns on open (``ALTER TABLE ADD COLUMN``), and a
table keyed without ``context_hash`` is rebuilt with it in its key (the old rows kept).

A row is keyed by its design (``design_hash``, the design's identity), its study context
(``context_hash``: engine, idle speed, requirement factors, morph reference; see
:mod:`.hashing`) and the model version: one design checked against two engines is two rows.
A store opened with ``context=...`` reads and writes only the rows of that context.
"""

from __future__ import annotations

import logging
import sqlite3
import sys
import time
from pathlib import Path
from typing import Iterable

from ..core import ClutchfemError, InputError

log = logging.getLogger("clutchfem")

#: file name of the store inside a study's output folder
STORE_NAME = "results.sqlite"
_KEY = ("design_hash", "model_version")
#: the key of a store whose columns hold the study context (:func:`.hashing.context_hash`)
_CONTEXT_KEY = ("design_hash", "context_hash", "model_version")
#: seconds a statement waits for a lock another program holds on the store
LOCK_WAIT_S = 30.0


class StoreLocked(ClutchfemError):
    """The store stayed locked by another program for :data:`LOCK_WAIT_S`."""


def _locked(exc: Exception) -> bool:
    return any(w in str(exc).lower() for w in ("database is locked", "database table is locked", "busy"))


class ResultStore:
    """Rows keyed by (design_hash, context_hash, model_version); see module docstring.

    ``context``: read and write only the rows of this study context (a
    :func:`~clutchfem.evaluation.hashing.context_hash`; None: every row)."""

    def __init__(self, path: str | Path, columns: Iterable[tuple[str, str, str]], context: str | None = None):
        self.path = Path(path)
        self.columns = [(c, t) for c, t, *_ in columns]
        names = [c for c, _ in self.columns]
        for k in _KEY:
            if k not in names:
                raise ValueError(f"store columns must include {k}")
        key = _CONTEXT_KEY if "context_hash" in names else _KEY
        self.context = context if "context_hash" in names else None
        try:
            self.db = sqlite3.connect(self.path, timeout=0.5, isolation_level=None)
            self._run("PRAGMA journal_mode=WAL")
            self._run("PRAGMA synchronous=NORMAL")
            cols = ", ".join(f'"{c}" {t}' for c, t in self.columns)
            self._run(f"CREATE TABLE IF NOT EXISTS results ({cols}, PRIMARY KEY ({', '.join(key)}))")
            info = self._run("PRAGMA table_info(results)").fetchall()
            have = {r[1] for r in info}
            for c, t in self.columns:
                if c not in have:
                    self._run(f'ALTER TABLE results ADD COLUMN "{c}" {t}')
            if key == _CONTEXT_KEY and "context_hash" not in {r[1] for r in info if r[5]}:
                self._rekey(cols, key)
            self._run("CREATE TABLE IF NOT EXISTS runs (run INTEGER PRIMARY KEY AUTOINCREMENT, "
                      "started_at REAL, finished_at REAL, source TEXT, model_version TEXT, points INTEGER, "
                      "todo INTEGER, computed INTEGER, outcome TEXT, spec TEXT)")
        except sqlite3.DatabaseError as exc:
            raise InputError(f"result store {self.path}: not a usable SQLite file ({exc}); move it away or "
                             "choose another --out") from None
        self.names = names

    def _rekey(self, cols: str, key: tuple[str, ...]) -> None:
        """Rebuild a table of an older version keyed without ``context_hash`` (rows kept)."""
        names = ", ".join(f'"{c}"' for c, _ in self.columns)
        self._run("BEGIN IMMEDIATE")
        try:
            self._run("ALTER TABLE results RENAME TO results_before_context")
            self._run(f"CREATE TABLE results ({cols}, PRIMARY KEY ({', '.join(key)}))")
            self._run(f"INSERT INTO results ({names}) SELECT {names} FROM results_before_context")
            self._run("UPDATE results SET context_hash = '' WHERE context_hash IS NULL")
            self._run("DROP TABLE results_before_context")
            self._run("COMMIT")
        except BaseException:
            self._run("ROLLBACK")
            raise

    def _where(self, model_version: str | None) -> tuple[str, list]:
        """The WHERE clause of one model version (None: any) in this store's context."""
        conds, args = [], []
        if model_version is not None:
            conds.append("model_version = ?")
            args.append(model_version)
        if self.context is not None:
            conds.append("context_hash = ?")
            args.append(self.context)
        return (" WHERE " + " AND ".join(conds) if conds else ""), args

    def _run(self, sql: str, args=()):
        """``db.execute`` retried while another program holds a lock (module docstring)."""
        return self._retry(lambda: self.db.execute(sql, args))

    def _retry(self, fn):
        t0 = None
        while True:
            try:
                return fn()
            except _lock_errors() as exc:
                if not _locked(exc):
                    raise
                now = time.monotonic()
                if t0 is None:
                    t0 = now
                    log.warning(f"the result store {self.path} is locked by another program (a database browser "
                                f"with unsaved changes?): waiting up to {LOCK_WAIT_S:g} s")
                elif now - t0 > LOCK_WAIT_S:
                    raise StoreLocked(f"the result store {self.path} stayed locked by another program for "
                                      f"{LOCK_WAIT_S:g} s (a database browser with unsaved changes, or a second "
                                      "study writing the same folder?): close it and run the same command again "
                                      "(the rows already stored are kept)") from None
                time.sleep(0.2)

    # -- writing --------------------------------------------------------------------------
    def put(self, row: dict) -> None:
        """Insert or replace one row and commit it (durable when this returns)."""
        if "context_hash" in self.names and row.get("context_hash") is None:  # ('' not NULL: NULLs never collide)
            row = {**row, "context_hash": self.context or ""}
        vals = [row.get(c) for c in self.names]
        marks = ", ".join("?" for _ in self.names)
        cols = ", ".join(f'"{c}"' for c in self.names)
        self._run(f"INSERT OR REPLACE INTO results ({cols}) VALUES ({marks})", vals)

    def start_run(self, source: str, model_version: str, points: int, todo: int, spec: str = "") -> int:
        cur = self._run("INSERT INTO runs (started_at, source, model_version, points, todo, computed, outcome, "
                              "spec) VALUES (?, ?, ?, ?, ?, 0, 'running', ?)",
                              (time.time(), source, model_version, points, todo, spec))
        return int(cur.lastrowid)

    def end_run(self, run: int, computed: int, outcome: str) -> None:
        self._run("UPDATE runs SET finished_at = ?, computed = ?, outcome = ? WHERE run = ?",
                        (time.time(), computed, outcome, run))

    # -- reading --------------------------------------------------------------------------
    def finished(self, model_version: str, keys: Iterable[str] | None = None) -> dict[str, str]:
        """{design_hash: status} of the stored rows of ``model_version`` (among ``keys``)."""
        where, args = self._where(model_version)
        cur = self._run(f"SELECT design_hash, status FROM results{where}", args)
        got = {h: s for h, s in cur}
        if keys is None:
            return got
        return {k: got[k] for k in keys if k in got}

    def select(self, model_version: str, keys: Iterable[str], columns: list[str]) -> dict[str, tuple]:
        """{design_hash: (values of ``columns``)} of the stored rows of ``model_version`` among ``keys``."""
        cols = ", ".join(f'"{c}"' for c in columns)
        where, args = self._where(model_version)
        cur = self._run(f"SELECT design_hash, {cols} FROM results{where}", args)
        got = {r[0]: tuple(r[1:]) for r in cur}
        return {k: got[k] for k in keys if k in got}

    def frame(self, model_version: str | None = None, keys: Iterable[str] | None = None):
        """The rows as a pandas DataFrame (of one model version, and only ``keys`` if given,
        in the order of ``keys``)."""
        import pandas as pd

        where, args = self._where(model_version)
        q = f"SELECT * FROM results{where}"
        df = self._retry(lambda: pd.read_sql_query(q, self.db, params=args))
        if keys is not None:
            order = {k: i for i, k in enumerate(keys)}
            df = df[df["design_hash"].isin(order)].copy()
            df["_order"] = df["design_hash"].map(order)
            df = df.sort_values("_order").drop(columns="_order").reset_index(drop=True)
        return df

    def runs(self):
        """The runs table (one row per run: started, finished, source, counts, outcome)."""
        import pandas as pd

        return self._retry(lambda: pd.read_sql_query("SELECT * FROM runs ORDER BY run", self.db))

    def close(self) -> None:
        self.db.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _lock_errors() -> tuple[type[Exception], ...]:
    """What a locked database raises: sqlite3's error, and pandas' wrapper of it once pandas is in
    use (the store imports pandas only for its tables, so that a live answer's start-up needs none)."""
    pd = sys.modules.get("pandas")
    return (sqlite3.OperationalError,) if pd is None else (sqlite3.OperationalError, pd.errors.DatabaseError)
