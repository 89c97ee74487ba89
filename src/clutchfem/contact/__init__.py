"""Contact stage: the contact nodes on the exact drum circle, the drum as a load-case part
(friction, condensed compliance), the small contact LCP and the elastic drum ring."""

from .drum import Compliance, DrumContact
from .lcp import lazy, lcp_residual, solve_lcp
from .nodes import ContactNodes, build_contact_nodes, check_drum_radius, contact_nodes
from .ring import DrumWall, RingDrum

__all__ = ["Compliance", "ContactNodes", "DrumContact", "DrumWall", "RingDrum", "build_contact_nodes",
           "check_drum_radius", "contact_nodes", "lazy", "lcp_residual", "solve_lcp"]
