"""Reading an engine curve from a CSV file: the columns and their units from the header,
the file's encoding, separator and decimal mark, and a bound on its size.

What is read, and why (issue 24: every one of these used to give a silent wrong answer):

* **Encoding.** UTF-8 with or without a byte-order mark (Excel's "CSV UTF-8"), UTF-16 with
  its mark (Excel's "Unicode text"), else Windows-1252/Latin-1 text (a header such as
  ``Drehmoment [N·m]`` saved by an older tool).  A file with NUL bytes is not text.
* **Separator and decimal mark.** ``,`` ``;`` or tab, whichever the header row uses.  With
  ``;`` or tab a decimal comma is read (``2500;1,90``: 1.90 N m, the European format;
  ``.`` then groups thousands: ``2.500``); with ``,`` a row with more fields than the
  header (``2500,1,90``) is refused: decimal commas cannot be told from separators there.
  A number grouped by thousands separators (``10,000``, quoted or not, in a ``,`` file) is
  said as such: the way out is to write it without them (``10000``), not another separator.
* **Plausible speeds.** A speed above :data:`MAX_ENGINE_RPM` (a ``1e7`` typo) is refused
  naming its row, before any analysis runs into it.
* **Columns.** The speed column is named ``rpm``, ``speed``, ``engine speed``, ``n``,
  ``drehzahl``, ``omega`` or by its unit alone; the torque column ``torque``, ``moment``,
  ``drehmoment``, ``couple`` or ``torque_<anything>``.  Two candidate columns for one of
  them (``torque_max, torque``) are refused naming both: which one is the full-throttle
  torque is the user's call.  Other columns (power, ...) are ignored.  The header may follow
  a few lines of metadata (the first of the first 20 rows with both columns).
* **Units** (:func:`clutchfem.core.units.header_unit`) from ``name [unit]``, ``name
  (unit)``, ``name, unit``, ``name in unit`` or ``name_unit``: torque in N m, N cm, N mm,
  kN m, kgf m, kgf cm, lbf ft, lbf in, ozf in; speed in rpm, 1/min, U/min, tr/min, rev/s,
  Hz, rad/s.  A column without a unit is N m / rpm (the documented default); a unit that
  is not known is refused, naming it.
* **Size.** At most :data:`MAX_ROWS` data rows and :data:`MAX_BYTES` bytes (checked before
  reading): every table speed used to become an FE solve (a 1e6-row dyno log ran for
  minutes); a longer log must be averaged to one torque per speed.
"""

from __future__ import annotations

import codecs
import csv
import io
import os
import re
from dataclasses import dataclass
from pathlib import Path

from ..core import InputError, header_unit, header_units

__all__ = ["MAX_BYTES", "MAX_ENGINE_RPM", "MAX_ROWS", "EngineTable", "read_engine_csv"]

#: the most data rows an engine curve file may hold (ASSUMED: a speed sweep at 1.5 rpm
#: resolution over 0..15 000 rpm; a curve needs a few dozen)
MAX_ROWS = 10_000
#: the largest engine curve file read [bytes] (10 000 rows of 20 wide columns fit)
MAX_BYTES = 8_000_000
#: the highest speed an engine curve row may give [rpm] (ASSUMED: model engines turn up to about
#: 40 000 rpm; a higher speed is a typo such as ``1e7`` or a column in another unit)
MAX_ENGINE_RPM = 60_000.0
#: a number grouped by thousands separators (``10,000``, ``1,250,000.5``)
_THOUSANDS = re.compile(r"[-+]?\d{1,3}(,\d{3})+(\.\d*)?")
#: the rows searched for the header (metadata lines of a dyno export may come first)
HEADER_ROWS = 20

_SPEED_NAMES = ("rpm", "speed", "enginespeed", "crankspeed", "n", "drehzahl", "omega", "regime", "vitesse",
                "speedrpm", "engine_speed")
_TORQUE_NAMES = ("torque", "moment", "drehmoment", "couple", "torquenm")


@dataclass(frozen=True)
class EngineTable:
    """The curve read from a file: rpm [rpm] and torque [N m] (converted), the units the
    file gave and how the file was read (for the curve's ``source`` text)."""

    rpm: tuple[float, ...]
    torque: tuple[float, ...]
    speed_unit: str
    torque_unit: str
    notes: tuple[str, ...]


