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
import logging
from pathlib import Path

from ..core import InputError, Material
from ..evaluation import COLUMNS, STORE_NAME, ResultStore
from ..geometry import MeshSettings, get_concept
from ..loadcase import Design, OperatingPoint, design_hash, model_version

#: where each run kind keeps its design in inputs.json
log = logging.getLogger("clutchfem")
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
    if op and "fidelity" not in op:  # a record from before issue 20: the uncorrected path it was computed on
        op["fidelity"] = "fast"
    point = OperatingPoint(**op)
    rec_ms = dict(record.get("mesh_settings") or record.get("mesh") or {})
    ms = mesh or (MeshSettings(**{**rec_ms, "model": "sector"}) if rec_ms
                  else MeshSettings.preset(point.fidelity, model="sector"))
    return Design.from_concept(c, params, point, ms)


def design_from_run(folder, mesh: MeshSettings | None = None) -> Design:
    """The design recorded in ``folder/inputs.json`` (see module docstring).

    Parameters
    ----------
    folder : path
        A run folder (``analyze --out``, ``report``, ``optimize``, ``compensate``,
        ``tolerance``, ``export``) or its ``inputs.json``.
    mesh : MeshSettings, optional
        Mesh it with these settings instead of the recorded ones (no hash check then).

    Returns
    -------
    Design
        The very design the run analysed (its hash is checked against the record's).

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> from clutchfem.loadcase import design_hash, design_inputs
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> run = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (run / "inputs.json").write_text(cf.dumps({**design_inputs(d), "design_hash": design_hash(d)}))
    >>> d2 = cf.design_from_run(run)                   # clutchfem export --from RUN
    >>> d2.name, design_hash(d2) == design_hash(d)
    ('concept1', True)
    """
    folder = Path(folder)
    path = folder / "inputs.json" if folder.is_dir() else folder
    if not path.is_file():
        raise InputError(f"--from {folder}: no inputs.json there (a folder written by analyze --out, report, "
                         "optimize --out, compensate --out, tolerance --out or export)")
    try:
        doc = json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise InputError(f"--from {path}: not a readable JSON document ({exc})") from None
    if not isinstance(doc, dict):
        raise InputError(f"--from {path}: not a run's record (a JSON object with the design's concept and "
                         f"parameters), but a JSON {type(doc).__name__}")
    record = next((doc[k] for k in KEYS if isinstance(doc.get(k), dict) and doc[k]), doc)
    d = _design(record, f"--from {path}", mesh)
    want = record.get("design_hash")
    if want and mesh is None and design_hash(d) != want:
        raise InputError(f"--from {path}: the design read back has hash {design_hash(d)}, the record says {want} "
                         "(written by another clutchfem version?)")
    return d


def design_from_study(folder, row: str, mesh: MeshSettings | None = None) -> Design:
    """The design of the study row whose design hash starts with ``row``.

    Parameters
    ----------
    folder : path
        A study's folder (its ``results.sqlite``) or the store itself.
    row : str
        At least 6 hex digits of the row's ``design_hash``, matching one row.
    mesh : MeshSettings, optional
        Mesh it with these settings instead of the study's.

    Returns
    -------
    Design
        The concept, the point's full parameter set and its operating point: the row's design
        hash under the row's model version (a row of another version is said with both hashes).

    Examples
    --------
    A store with one hand-written row (a study writes them; ``clutchfem export --study DIR --row HASH``):

    >>> import clutchfem as cf, tempfile, pathlib
    >>> from clutchfem.evaluation import COLUMNS, ResultStore
    >>> study = pathlib.Path(tempfile.mkdtemp())
    >>> inputs = {"settings": {"concept": "concept1", "mesh": {"size": 0.003}}, "params": {"flexure_thickness": 0.0022}}
    >>> with ResultStore(study / "results.sqlite", COLUMNS) as st:
    ...     st.put({"design_hash": "a1b2c3d4e5f6", "model_version": "v1", "status": "ok", "inputs_json": cf.dumps(inputs)})
    >>> d = cf.design_from_study(study, "a1b2c3")
    >>> d.name, d.params.flexure_thickness
    ('concept1', 0.0022)
    """
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
    hit = hit.assign(_now=hit["model_version"] != model_version(hit.iloc[0]["design"] or None)).sort_values("_now")
    want = str(hit.iloc[0]["design_hash"])  # (a row of this model version first)
    inputs = json.loads(hit.iloc[0]["inputs_json"])
    settings = inputs.get("settings") or {}
    record = {"concept": settings.get("concept"), "params": inputs.get("params"), "op": inputs.get("op"),
              "mesh": settings.get("mesh")}
    if not record["concept"] or not record["params"]:
        raise InputError(f"--row {row}: the row has no concept parameters (status {hit.iloc[0]['status']}; a "
                         "refused point or a --mesh study)")
    d = _design(record, f"--study {store} --row {row}", mesh)
    if mesh is None and d.hash != want:
        rv = hit.iloc[0]["model_version"]
        said = (f"--study {store} --row {row}: the design read back has hash {d.hash} (model version "
                f"{d.identity.model_version}), the row {want} (model version {rv})")
        if rv == d.identity.model_version:  # one design, one model: one hash, or the row is not this design
            raise InputError(said + ": the row's inputs do not rebuild its design (a store edited by hand?)")
        log.warning(said + ": the row was computed by another model version, the files carry this version's "
                    "hash (run the study again to bring its rows to this version)")
    return d
