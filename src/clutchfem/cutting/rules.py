"""What a cutting process can make: kerf, smallest inside radius, slot and web, kerf error,
taper and tolerance, as one typed parameter set (:class:`ProcessRules`) shared by the API,
the command line (``--process``, ``--kerf``, ``--min-inside-radius``, ``--min-slot``,
``--min-web``) and the docs.

The defaults of each process are ASSUMED typical values for ~10 mm hardened steel plate, not
a shop's capability: give a shop's own numbers with the options.  Sources (retrieved 2026):

* **laser** (fibre, oxygen/nitrogen assist): kerf 0.13-0.38 mm (SMS Laser, "Laser cutting
  design rules"; 0.3 mm used); minimum slot and web 0.7 x the plate thickness (Acute Laser,
  "Minimum dimensions for laser cutting": hole diameter, web and slot width = 0.7 x
  thickness; other shops say 1 x thickness: tuanthinh.net "sheet metal hole and edge
  spacing rules"); cutting accuracy 0.1 mm at 0.5 mm up to 1.1 mm at 25 mm thickness (Acute
  Laser; +-0.3 mm used for ~10 mm); inside radius 0.25 mm (ASSUMED: the beam's half kerf
  plus margin).  A thermal process: its heat-affected zone (0.13-0.5 mm, SMS Laser) tempers
  a hardened flexure's surface -- cut before hardening, or choose wire EDM;
* **waterjet** (abrasive): kerf 0.030 in = 0.76 mm, taper 0.003-0.010 in (0.15 mm used), no
  inside radius under 0.02 in = 0.5 mm, tolerance +-0.005 in (metalcreature.com, "Design for
  waterjet"); +-0.05 mm "realistic" positioning (waterjets.org, "Waterjet machining
  tolerances", used as the kerf error); minimum slot 1.0 mm and web 1.0 mm ASSUMED (a slot
  must be wider than the kerf to be cut as a slot, a thin web chatters in the jet);
* **wire-edm** (0.25 mm brass wire): kerf 0.30-0.41 mm (0.33 mm used; industrialmonitordirect,
  "Wire EDM kerf width tolerance guide"); tolerances to +-0.005 mm and sharp inside corners
  only down to the wire radius plus spark gap (6cproto, "What is EDM machining"; 0.2 mm
  used); kerf error +-0.005 mm; minimum slot 0.4 mm and web 0.3 mm ASSUMED.

A slot narrower than the kerf cannot be cut, and no inside radius below half the kerf (the
tool's own radius): both are enforced whatever the user sets (:meth:`ProcessRules.check`).
"""

from __future__ import annotations

from typing import ClassVar, Literal

from ..core import ParameterError, ParamSet, choice, param

#: the processes with built-in (ASSUMED, sourced) rules
PROCESSES = ("laser", "waterjet", "wire-edm")