def _decode(path: Path) -> tuple[str, str]:
    """(text, encoding) of the file (module docstring); a file over :data:`MAX_BYTES` is
    refused before it is read."""
    size = path.stat().st_size
    if size > MAX_BYTES:
        raise InputError(f"engine curve file {path}: {size / 1e6:.0f} MB, more than {MAX_BYTES / 1e6:.0f} MB; a "
                         f"full-throttle curve needs a few dozen rows (at most {MAX_ROWS:,}): average or resample "
                         "the log (e.g. one row every 100 rpm)")
    raw = path.read_bytes()
    if raw.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        try:
            return raw.decode("utf-16"), "UTF-16"
        except UnicodeDecodeError:
            raise InputError(f"engine curve file {path}: starts with a UTF-16 mark but is not UTF-16 text") from None
    if b"\x00" in raw:
        raise InputError(f"engine curve file {path} is not a text CSV (it holds NUL bytes: a binary or "
                         "spreadsheet file?); save it as CSV with columns rpm, torque")
    try:
        return raw.decode("utf-8-sig"), "UTF-8"
    except UnicodeDecodeError:
        pass
    try:
        return raw.decode("cp1252"), "Windows-1252"
    except UnicodeDecodeError:
        return raw.decode("latin-1"), "Latin-1"


def _split_header(cell: str) -> tuple[str, str | None]:
    """(name, unit or None) of a header cell: ``torque [lbf ft]``, ``torque (N m)``,
    ``torque, Nm``, ``torque in N m``, ``torque_nm``, or a bare unit (``rpm``)."""
    c = cell.strip().strip('"').strip()
    m = re.fullmatch(r"(.*?)\s*[\[(\{]\s*(.*?)\s*[\])\}]\s*", c)
    if m:
        return m.group(1).strip(), m.group(2).strip()
    m = re.fullmatch(r"(.*?)\s*(?:,|/|\bin\b)\s*(\S.*)", c, flags=re.I)
    if m and m.group(1).strip() and (header_unit(m.group(2), "N m") or header_unit(m.group(2), "rpm")):
        return m.group(1).strip(), m.group(2).strip()
    m = re.fullmatch(r"([A-Za-z]+)[_\s]+(.+)", c)
    if m and (header_unit(m.group(2), "N m") is not None or header_unit(m.group(2), "rpm") is not None):
        return m.group(1), m.group(2)
    return c, None


def _compact(name: str) -> str:
    return re.sub(r"[\s_\-.]+", "", name.lower())


def _kind(cell: str) -> tuple[str | None, str, str | None]:
    """(``"speed"``/``"torque"``/None, name, unit) of a header cell."""
    name, unit = _split_header(cell)
    n = _compact(name)
    if unit is None and header_unit(name, "rpm") is not None:
        return "speed", name, name  # the unit alone names the column (rpm, 1/min)
    if unit is None and header_unit(name, "N m") is not None:
        return "torque", name, name
    if n in _SPEED_NAMES or n.startswith(("rpm", "enginespeed", "drehzahl")):
        return "speed", name, unit
    if n.startswith(_TORQUE_NAMES):
        return "torque", name, unit
    return None, name, unit


def _delimiter(line: str) -> str:
    for d in (";", "\t"):
        if d in line:
            return d
    return ","


def _number(cell: str, comma: bool) -> float:
    c = cell.strip().replace("\u00a0", "").replace(" ", "")
    if comma:
        if re.fullmatch(r"[-+]?\d{1,3}(\.\d{3})+(,\d*)?", c):
            c = c.replace(".", "")
        c = c.replace(",", ".")
    return float(c)


