"""Cutting stage: from a design to the part a cutter makes, and back.

* :mod:`.outline` -- the whole part's exact outline from the OCC model (lines, arcs,
  B-splines; closed loops; zones);
* :mod:`.rules` -- what a process can cut (:class:`ProcessRules`: kerf, smallest inside
  radius, slot, web, kerf error, taper, tolerance; ASSUMED defaults with sources);
* :mod:`.features` -- the inside radii, slots and webs measured on the part, the check
  against the rules (:class:`CuttingError`);
* :mod:`.ligament` -- the thinnest section of the part and where it is;
* :mod:`.dimensions` -- what the workshop drawing dimensions, from the outline;
* :mod:`.offset` -- offset outlines: the kerf-compensated tool path, the as-cut part;
* :mod:`.ascut` -- the as-cut variants analysed like any part;
* :mod:`.dxf`, :mod:`.step`, :mod:`.sheet` -- the DXF, STEP and workshop-drawing writers;
* :mod:`.source` -- the design of a run folder (``inputs.json``) or a study row;
* :mod:`.export` -- :func:`export` (``cf.export``, ``clutchfem export``).

The package is named for the stage (cutting a part), and the entry point ``cf.export`` for
what the user does: a package ``export/`` would have shadowed the public function.
"""

from .ascut import as_cut, variants
from .dimensions import Dimension, dimensions
from .export import ExportResult, export
from .features import CuttingError, Feature, check, measure
from .ligament import Ligament, thinnest_ligament
from .offset import offset_loop, offset_loops
from .outline import PartOutline, part_outline
from .rules import PROCESSES, ProcessRules
from .source import design_from_run, design_from_study
from .step import write_step

__all__ = ["PROCESSES", "CuttingError", "Dimension", "ExportResult", "Feature", "Ligament", "PartOutline",
           "ProcessRules", "as_cut", "check", "design_from_run", "design_from_study", "dimensions", "export", "measure",
           "offset_loop", "offset_loops", "part_outline", "thinnest_ligament", "variants", "write_step"]
