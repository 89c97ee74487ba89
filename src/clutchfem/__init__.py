"""clutchfem: FEM toolkit for one-piece compliant centrifugal clutches."""

__version__ = "0.1.0"
