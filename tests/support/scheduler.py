"""A `dask scheduler --scheduler-file` process's address, read once its file is whole."""

from __future__ import annotations

import json
import time
from pathlib import Path


def scheduler_address(path: Path, proc, timeout: float = 60.0) -> str:
    """The address in the scheduler file ``path`` of ``proc`` (a ``dask scheduler`` process).
    Dask creates the file, then writes it: a file that is there but not yet a whole JSON
    document with an address is read again (a reader that took the first existing file read
    an empty one, now and then, on a busy machine)."""
    t0 = time.time()
    while time.time() - t0 < timeout:
        if proc.poll() is not None:
            raise RuntimeError(f"the dask scheduler exited ({proc.returncode}) before writing {path}")
        try:
            return json.loads(path.read_text())["address"]
        except (FileNotFoundError, json.JSONDecodeError, KeyError):
            time.sleep(0.1)
    raise RuntimeError(f"no scheduler address in {path} after {timeout:.0f} s")
