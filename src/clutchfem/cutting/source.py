"""The design an export is made of, when it is not typed as CONCEPT --set: a run folder's
``inputs.json`` (``--from DIR``) or a study row (``--study DIR --row HASH``).

* ``inputs.json`` of ``clutchfem analyze/report/export`` holds the design itself
  (``concept``, ``params``, ``operating_point``, ``mesh_settings``); that of ``optimize`` its
  final design (``final_design``), of ``compensate`` the compensated one (``after``), of
  ``tolerance`` the nominal one (``nominal_design``).  The parameters are read back exactly
  (JSON keeps every float bit for bit), so the exported part is the very design the run
  analysed: its hash is checked against the recorded one when the record has it.
* a study's ``results.sqlite`` row (a prefix of its ``design_hash``, at least 6 hex digits,
  unique) gives the concept, the point's full parameter set and its operating point.
"""

from __future__ import annotations

import json
from pathlib import Path

from ..core import InputError, Material
from ..geometry import MeshSettings, get_concept
from ..loadcase import Design, OperatingPoint, design_hash
from ..studies import COLUMNS, STORE_NAME, ResultStore

#: where each run kind keeps its design in inputs.json
KEYS = ("final_design", "after", "nominal_design")


def _design(record: dict, where: str, mesh: MeshSettings | None) -> Design:
    if "concept" not in record or "params" not in record:
        raise InputError(f"{where}: no concept design in it (a --mesh part's record has no concept parameters)")
    c = get_concept(record["concept"])
    params = c.Params(**record["params"])
    op = dict(record.get("operating_point") or record.get("op") or {})
    for k in ("drum_radius", "thickness"):  # a concept's own geometry parameters
        op.pop(k, None)
    if isinstance(op.get("material"), dict):
        op["material"] = Material(**op["material"])
    ms = mesh or MeshSettings(**{**dict(record.get("mesh_settings") or record.get("mesh") or {}), "model": "sector"})
    return Design.from_concept(c, params, OperatingPoint(**op), ms)


def design_from_run(folder, mesh: MeshSettings | None = None) -> Design:
    """The design recorded in ``folder/inputs.json`` (see module docstring)."""
    folder = Path(folder)
    path = folder / "inputs.json" if folder.is_dir() else folder
    if not path.is_file():
        raise InputError(f"--from {folder}: no inputs.json there (a folder written by analyze --out, report, "
                         "optimize --out, compensate --out, tolerance --out or export)")
    try:
        doc = json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise InputError(f"--from {path}: not a readable JSON document ({exc})") from None
    record = next((doc[k] for k in KEYS if isinstance(doc.get(k), dict) and doc[k]), doc)
    d = _design(record, f"--from {path}", mesh)
    want = record.get("design_hash")
    if want and mesh is None and design_hash(d) != want:
        raise InputError(f"--from {path}: the design read back has hash {design_hash(d)}, the record says {want} "
                         "(written by another clutchfem version?)")
    return d


def design_from_study(folder, row: str, mesh: MeshSettings | None = None) -> Design:
    """The design of the study row whose design hash starts with ``row``."""
    folder = Path(folder)
    store = folder / STORE_NAME if folder.is_dir() else folder
    if not store.is_file():
        raise InputError(f"--study {folder}: no {STORE_NAME} there (the folder of a clutchfem study)")
    if len(row) < 6 or any(ch not in "0123456789abcdef" for ch in row.lower()):
        raise InputError(f"--row {row!r}: give at least 6 hex digits of the row's design_hash")
    with ResultStore(store, COLUMNS) as st:
        df = st.frame()
    hit = df[df["design_hash"].astype(str).str.startswith(row.lower())]
    if hit.empty:
        raise InputError(f"--row {row}: no row of {store} has a design_hash starting so")
    if hit["design_hash"].nunique() > 1:
        raise InputError(f"--row {row}: {hit['design_hash'].nunique()} rows match; give more digits ("
                         + ", ".join(sorted(hit["design_hash"].unique())[:5]) + ")")
    inputs = json.loads(hit.iloc[0]["inputs_json"])
    settings = inputs.get("settings") or {}
    record = {"concept": settings.get("concept"), "params": inputs.get("params"), "op": inputs.get("op"),
              "mesh": settings.get("mesh")}
    if not record["concept"] or not record["params"]:
        raise InputError(f"--row {row}: the row has no concept parameters (status {hit.iloc[0]['status']}; a "
                         "refused point or a --mesh study)")
    return _design(record, f"--study {store} --row {row}", mesh)
