"""Contact stage: the contact nodes on the exact drum circle, the drum as a load-case part
(friction, condensed compliance), the small contact LCP and the elastic drum ring (with the
annulus it is verified against)."""

from .annulus import annulus_harmonic_compliance
from .arc import EDGE_COMPLIANCE, END_ERROR, arc_error_deg, contact_ends, contact_modulus, signed_gap
from .drum import MAX_SMOOTHING, Compliance, DrumContact
from .lcp import lazy, lcp_residual, smooth_lcp, solve_lcp
from .nodes import ContactNodes, build_contact_nodes, check_drum_radius, contact_nodes
from .ring import DrumWall, RingDrum, lame_free_ring_expansion

__all__ = ["EDGE_COMPLIANCE", "END_ERROR", "arc_error_deg", "contact_ends", "contact_modulus", "signed_gap",
           "Compliance", "ContactNodes", "DrumContact", "DrumWall", "RingDrum", "annulus_harmonic_compliance",
           "build_contact_nodes", "check_drum_radius", "contact_nodes", "lame_free_ring_expansion", "lazy",
           "lcp_residual", "smooth_lcp", "solve_lcp", "MAX_SMOOTHING"]
