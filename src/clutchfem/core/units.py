"""Unit helpers.  SI inside clutchfem; rpm is accepted and shown where designers expect it."""

from __future__ import annotations

import math

import numpy as np

RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)


def rpm_to_rad_s(rpm):
    """Angular speed in rpm -> rad/s (works on floats and numpy arrays)."""
    if np.ndim(rpm):
        return np.asarray(rpm, dtype=float) / RPM_PER_RAD_S
    return float(rpm) / RPM_PER_RAD_S


def rad_s_to_rpm(omega):
    """Angular speed in rad/s -> rpm (works on floats and numpy arrays)."""
    if np.ndim(omega):
        return np.asarray(omega, dtype=float) * RPM_PER_RAD_S
    return float(omega) * RPM_PER_RAD_S


def mm(x: float) -> float:
    """Millimetres -> metres (for readable defaults: ``mm(34.4)``)."""
    return x * 1e-3


def deg(x: float) -> float:
    """Degrees -> radians."""
    return math.radians(x)


def wrap_angle(a, ref: float = 0.0):
    """Angle(s) [rad] shifted by whole turns into [ref - pi, ref + pi): the one place where
    polar angles are unwrapped (around a shoe, a pivot ray, a mean direction)."""
    out = ref + (np.asarray(a, dtype=float) - ref + math.pi) % (2 * math.pi) - math.pi
    return float(out) if np.ndim(out) == 0 else out
