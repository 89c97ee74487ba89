"""The self-checks of a sweep (clutchfem.checks) against brute force."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from clutchfem.geometry import MeshSettings
from clutchfem.loadcase import Design, drum_intrusion


@pytest.fixture(scope="module")
def res():
    d = Design.from_concept("concept4", mesh=MeshSettings(size=2e-3))
    return d.sweep([0.0, 6000.0, 9000.0, 12000.0])


def _brute(res, nodes):
    """Deepest pass |x + u| - R_d over every node that is not a contact node, every state."""
    b = res.fields.fe_basis
    xd = np.concatenate([b.nodal_dofs[0], b.facet_dofs[0]])
    X = b.doflocs[:, xd]
    keep = ~np.isin(xd, nodes.dof_x)
    keep &= np.hypot(*X) < nodes.drum_radius - 0.5 * float(np.min(nodes.gap0, initial=0.0)) - 1e-12
    U = np.column_stack([res.fields.displacement(k) for k in range(res.fields.n)])
    r = np.hypot(X[0, keep][:, None] + U[xd[keep]], X[1, keep][:, None] + U[xd[keep] + 1]) - nodes.drum_radius
    i, j = np.unravel_index(int(np.argmax(r)), r.shape)
    return int(j), float(r[i, j]), (float(X[0, keep][i]), float(X[1, keep][i]))


def test_no_node_passes_the_real_drum(res):
    assert drum_intrusion(res)[1] <= 0 and _brute(res, res.contact.nodes)[1] <= 0


@pytest.mark.parametrize("depth", [2e-5, 3e-4, 2e-3])
def test_screened_intrusion_equals_brute_force(res, depth):
    """A drum made smaller (the contact nodes' own gaps kept) so that other nodes pass it by
    up to ``depth``: the screened search finds the same state, depth and node as checking
    every node."""
    nd = res.contact.nodes
    deepest = _brute(res, nd)[1] + nd.drum_radius  # the outermost non-contact node's |x + u|
    small = SimpleNamespace(drum_radius=deepest - depth, dof_x=nd.dof_x, gap0=nd.gap0)
    fake = SimpleNamespace(fields=res.fields, curve=res.curve, contact=SimpleNamespace(nodes=small))
    k, dep, where = drum_intrusion(fake)
    kb, db, wb = _brute(fake, small)
    assert dep > 0 and (k, where) == (kb, wb) and dep == pytest.approx(db, rel=1e-12)
    assert dep <= depth * (1 + 1e-9)  # (nodes already outside the smaller drum are not checked)
