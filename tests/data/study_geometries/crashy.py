"""Test-only concept (tests/test_study_*.py, via CLUTCHFEM_GEOMETRIES): concept 4 with a
switch ``crash``: 1 kills the process inside the geometry build with SIGSEGV, as a gmsh
segfault does; 2 is a bug in the concept's checks (ZeroDivisionError, not a ClutchfemError).
"""

import os
import signal
from pathlib import Path

import clutchfem
from clutchfem.core import param
from clutchfem.geometry import load_concept_file

_C4 = load_concept_file(str(Path(clutchfem.__file__).resolve().parents[2] / "geometries" / "concept4.py"))


class CrashyParams(type(_C4).Params):
    context = "crashy"
    crash: int = param(0, "-", 0, 2, "test switch: 1 = SIGSEGV in the geometry build, 2 = ZeroDivisionError")

    def check(self):
        super().check()
        if self.crash == 2:
            1 / 0  # noqa: B018 - the bug under test


class Crashy(type(_C4)):
    name = "crashy"
    title = "test concept that crashes on purpose"
    Params = CrashyParams

    def build(self, p):
        if p.crash == 1:
            os.kill(os.getpid(), signal.SIGSEGV)
        return super().build(p)


CONCEPT = Crashy()
