"""App stage: the live design app in the browser (``clutchfem app``): a design panel whose
every change is analysed at once, the answers with their bands, the charts and the part at a
speed, compare, studies and downloads, on the same public API as the command line.

* :mod:`.session` -- one tab's design, its values and refusals, the two-pass analysis;
* :mod:`.figures` -- the part picture and the charts' options;
* :mod:`.page` -- the NiceGUI page and its handlers;
* :mod:`.server` -- :func:`serve_app`.
"""

from .server import serve_app
from .session import Control, DesignSession, Outcome

__all__ = ["Control", "DesignSession", "Outcome", "serve_app"]
