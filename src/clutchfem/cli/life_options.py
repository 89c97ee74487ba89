"""The options of a life run shared by ``clutchfem life`` and ``clutchfem tolerance --life``:
the drive line's and Archard's values from their option strings, ``--rebuild-depth``."""

from __future__ import annotations

from .. import ParameterError
from .common import quantity

#: option -> field of DriveLine (the assumed inertias, loads and throttle ramp of a start)
DRIVE_OPTIONS = {"--engine-inertia": "engine_inertia", "--driven-inertia": "driven_inertia",
                 "--drag-torque": "drag_torque", "--cutting-torque": "cutting_torque",
                 "--throttle-ramp": "throttle_ramp"}
#: option -> field of WearParams (Archard's coefficients and the wear step)
WEAR_OPTIONS = {"--wear-regime": "regime", "--wear-coefficient": "wear_coefficient", "--hardness": "hardness",
                "--drum-wear-coefficient": "drum_wear_coefficient", "--drum-hardness": "drum_hardness",
                "--max-wear-step": "max_step", "--wear-rate-change": "rate_change"}


def life_given(o, rebuild: bool = False) -> dict:
    """The wear options of a command's shared namespace ``o`` (:data:`~.options.SHARED`) as
    option -> raw text (``rebuild``: ``--rebuild-depth`` too)."""
    attr = {"--max-wear-step": "max_wear_step", "--wear-rate-change": "wear_rate_change",
            "--wear-regime": "wear_regime"}
    out = {opt: getattr(o, attr.get(opt, field)) for opt, field in WEAR_OPTIONS.items()}
    if rebuild:
        out["--rebuild-depth"] = o.rebuild_depth
    return out


def params_from(cls, given: dict, options: dict):
    """``cls`` from the option strings ``given`` (option -> raw or None); a refusal names the
    option typed."""
    values = {}
    for opt, raw in given.items():
        if raw is None:
            continue
        name = options[opt]
        try:
            values[name] = cls.parse_value(name, raw)
        except ParameterError as exc:
            raise ParameterError(exc.name, raw, exc.allowed, f"option {opt}") from None
    try:
        return cls(**values)
    except ParameterError as exc:
        opt = next((o for o, n in options.items() if n == exc.name), None)
        raise ParameterError(exc.name, exc.value, exc.allowed, f"option {opt}" if opt else None,
                             shown=given.get(opt) or exc.shown) from None


def wear_from(given: dict):
    """The WearParams of the ``--wear-*`` options ``given`` (option -> raw or None)."""
    from .. import WearParams

    return params_from(WearParams, given, WEAR_OPTIONS)


def rebuild_from(raw: str | None) -> dict:
    """``--rebuild-depth`` as keywords of cf.life: {} (its default), or {"rebuild_depth": m or None}."""
    if raw is not None and raw.strip().lower() == "never":
        return {"rebuild_depth": None}
    d = quantity("--rebuild-depth", raw, "m", 1e-6, 1e-2)  # not given: cf.life's own default
    return {} if d is None else {"rebuild_depth": d}
