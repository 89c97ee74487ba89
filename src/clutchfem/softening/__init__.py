"""Softening stage: spin softening and the centrifugal pre-stress stiffening as
interchangeable strategies behind ``bind(model, contact)`` (:mod:`.strategies`), on
load-dependent Ritz spaces (:mod:`.krylov`) with one response interface (:mod:`.response`)."""

from .krylov import KrylovSpace, divergence_omega, krylov_blocks, krylov_seeds, krylov_space, ritz_pairs
from .prestress import PrestressedModel, PrestressRitz, prestressed
from .response import POLE_BAND, ExactResponse, ModalResponse, model_compliance
from .strategies import SOFTENINGS, Exact, Off, PrestressExact, Ritz, Softening, get_softening

__all__ = ["POLE_BAND", "SOFTENINGS", "Exact", "ExactResponse", "KrylovSpace", "ModalResponse", "Off",
           "PrestressExact", "PrestressRitz", "PrestressedModel", "Ritz", "Softening", "divergence_omega", "get_softening",
           "krylov_blocks", "krylov_seeds", "krylov_space", "model_compliance", "prestressed", "ritz_pairs"]