class ProcessRules(ParamSet):
    """The limits and errors of one cutting process (see module docstring for the sources).

    Parameters
    ----------
    process : {"laser", "waterjet", "wire-edm", "custom"}
        The process the defaults come from (``custom``: all given).
    kerf : float or str
        Width of the cut [m]; the tool path is offset by half of it.
    min_inside_radius, min_slot, min_web : float or str
        Smallest inside corner radius, slot width and web (material strip) width [m] the
        process cuts; ``min_slot_per_thickness``, ``min_web_per_thickness``: the same as a
        multiple of the plate thickness (the larger limit applies).
    kerf_error : float or str
        The process's kerf variation [m] (+-): the default as-cut error.
    taper : float or str
        Difference of the kerf width between the two faces [m] (waterjet).
    tolerance : float or str
        Profile tolerance of the cut contour [m] (+-), printed on the drawing.

    Examples
    --------
    >>> import clutchfem as cf
    >>> r = cf.ProcessRules.of("wire-edm", kerf="0.3mm")
    >>> r.kerf, r.min_inside_radius
    (0.0003, 0.0002)
    >>> r.limits(0.011)["min_slot"]
    0.0004
    """

    context: ClassVar[str] = "process rules"
    process: Literal["laser", "waterjet", "wire-edm", "custom"] = choice(
        "custom", "the cutting process the rules belong to")
    kerf: float = param(0.3e-3, "m", 0.01e-3, 5e-3, "kerf: width of the cut (tool path offset by half of it)")
    min_inside_radius: float = param(0.2e-3, "m", 0.0, 10e-3, "smallest inside corner radius the process cuts")
    min_slot: float = param(0.4e-3, "m", 0.0, 50e-3, "smallest slot width the process cuts")
    min_slot_per_thickness: float = param(0.0, "-", 0.0, 3.0, "smallest slot width as a multiple of the plate "
                                          "thickness (the larger of the two limits applies)")
    min_web: float = param(0.3e-3, "m", 0.0, 50e-3, "narrowest web (strip of material between cuts) the process "
                           "leaves flat and whole")
    min_web_per_thickness: float = param(0.0, "-", 0.0, 3.0, "narrowest web as a multiple of the plate thickness")
    kerf_error: float = param(0.02e-3, "m", 0.0, 1e-3, "kerf variation (+-) of the process: the as-cut error")
    taper: float = param(0.0, "m", 0.0, 1e-3, "kerf width difference between the two faces (waterjet taper)")
    tolerance: float = param(0.05e-3, "m", 0.0, 2e-3, "profile tolerance (+-) of the cut contour")

    def check(self) -> None:
        if self.min_inside_radius < 0.5 * self.kerf - 1e-12:
            self.fail("min_inside_radius", f">= half the kerf = {0.5 * self.kerf * 1e3:.3g} mm (the tool's own "
                                           "radius: no process cuts a smaller inside corner)")
        if self.min_slot < self.kerf - 1e-12:
            self.fail("min_slot", f">= the kerf = {self.kerf * 1e3:.3g} mm (a slot narrower than the cut "
                                  "cannot be cut)")

    @classmethod
    def of(cls, process: str = "custom", **overrides) -> "ProcessRules":
        """The rules of ``process`` (``laser``, ``waterjet``, ``wire-edm``; ``custom``: the
        class defaults) with some values changed (``kerf="0.3mm"``).  A kerf given without
        them lifts the smallest inside radius and slot to half the kerf and the kerf (the
        tool's own size); given explicitly below that, they are refused.  A ``min_slot`` or
        ``min_web`` given replaces the process's rule for it, its multiple of the thickness
        included (unless that is given too)."""
        if process not in PROCESSES + ("custom",):
            raise ParameterError("process", process, "one of " + ", ".join(repr(p) for p in PROCESSES + ("custom",)),
                                 cls.context)
        base = dict(DEFAULTS.get(process, {}))
        given = {k: v for k, v in overrides.items() if v is not None}
        if "kerf" in given:  # a wider kerf lifts the physical floors it implies, unless given
            k = cls.parse_value("kerf", given["kerf"]) if isinstance(given["kerf"], str) else float(given["kerf"])
            ref = cls()
            base["min_inside_radius"] = max(base.get("min_inside_radius", ref.min_inside_radius), 0.5 * k)
            base["min_slot"] = max(base.get("min_slot", ref.min_slot), k)
        for k in ("min_slot", "min_web"):  # a limit given is the limit: the process's thickness rule gives way
            if k in given and f"{k}_per_thickness" not in given:
                base[f"{k}_per_thickness"] = 0.0
        return cls(process=process, **{**base, **given})

    def check_kerf_error(self, kerf_error: float, context: str = "export") -> float:
        """``kerf_error`` [m] if an as-cut analysis can mean it: in [0, kerf) (the narrow
        variant cuts ``kerf - kerf_error`` wide: a cut of zero or negative width is no cut);
        else a :class:`~clutchfem.ParameterError` naming it (``context``: who asked).

        Examples
        --------
        >>> import clutchfem as cf
        >>> cf.ProcessRules.of("wire-edm").check_kerf_error(0.9e-3)
        Traceback (most recent call last):
        ...
        clutchfem.core.errors.ParameterError: export: parameter 'kerf_error' = 0.9 mm is not allowed: [0, 0.33 mm): below the kerf 0.33 mm of wire-edm (the narrow as-cut variant cuts kerf - error wide; a cut of zero or negative width is no cut)
        """
        if not 0.0 <= kerf_error < self.kerf:
            raise ParameterError("kerf_error", kerf_error, f"[0, {self.kerf * 1e3:g} mm): below the kerf "
                                 f"{self.kerf * 1e3:g} mm of {self.process} (the narrow as-cut variant cuts kerf - "
                                 "error wide; a cut of zero or negative width is no cut)", context,
                                 shown=f"{kerf_error * 1e3:g} mm")
        return kerf_error

    def limits(self, thickness: float) -> dict:
        """The effective limits [m] for a plate of ``thickness`` [m]: the larger of the
        absolute value and the thickness rule."""
        return {"min_inside_radius": self.min_inside_radius,
                "min_slot": max(self.min_slot, self.min_slot_per_thickness * thickness),
                "min_web": max(self.min_web, self.min_web_per_thickness * thickness)}

    def sources(self) -> str:
        """Where the defaults come from (one line for the drawing and the messages)."""
        return SOURCES.get(self.process, "given by the user")


#: built-in rules (ASSUMED typical values, sources in the module docstring)
DEFAULTS: dict[str, dict] = {
    "laser": {"kerf": 0.3e-3, "min_inside_radius": 0.25e-3, "min_slot": 0.5e-3, "min_slot_per_thickness": 0.7,
              "min_web": 0.5e-3, "min_web_per_thickness": 0.7, "kerf_error": 0.05e-3, "taper": 0.0,
              "tolerance": 0.3e-3},
    "waterjet": {"kerf": 0.76e-3, "min_inside_radius": 0.5e-3, "min_slot": 1.0e-3, "min_web": 1.0e-3,
                 "kerf_error": 0.05e-3, "taper": 0.15e-3, "tolerance": 0.13e-3},
    "wire-edm": {"kerf": 0.33e-3, "min_inside_radius": 0.2e-3, "min_slot": 0.4e-3, "min_web": 0.3e-3,
                 "kerf_error": 0.005e-3, "taper": 0.0, "tolerance": 0.01e-3},
}
SOURCES = {
    "laser": "ASSUMED typical fibre laser, ~10 mm steel (SMS Laser; Acute Laser: slot/web 0.7 x thickness)",
    "waterjet": "ASSUMED typical abrasive waterjet (metalcreature.com: kerf 0.76 mm, R >= 0.5 mm; waterjets.org)",
    "wire-edm": "ASSUMED typical wire EDM, 0.25 mm wire (kerf 0.30-0.41 mm; R >= wire radius + spark gap)",
}
