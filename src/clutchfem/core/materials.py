"""Isotropic linear-elastic materials (SI units) and a small library.

Values: 51CrV4 / SS 2230 spring steel from the thesis (E = 210 GPa, rho = 7850 kg/m^3,
Rp0.2 = 1250 MPa hardened to ~45 HRC; nu = 0.3 is *assumed*).  Titanium and aluminium are
typical handbook values for Ti-6Al-4V and 7075-T6 (the thesis only says titanium has about
half the density and modulus of steel).
"""

from __future__ import annotations

from typing import ClassVar

from .errors import ParameterError
from .params import ParamSet, param


class Material(ParamSet):
    """An isotropic linear-elastic material.

    Parameters
    ----------
    name : str
    E : float or str
        Young's modulus (``"210GPa"``).
    nu : float
        Poisson's ratio.
    rho : float or str
        Density [kg/m^3].
    yield_strength : float or str
        Rp0.2, for the safety factors (``"1250MPa"``).

    Examples
    --------
    >>> import clutchfem as cf
    >>> m = cf.Material(name="my steel", E="200GPa", rho=7800, yield_strength="1100MPa")
    >>> m.E, m.lame_plane_stress()[1] == m.E / (2 * (1 + m.nu))
    (200000000000.0, True)
    """

    context: ClassVar[str] = "material"
    name: str = "user"
    E: float = param(210e9, "Pa", 1e6, 1e13, "Young's modulus")
    nu: float = param(0.3, "-", 0.0, 0.499, "Poisson's ratio")
    rho: float = param(7850.0, "kg/m^3", 1.0, 1e5, "density")
    yield_strength: float = param(1250e6, "Pa", 1e5, 1e11, "yield strength Rp0.2 (for safety factors)")

    def lame_plane_stress(self) -> tuple[float, float]:
        """Plane-stress Lame pair (lambda*, mu) = (E nu / (1 - nu^2), E / (2 (1 + nu))).

        Computed here on purpose: skfem's ``plane_stress`` helper changed meaning between
        releases."""
        return self.E * self.nu / (1.0 - self.nu ** 2), self.E / (2.0 * (1.0 + self.nu))

    def lame_plane_strain(self) -> tuple[float, float]:
        """Plane-strain (3-D) Lame pair (lambda, mu) = (E nu / ((1 + nu)(1 - 2 nu)), E / (2 (1 + nu)))."""
        return (self.E * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu)),
                self.E / (2.0 * (1.0 + self.nu)))


LIBRARY: dict[str, Material] = {
    "51CrV4": Material(name="51CrV4 (SS 2230) spring steel, hardened ~45 HRC", E=210e9, nu=0.3,
                       rho=7850.0, yield_strength=1250e6),
    "titanium": Material(name="Ti-6Al-4V", E=114e9, nu=0.34, rho=4430.0, yield_strength=880e6),
    "aluminium": Material(name="7075-T6 aluminium", E=71.7e9, nu=0.33, rho=2810.0, yield_strength=503e6),
}
ALIASES = {"ss2230": "51CrV4", "steel": "51CrV4", "51crv4": "51CrV4", "ti": "titanium",
           "ti6al4v": "titanium", "aluminum": "aluminium", "al": "aluminium", "7075": "aluminium"}


def get_material(name: str) -> Material:
    """A material of the library by name.

    Parameters
    ----------
    name : str
        ``"51CrV4"`` (alias steel, SS2230), ``"titanium"`` (Ti-6Al-4V), ``"aluminium"`` (7075-T6).

    Returns
    -------
    Material

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.get_material("steel").yield_strength
    1250000000.0
    """
    key = name.strip()
    key = ALIASES.get(key.lower().replace("-", "").replace(" ", ""), key)
    if key not in LIBRARY:
        raise ParameterError("material", name, "one of " + ", ".join(LIBRARY) + " (or give E, nu, rho)")
    return LIBRARY[key]
