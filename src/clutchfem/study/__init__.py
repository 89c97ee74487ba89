"""Studies: parametric sweeps on Dask and design guidelines.

* :mod:`.spec`: a TOML sweep spec -> validated :class:`~.spec.SweepSpec` -> points;
* :mod:`.point`: one point -> one row (the only module that calls the analysis);
* :mod:`.hashing`: the design hash that keys a row in the store;
* :mod:`.store`: the SQLite (WAL) result store, written as each point finishes;
* :mod:`.runner`: scheduling on a local or remote ``dask.distributed`` cluster, resume,
  progress, summary;
* :mod:`.charts`: answers vs inputs with requirement limits, parallel coordinates;
* :mod:`.guidelines`: elasticities with a step-stability check, one-at-a-time sweeps.
"""

from .point import COLUMNS, Settings, evaluate, model_version
from .spec import EXAMPLE_SPEC, SpecError, SweepSpec, load_spec, parse_spec

__all__ = ["COLUMNS", "EXAMPLE_SPEC", "Settings", "SpecError", "SweepSpec", "evaluate", "load_spec",
           "model_version", "parse_spec"]
