"""The duty cycle of a saw over its life (:class:`DutyCycle`): starts per hour, held-drum slips
and the share of starts made in the cut, from options or a TOML file (:meth:`DutyCycle.from_toml`).

ASSUMED defaults (a professional saw; no source gives a duty cycle of a chainsaw clutch):
20 starts an hour (a start every 3 minutes of felling and limbing), 2 held-drum slips an hour
of 1 s each (the chain brake applied or the chain pinched with the throttle open: the
thesis's slip test in short), 10 % of the starts made in the cut (the load of a start is
then the cutting torque of :class:`~clutchfem.durability.DriveLine`, else the chain's drag).

A TOML file holds one table ``[duty]`` whose values are numbers in the field's unit or
strings with a unit suffix of the field's dimension (``starts_per_hour = "20 1/h"``,
``held_slip_duration = "1 s"``); a value in another dimension (``"1 mm"``) or an unknown
key is refused, naming the key, the value and what is allowed.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import ClassVar

from ..core import InputError, ParameterError, ParamSet, param

__all__ = ["DutyCycle"]


class DutyCycle(ParamSet):
    """How the saw is used over its life (ASSUMED defaults: module :mod:`clutchfem.lifetime.duty`).

    Parameters
    ----------
    starts_per_hour : float or str
        Engagements from idle per running hour [1/h].
    held_slips_per_hour : float or str
        Slips with the drum held at full throttle per hour [1/h].
    held_slip_duration : float or str
        Duration of one held-drum slip [s].
    cutting_share : float
        Share of the starts made in the cut (0..1).

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.DutyCycle(starts_per_hour="0.5 1/min")
    >>> d.starts_per_hour, d.held_slips_per_start
    (30.0, 0.06666666666666667)
    >>> cf.DutyCycle(held_slip_duration="1 mm")
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: duty cycle: parameter 'held_slip_duration' = '1 mm' is not allowed: a time in s ...
    """

    context: ClassVar[str] = "duty cycle"
    starts_per_hour: float = param(20.0, "1/h", 0.01, 3600.0, "engagements from idle per running hour (ASSUMED: "
                                   "a start every 3 min)", "n_s")
    held_slips_per_hour: float = param(2.0, "1/h", 0.0, 3600.0, "slips with the drum held at full throttle per "
                                       "hour (chain brake or pinched chain; ASSUMED)", "n_h")
    held_slip_duration: float = param(1.0, "s", 0.0, 60.0, "duration of one held-drum slip (ASSUMED)", "t_h")
    cutting_share: float = param(0.1, "-", 0.0, 1.0, "share of the starts made in the cut (ASSUMED)", "c_cut")

    @property
    def held_slips_per_start(self) -> float:
        return self.held_slips_per_hour / self.starts_per_hour

    def hours(self, starts):
        """Running hours [h] of ``starts`` starts."""
        return starts / self.starts_per_hour

    @classmethod
    def from_toml(cls, path) -> "DutyCycle":
        """The duty cycle of a TOML file's ``[duty]`` table (module docstring)."""
        p = Path(path)
        if not p.is_file():
            raise InputError(f"duty file {p}: not found (a TOML file with a [duty] table)")
        try:
            doc = tomllib.loads(p.read_text(encoding="utf-8"))
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
            raise InputError(f"duty file {p}: not valid TOML ({exc})") from None
        extra = sorted(set(doc) - {"duty"})
        if "duty" not in doc or not isinstance(doc["duty"], dict) or extra:
            raise InputError(f"duty file {p}: expected one table [duty] with the keys "
                             f"{', '.join(cls.model_fields)}" + (f" (unknown: {', '.join(extra)})" if extra else ""))
        values = {}
        for k, v in doc["duty"].items():
            if isinstance(v, bool) or not isinstance(v, (int, float, str)):
                raise ParameterError(k, v, "a number or a text with its unit, e.g. \"20 1/h\"", f"duty file {p}")
            values[k] = v
        try:
            return cls(**values)
        except ParameterError as exc:
            raise ParameterError(exc.name, exc.value, exc.allowed, f"duty file {p}", shown=exc.shown) from None