def read_engine_csv(path: str | Path) -> EngineTable:
    """The engine curve of a CSV file (module docstring); refusals are
    :class:`~clutchfem.core.InputError` naming the file, the row or column and what is
    wrong."""
    if not isinstance(path, (str, os.PathLike)):
        raise InputError(f"engine curve file: a path (str or Path), not {type(path).__name__} {path!r:.60}")
    path = Path(path)
    if not path.is_file():
        raise InputError(f"engine curve file not found (or not a file): {path}")
    try:
        text, encoding = _decode(path)
    except OSError as exc:
        raise InputError(f"engine curve file {path} cannot be read: {exc.strerror or exc}") from None
    lines = [ln for ln in io.StringIO(text, newline=None).read().splitlines()]
    body = [(i + 1, ln) for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith("#")]
    if not body:
        raise InputError(f"engine curve file {path} is empty")
    # the header: the first row (of the first HEADER_ROWS) with a speed and a torque column
    found = None
    for k, (lineno, ln) in enumerate(body[:HEADER_ROWS]):
        delim = _delimiter(ln)
        cells = next(csv.reader([ln], delimiter=delim))
        kinds = [_kind(c) for c in cells]
        speed = [i for i, (kd, _, _) in enumerate(kinds) if kd == "speed"]
        torque = [i for i, (kd, _, _) in enumerate(kinds) if kd == "torque"]
        if speed and torque:
            found = (k, lineno, delim, cells, kinds, speed, torque)
            break
    if found is None:
        raise InputError(f"engine curve file {path}: no header row with a speed column (rpm, speed, ...) and a "
                         f"torque column (torque, ...) in its first {HEADER_ROWS} rows; the first row is "
                         f"{body[0][1].strip()[:120]!r}")
    k, hline, delim, cells, kinds, speed, torque = found
    notes = []
    if k > 0:
        notes.append(f"header on line {hline}; the {k} line(s) above it ignored")
    for what, idx in (("speed", speed), ("torque", torque)):
        if len(idx) > 1:
            names = ", ".join(repr(cells[i].strip()) for i in idx)
            raise InputError(f"engine curve file {path}: {len(idx)} columns could be the {what} ({names}): "
                             f"ambiguous; keep the full-throttle {what} column only, or rename the others")
    i_rpm, i_tq = speed[0], torque[0]
    units = {}
    for what, i, canon in (("speed", i_rpm, "rpm"), ("torque", i_tq, "N m")):
        unit = kinds[i][2]
        if unit is None:
            units[what] = (canon, 1.0)
            continue
        f = header_unit(unit, canon)
        if f is None:
            raise InputError(f"engine curve file {path}: unknown {what} unit {unit!r} in column "
                             f"{cells[i].strip()!r}; known: {', '.join(header_units(canon))}")
        units[what] = (unit, f)
    data = body[k + 1:]
    if len(data) > MAX_ROWS:
        raise InputError(f"engine curve file {path}: more than {MAX_ROWS:,} data rows; a full-throttle curve "
                         "needs a few dozen (one torque per speed): average or resample the log (e.g. one row "
                         "every 100 rpm)")
    rows = [(ln_no, next(csv.reader([ln], delimiter=delim))) for ln_no, ln in data]
    width = len(cells)
    comma = delim != "," and any("," in r[i] for _, r in rows for i in (i_rpm, i_tq) if i < len(r))
    if delim == ",":
        wide = next(((n, r) for n, r in rows if len(r) > width and any(x.strip() for x in r[width:])), None)
        if wide is not None:
            n, r = wide
            # (speeds reach thousands: a speed split at its thousands separators; a torque so split is
            # a decimal comma far likelier)
            grouped = next((",".join(r[i_rpm:j]) for j in range(len(r), i_rpm + 1, -1)
                            if _THOUSANDS.fullmatch(",".join(x.strip() for x in r[i_rpm:j]))), None)
            if grouped is not None:
                raise InputError(f"engine curve file {path}, row {n}: {len(r)} fields under a header of {width} "
                                 f"({','.join(r)!s}): {grouped!r} reads as a number with thousands separators "
                                 f"({grouped.replace(',', '')}); write the numbers without thousands separators")
            raise InputError(f"engine curve file {path}, row {n}: {len(r)} fields under a header of "
                             f"{width} ({','.join(r)!s}): decimal commas with ',' as the separator cannot be "
                             "read; save the file with ';' between the columns (the European CSV format)")
    rpm, tq = [], []
    for lineno, r in rows:
        try:
            rpm.append(_number(r[i_rpm], comma) * units["speed"][1])
            tq.append(_number(r[i_tq], comma) * units["torque"][1])
        except (ValueError, IndexError):
            cell = next((r[i].strip() for i in (i_rpm, i_tq) if i < len(r) and _THOUSANDS.fullmatch(r[i].strip())),
                        None)
            if cell is not None and not comma:
                raise InputError(f"engine curve file {path}, row {lineno}: {cell!r} is a number with thousands "
                                 f"separators ({cell.replace(',', '')}); write the numbers without thousands "
                                 "separators") from None
            raise InputError(f"engine curve file {path}, row {lineno}: expected numbers in columns "
                             f"{cells[i_rpm].strip()!r} and {cells[i_tq].strip()!r}, got {r}") from None
    top = next(((n, x) for (n, _), x in zip(rows, rpm) if x > MAX_ENGINE_RPM), None)
    if top is not None:
        raise InputError(f"engine curve file {path}, row {top[0]}: speed {top[1]:.6g} rpm is above "
                         f"{MAX_ENGINE_RPM:,.0f} rpm, faster than any engine this clutch fits (a typo, or a "
                         f"column in another unit?): correct that row")
    if encoding != "UTF-8":
        notes.append(f"read as {encoding} text")
    if delim != ",":
        notes.append(f"'{'tab' if delim == chr(9) else delim}'-separated" + (", decimal commas" if comma else ""))
    for what, canon in (("speed", "rpm"), ("torque", "N m")):
        u, f = units[what]
        if f != 1.0:
            notes.append(f"{what} read in {u}, converted to {canon}")
    return EngineTable(tuple(rpm), tuple(tq), units["speed"][0], units["torque"][0], tuple(notes))
