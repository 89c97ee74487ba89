"""Reading a run folder's own files back (``report --run``): JSON and CSV written by
clutchfem, or edited since, with refusals that name the file and what is wrong.

What a folder may hold after it left clutchfem's hands (issue 24: each was a traceback):

* **truncated** JSON (a full disk, a copy interrupted): refused naming the file and where
  the text stops (line, column);
* **another encoding** (a CSV saved by a spreadsheet in Windows-1252 / Latin-1, a JSON
  edited in an old editor): JSON must be UTF-8 (RFC 8259) and is refused naming the first
  byte that is not; a CSV is read as UTF-8, else as Windows-1252 (its text shown as it is);
* a **truncated or ragged** CSV (rows with more fields than the header): refused naming the
  file and the row;
* a ``page.json`` that is JSON but no page (a key missing): refused naming the key.
"""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from ..core import InputError

__all__ = ["read_csv", "read_json"]


def read_json(path: str | Path, what: str = "JSON file"):
    """The JSON document in ``path`` (module docstring)."""
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"{what} {path}: cannot be read ({exc.strerror or exc})") from None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"{what} {path}: not UTF-8 text (byte 0x{raw[exc.start]:02x} at position {exc.start}: saved "
                         "in another encoding, e.g. Latin-1?); save it as UTF-8 again") from None
    if not text.strip():
        raise InputError(f"{what} {path}: empty")
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        cut = exc.msg.startswith("Unterminated") or exc.pos >= len(text.rstrip()) - 1
        raise InputError(f"{what} {path}: " + ("truncated: the text ends" if cut else "not valid JSON")
                         + f" at line {exc.lineno}, column {exc.colno} ({exc.msg}); restore the file or run the "
                         "command that wrote it again") from None


def read_csv(path: str | Path) -> pd.DataFrame:
    """The table in the CSV file ``path`` (module docstring)."""
    path = Path(path)
    last = None
    for enc in ("utf-8-sig", "cp1252"):
        try:
            return pd.read_csv(path, encoding=enc)
        except UnicodeDecodeError as exc:
            last = exc
            continue
        except pd.errors.EmptyDataError:
            raise InputError(f"CSV file {path}: empty (no header row)") from None
        except pd.errors.ParserError as exc:
            raise InputError(f"CSV file {path}: a row does not fit the header, truncated or edited? "
                             f"({str(exc).strip()})") from None
        except OSError as exc:
            raise InputError(f"CSV file {path}: cannot be read ({exc.strerror or exc})") from None
    raise InputError(f"CSV file {path}: not text in UTF-8 or Windows-1252 ({last})")
