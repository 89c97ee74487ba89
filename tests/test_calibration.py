"""Calibration to measured parts (issue 39): the inputs read, the posterior on a reduced model
(here fitted to rows made from known functions, so that the truth is known and no FE runs),
its coverage on synthetic parts, the check that says a measurement is not explained, the
Laplace approximation against emcee, and the refusals."""

from __future__ import annotations

import json

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.reduced import ReducedModel, Region
from support.cli import cli_in_process

DRAWN_T = 2.2e-3


def eng(t, mu):
    """The engagement speed [rpm]: a stiffer flexure engages later; mu plays no part."""
    return 4000.0 * (t / DRAWN_T) ** 1.5


def slip(t, mu):
    """The slip speed [rpm]: above the engagement, lower with more friction."""
    return eng(t, mu) * (1.0 + 0.2 / mu)


@pytest.fixture(scope="module")
def design():
    return cf.Design.from_concept("concept1", fidelity="live")


@pytest.fixture(scope="module")
def model(design):
    """A reduced model of (flexure_thickness, mu) fitted to 36 rows of the functions above and
    its error measured on 10 more (a Gaussian process on a smooth answer: well below 0.1 %)."""
    r = Region.around(design, free=["flexure_thickness", "mu"],
                      ranges={"flexure_thickness": ("2.0mm", "2.4mm"), "mu": (0.1, 0.35)})
    pts = np.random.default_rng(0).random((46, 2)) * [0.4e-3, 0.25] + [2.0e-3, 0.1]
    row = lambda p: {"status": "ok", "point_json": json.dumps(dict(zip(r.names, map(float, p)))),  # noqa: E731
                     "engagement_rpm": eng(*p), "engagement_err_rpm": 0.002 * eng(*p), "slip_rpm": slip(*p),
                     "slip_err_rpm": 0.002 * slip(*p)}
    m = ReducedModel.fit(r, [row(p) for p in pts[:36]])
    m.measure([row(p) for p in pts[36:]])
    return m


PRIORS = ["flexure_thickness=+-0.1mm", "mu=0.1:0.35"]


def measure(t, mu, rng, u_eng=20.0, u_slip=40.0):
    return [f"engagement={eng(t, mu) + rng.normal(0, u_eng):.1f}rpm+-{u_eng:g}rpm",
            f"slip={slip(t, mu) + rng.normal(0, u_slip):.1f}rpm+-{u_slip:g}rpm"]


def test_synthetic_parts_lie_in_their_intervals_and_the_intervals_are_narrower_than_the_priors(design, model):
    rng = np.random.default_rng(11)
    inside, total, narrowed = 0, 0, []
    for _ in range(5):
        t, mu = rng.normal(DRAWN_T, 0.1e-3 / 3), rng.uniform(0.12, 0.33)
        c = cf.calibrate(design, measure(t, mu, rng), PRIORS, model=model, steps=1500, seed=int(rng.integers(1000)))
        assert c.consistent, c.checks
        for name, truth in (("flexure_thickness", t), ("mu", mu)):
            p = c.posterior[name]
            assert p["identified"], (name, p)  # two measurements, two inputs: both identified here
            total += 1
            inside += p["ci95"][0] <= truth <= p["ci95"][1]
            narrowed.append(p["narrowed"])
    assert inside >= total - 1, (inside, total)  # 95 % intervals: at most one miss in ten
    assert min(narrowed) > 0.3


def test_the_posterior_says_what_the_data_do_not_identify_and_a_dimension_measured_is_data(design, model):
    # only the engagement: it says nothing of mu (the engagement does not depend on it)
    c = cf.calibrate(design, ["engagement=4100rpm+-20rpm"], PRIORS, model=model, steps=1500)
    assert not c.posterior["mu"]["identified"] and c.posterior["flexure_thickness"]["identified"]
    assert any("mu" in e and "NOT IDENTIFIED" in e for e in c.explanations)
    # a micrometer reading of the flexure narrows it beyond what the engagement does
    d = cf.calibrate(design, ["engagement=4100rpm+-20rpm", "flexure_thickness=2.25mm+-0.005mm"], PRIORS, model=model,
                     steps=1500)
    w = lambda x: x["ci95"][1] - x["ci95"][0]  # noqa: E731
    assert w(d.posterior["flexure_thickness"]) < w(c.posterior["flexure_thickness"])
    assert abs(d.posterior["flexure_thickness"]["mean"] - 2.25e-3) < 10e-6


def test_a_measurement_no_input_within_its_prior_explains_is_said_to_be_so(design, model):
    # +25 % engagement: a flexure thickness 4 sigma above the drawn one gives +8 %
    c = cf.calibrate(design, ["engagement=5000rpm+-20rpm", "slip=9000rpm+-40rpm"], PRIORS, model=model, steps=1500)
    assert not c.consistent
    chk = {x["measured"]: x for x in c.checks}
    assert not chk["engagement"]["explained"] and chk["engagement"]["z_best"] < -3
    assert any("NOT EXPLAINED: engagement=5000rpm" in n for n in c.notes)
    assert c.posterior["flexure_thickness"]["at_edge"] == "hi"
    assert c.explanations[0].startswith("no combination")


def test_laplace_agrees_with_emcee_where_the_posterior_is_near_gaussian(design, model):
    meas = measure(2.25e-3, 0.2, np.random.default_rng(3))
    a = cf.calibrate(design, meas, PRIORS, model=model, steps=3000)
    b = cf.calibrate(design, meas, PRIORS, model=model, method="laplace")
    assert b.info["gaussian"]
    for name in ("flexure_thickness", "mu"):
        pa, pb = a.posterior[name], b.posterior[name]
        assert abs(pa["mean"] - pb["mean"]) < 0.15 * pa["sd"], name
        assert pb["sd"] == pytest.approx(pa["sd"], rel=0.15), name


def test_the_json_and_the_pictures(design, model, tmp_path):
    from clutchfem.core.figures import figure_record

    c = cf.calibrate(design, measure(2.25e-3, 0.2, np.random.default_rng(4)), PRIORS, model=model, steps=1000)
    doc = json.loads(cf.dumps(c.to_json()))
    p = doc["posterior"]["flexure_thickness"]
    assert p["ci95"][0] < p["mean"] < p["ci95"][1] and 2.0e-3 < p["mean"] < 2.4e-3  # the value as built, in m
    assert doc["posterior"]["mu"]["prior"]["kind"] == "uniform" and doc["posterior"]["mu"]["prior"]["lo"] == 0.1
    a = doc["answers"]["slip_rpm"]
    assert a["ci95"][0] < a["mean"] < a["ci95"][1] and a["band"] > 0 and a["measured"] == c.measured[1].value
    paths = c.write_figures(tmp_path)
    assert [x.name for x in paths] == ["calibration_inputs.png", "calibration_answers.png"]
    rec = figure_record(paths[0])
    assert any("flexure_thickness as built [mm]" in ax.get("xlabel", "") for ax in rec["axes"])


@pytest.mark.parametrize("measured, uncertain, name", [
    (["engagement=4191rpm+-25rpm", "slip=4000rpm+-40rpm"], PRIORS, "slip"),       # slips before it engages
    (["engagement=4191rpm+-0rpm"], PRIORS, "engagement"),                           # no uncertainty
    (["engagement=4191+-25"], PRIORS, "engagement"),                                # fine: rpm is the default unit
    (["engagement=4191mm+-25rpm"], PRIORS, "engagement"),                           # a length for a speed
    (["stiffness=3N+-1N"], PRIORS, "stiffness"),                                    # not a measurement
    (["clearance=0.6mm+-0.01mm"], PRIORS, "clearance"),                             # a dimension not uncertain
    (["torque@6000rpm=5Nm+-0.1Nm"], PRIORS, "torque"),                              # not the model's speed
    (["engagement=4191rpm+-25rpm"], ["flexure_thickness=+-0mm"], "flexure_thickness"),
    (["engagement=4191rpm+-25rpm"], ["hub_magic=+-1mm"], "hub_magic"),
    (["engagement=4191rpm+-25rpm"], ["mu=0.3:0.2"], "mu"),
    (["engagement=4191rpm+-25rpm"], ["flexure_thickness=+-0.1mm", "flexure_thickness=+-0.2mm"], "flexure_thickness"),
    (["slip=7500rpm+-40rpm"], PRIORS + ["E=200GPa:220GPa"], "E"),                  # similarity moves the slip's speed
    (["engagement=4191rpm+-25rpm"], ["clearance=+-0.05mm"], "clearance"),           # not an axis of this model
])
def test_bad_inputs_are_refused_naming_the_input(design, model, measured, uncertain, name):
    if measured == ["engagement=4191+-25"]:  # a plain number is the field's unit (rpm): accepted
        cf.calibrate(design, measured, PRIORS, model=model, steps=1000)
        return
    with pytest.raises(cf.ParameterError) as e:
        cf.calibrate(design, measured, uncertain, model=model, steps=1000)
    assert e.value.name == name, str(e.value)


def test_e_and_density_enter_by_exact_similarity(design, model):
    """The engagement of a part of (E, rho) is the reference's times sqrt(E rho0 / (E0 rho))."""
    from clutchfem.calibration.inference import Forward
    from clutchfem.calibration.inputs import parse_uncertain

    U = [parse_uncertain(design, t) for t in ("flexure_thickness=+-0.1mm", "E=190GPa:230GPa", "density=7700:8000")]
    f = Forward(model, U, design)
    ans, ok = f(np.array([[2.2e-3, 210e9, 7850.0], [2.2e-3, 190e9, 8000.0]]), ["engagement_rpm"])
    assert ok.all()
    assert ans["engagement_rpm"][1] / ans["engagement_rpm"][0] == pytest.approx(np.sqrt(190 / 210 * 7850 / 8000),
                                                                                rel=1e-12)


def test_a_region_may_hold_mu_as_an_axis_and_its_key_says_so(design):
    r = Region.around(design, free=["flexure_thickness", "mu"], ranges={"mu": (0.1, 0.35)})
    assert r.bounds("mu") == (0.1, 0.35) and "mu 0.1..0.35" in r.describe()
    other = cf.Design.from_concept("concept1", fidelity="live", mu=0.3)
    same = Region.around(other, free=["flexure_thickness", "mu"], ranges={"mu": (0.1, 0.35),
                                                                          "flexure_thickness": r.bounds("flexure_thickness")})
    assert same.key() == r.key()  # the base's mu is not part of the key: it is an axis
    assert same.design_values(other)["mu"] == 0.3 and r.design_values(design)["mu"] == pytest.approx(0.165)
    assert Region.around(design, free=["flexure_thickness", "mu"], ranges={"mu": (0.1, 0.3)}).key() != r.key()
    assert all(0.1 <= p["mu"] <= 0.35 for p in r.sample(4))
    with pytest.raises(cf.ParameterError) as e:
        Region.around(design, free=["drum_wall"])  # a live design's drum is elastic; a rigid one has no wall
    assert e.value.name == "drum_wall" if design.op.drum_wall is None else True


def test_the_command_line_refuses_bad_measurements_before_any_work():
    for args, name in ((["--measured", "engagement=4191rpm+-25rpm", "--measured", "slip=4000rpm+-25rpm"], "slip"),
                       (["--measured", "engagement=4191rpm+-0rpm"], "engagement"),
                       (["--measured", "slip=7000rpm+-40rpm", "--torque-sd", "0.1Nm"], "torque_sd")):
        out = cli_in_process("calibrate", "concept1", *args, "--uncertain", "mu=0.1:0.35", ok=False)
        assert out.returncode != 0 and f"'{name}'" in out.stderr, out.stderr


@pytest.mark.slow
def test_the_command_line_calibrates_on_a_reduced_model_it_builds(tmp_path):
    """A tiny region of concept 1 on the fast path (3 mm mesh; 4 designs fitted, 2 held out:
    what is checked is the command building its model and calibrating on it, and over this
    small box the answers are near log-linear, so the trend and 4 designs hold them to
    4e-5 (engagement) and 1.3e-3 (slip) on the held-out ones; 6 designs cost 4 s of CPU
    more for the same posterior to 1 %): the JSON's posterior holds each input as built, SI;
    the corrected design and its cutting files.  1500 steps a walker (the default 5000 is for
    a user's posterior; the sampler's accuracy is the API tests' above, which run
    1000-3000): the command's CPU 22.6 s -> 17.1 s, and --steps reaches the run."""
    out = cli_in_process("calibrate", "concept1", "--fidelity", "fast", "--mesh-size", "3mm", "--n", "4",
                         "--held-out", "2", "--workers", "0", "--steps", "1500",
                         "--measured", "engagement=4000rpm+-30rpm",
                         "--measured", "slip=7500rpm+-60rpm", "--uncertain", "mu=0.15:0.2", "--uncertain",
                         "flexure_thickness=+-0.05mm", "--correct", "flexure_thickness", "--target",
                         "engagement=4000rpm", "--json", "--out", str(tmp_path), ok=True)
    doc = json.loads(out.stdout)
    k = doc["corrected"]  # the next part drawn so that, as built, it engages at the target
    lo, hi = k["answers"]["engagement_rpm"]["ci95"]
    assert k["met"] and lo <= 4000.0 <= hi and (tmp_path / "corrected" / f"{k['label']}.dxf").exists()
    ch = k["changes"]["flexure_thickness"]
    assert ch["as_built"] == pytest.approx(ch["corrected"] + ch["offset"])
    assert set(doc["posterior"]) == {"mu", "flexure_thickness"}
    t = doc["posterior"]["flexure_thickness"]
    assert 2.13e-3 < t["ci95"][0] < t["mean"] < t["ci95"][1] < 2.27e-3 and t["prior"]["kind"] == "normal"
    assert 0.15 <= doc["posterior"]["mu"]["ci95"][0] < doc["posterior"]["mu"]["ci95"][1] <= 0.2
    assert doc["answers"]["engagement_rpm"]["measured"] == 4000.0 and doc["info"]["region"]["free"]["mu"] == [0.15, 0.2]
    assert doc["info"]["method"] == "emcee" and doc["info"]["steps"] == 1500  # --steps reached the sampler
    assert (tmp_path / "calibration_inputs.png").exists() and (tmp_path / "calibration_answers.png").exists()


# -- the corrected design, several parts, repeated readings ---------------------------------
def test_the_corrected_design_draws_the_flexure_thinner_by_the_offset_and_its_part_meets_the_target(design, model):
    rng = np.random.default_rng(21)
    t_true, mu_true = 2.25e-3, 0.2  # the part came out 0.05 mm thick
    c = cf.calibrate(design, measure(t_true, mu_true, rng), PRIORS, model=model, steps=1500)
    k = cf.corrected_design(c, adjust=["flexure_thickness"], targets=["engagement=4000rpm"])
    ch = k.changes["flexure_thickness"]
    off = c.offsets["flexure_thickness"]
    assert off["ci95"][0] < t_true - DRAWN_T < off["ci95"][1] and ch["offset"] == pytest.approx(off["mean"])
    # engagement depends on the thickness alone: the target is the drawn thickness as built
    assert abs(ch["as_built"] - DRAWN_T) < 3e-6 and ch["corrected"] == pytest.approx(ch["plain"], abs=3e-6)
    assert k.met and k.answers["engagement_rpm"]["met"] and k.target_source == "given"
    # the true next part (drawn at the corrected value, the true offset, the true mu) lies in the bands
    nxt = ch["corrected"] + (t_true - DRAWN_T)
    for a, f in (("engagement_rpm", eng), ("slip_rpm", slip)):
        lo, hi = k.answers[a]["ci95"]
        assert lo <= f(nxt, mu_true) <= hi, (a, f(nxt, mu_true), lo, hi)
    assert k.answers["engagement_rpm"]["uncorrected"] == pytest.approx(eng(t_true, mu_true), rel=0.01)
    assert k.design.params.flexure_thickness == pytest.approx(ch["corrected"]) and k.set_args == [
        f"flexure_thickness={ch['corrected'] * 1e3:.6g}mm"]
    doc = json.loads(cf.dumps(k.to_json()))
    assert doc["changes"]["flexure_thickness"]["corrected"] == pytest.approx(ch["corrected"])


def test_the_default_targets_are_the_drawn_predictions_and_a_target_out_of_reach_is_said_to_be(design, model):
    c = cf.calibrate(design, measure(2.25e-3, 0.2, np.random.default_rng(5)), PRIORS, model=model, steps=1000)
    k = cf.corrected_design(c)  # every calibrated geometry input; the drawn design's predictions
    assert list(k.changes) == ["flexure_thickness"] and k.target_source == "the drawn design's prediction"
    assert set(k.targets) == {"engagement_rpm", "slip_rpm"}
    assert k.targets["engagement_rpm"] == pytest.approx(c.answers["engagement_rpm"]["nominal"])
    assert any("1 input(s) adjusted for 2 targets" in n for n in k.notes)
    far = cf.corrected_design(c, targets={"engagement_rpm": 6000.0})  # +50 %: the region ends at +9 %
    assert not far.met and not far.answers["engagement_rpm"]["met"]
    assert any(n.startswith("NOT REACHED: engagement_rpm") and "flexure_thickness at the bound" in n
               for n in far.notes)


@pytest.mark.parametrize("kw, name", [
    ({"adjust": ["mu"]}, "mu"),                                               # shared: not drawn
    ({"adjust": ["clearance"]}, "clearance"),                                 # not calibrated
    ({"adjust": []}, "correct"),
    ({"targets": ["stiffness=3N"]}, "stiffness"),
    ({"targets": ["engagement=4000mm"]}, "engagement"),
    ({"targets": ["engagement=-4000rpm"]}, "engagement"),
    ({"targets": ["engagement=4000rpm", "engagement=4100rpm"]}, "engagement_rpm"),
    ({"targets": ["engagement=5000rpm", "slip=4500rpm"]}, "slip"),          # slips before it engages
    ({"targets": ["torque=5Nm"]}, "torque_at_max_engine_torque_Nm"),          # not an answer of this model
])
def test_bad_corrections_are_refused_naming_the_option(design, model, kw, name):
    c = cf.calibrate(design, ["engagement=4100rpm+-20rpm"], PRIORS, model=model, method="laplace")
    with pytest.raises(cf.ParameterError) as e:
        cf.corrected_design(c, **kw)
    assert e.value.name == name, str(e.value)


def test_several_parts_share_mu_and_each_has_its_own_flexure(design, model, tmp_path):
    from clutchfem.core.figures import figure_record

    rng = np.random.default_rng(8)
    mu = 0.22
    parts = {"p1": 2.24e-3, "p2": 2.27e-3}
    meas = [f"{p}:{m}" for p, t in parts.items() for m in measure(t, mu, rng)]
    c = cf.calibrate(design, meas, PRIORS, model=model, steps=2000)
    assert c.parts == ["p1", "p2"] and c.consistent
    assert set(c.posterior) == {"mu", "flexure_thickness[p1]", "flexure_thickness[p2]"}
    # one calibration (a single 95 % interval may miss: coverage is the first test's), each truth
    # within 3 sd; each part's flexure as that part's own calibration finds it
    for p, t in parts.items():
        post = c.posterior[f"flexure_thickness[{p}]"]
        assert abs(post["mean"] - t) < 3 * post["sd"], (p, post)
        alone = cf.calibrate(design, [m.split(":", 1)[1] for m in meas if m.startswith(p + ":")], PRIORS, model=model,
                             steps=2000)
        assert abs(post["mean"] - alone.posterior["flexure_thickness"]["mean"]) < 0.5 * post["sd"]
        # one part's data alone leave mu wider than two parts' that share it
        w = lambda x: x["ci95"][1] - x["ci95"][0]  # noqa: E731
        assert w(c.posterior["mu"]) < w(alone.posterior["mu"])
        assert c.answers[f"engagement_rpm[{p}]"]["measured"] == c.measured[[m.part for m in c.measured].index(p)].value
    assert abs(c.posterior["mu"]["mean"] - mu) < 3 * c.posterior["mu"]["sd"]
    off = c.offsets["flexure_thickness"]
    dev = [c.posterior[f"flexure_thickness[{p}]"]["mean"] - DRAWN_T for p in parts]
    assert off["parts"] == 2 and off["mean"] == pytest.approx(np.mean(dev), rel=1e-9)
    k = cf.corrected_design(c, targets=["engagement=4000rpm"])
    assert k.changes["flexure_thickness"]["offset"] == pytest.approx(off["mean"])
    rec = figure_record(c.write_figures(tmp_path)[1])  # the answers per part, each with its measurement
    assert sum("(p2)" in ax["title"] for ax in rec["axes"]) == 2
    # a slip of one part below another part's engagement is no contradiction; unnamed with named is refused
    cf.check_measurements([cf.parse_measured("p1:slip=4300rpm+-40rpm"), cf.parse_measured("p2:engagement=4400rpm+-9rpm"),
                           cf.parse_measured("p1:engagement=4000rpm+-9rpm")])
    with pytest.raises(cf.ParameterError) as e:
        cf.calibrate(design, ["p1:engagement=4100rpm+-20rpm", "slip=7000rpm+-40rpm"], PRIORS, model=model, steps=1000)
    assert e.value.name == "measured" and "PART:" in str(e.value)


def test_repeated_readings_of_one_part_enter_once_with_the_model_error(design, model):
    from clutchfem.calibration import combine_readings

    reads = ["slip=7500rpm+-40rpm", "slip=7540rpm+-40rpm", "slip=7520rpm+-40rpm", "slip=7510rpm+-40rpm"]
    ms, notes = combine_readings([cf.parse_measured(t) for t in reads])
    assert len(ms) == 1 and ms[0].readings == 4 and ms[0].sd == pytest.approx(20.0) and not notes
    assert ms[0].value == pytest.approx(np.mean([7500, 7540, 7520, 7510]))
    c4 = cf.calibrate(design, ["engagement=4100rpm+-20rpm", *reads], PRIORS, model=model, method="laplace")
    c1 = cf.calibrate(design, ["engagement=4100rpm+-20rpm", f"slip={ms[0].value}rpm+-20rpm"], PRIORS, model=model,
                      method="laplace")
    assert c4.posterior["mu"]["sd"] == pytest.approx(c1.posterior["mu"]["sd"], rel=0.05)
    assert [ch["readings"] for ch in c4.checks] == [1, 4]
    _, bad = combine_readings([cf.parse_measured(t) for t in ("slip=7500rpm+-10rpm", "slip=7700rpm+-10rpm")])
    assert bad and "disagree beyond their uncertainties" in bad[0]


def test_the_command_line_writes_the_corrected_design_and_its_cutting_files(design, model, tmp_path, monkeypatch):
    """The calibration itself on the hand-fitted model (the CLI's own reduced model is the slow
    test's): ``--correct all --target ... --process ... --out ... --json``.  The two runs
    calibrate on the same measurements and priors: the second (the table) is given the
    first's calibration (the same seed: the same posterior), not the same sampling again."""
    real, done = cf.calibrate, {}

    def calibrate(d, meas, unc, **kw):
        key = (tuple(meas), tuple(unc))
        if key not in done:
            done[key] = real(design, meas, unc, model=model, steps=1000)
        return done[key]

    monkeypatch.setattr(cf, "calibrate", calibrate)
    meas = measure(2.25e-3, 0.2, np.random.default_rng(6))
    out = cli_in_process("calibrate", "concept1", "--fidelity", "live", "--measured", meas[0], "--measured", meas[1],
                         *[x for p in PRIORS for x in ("--uncertain", p)], "--correct", "all", "--target",
                         "engagement=4000rpm", "--process", "wire-edm", "--json", "--out", str(tmp_path), ok=True)
    doc = json.loads(out.stdout)
    k = doc["corrected"]
    assert k["met"] and k["targets"] == {"engagement_rpm": 4000.0}
    assert abs(k["changes"]["flexure_thickness"]["as_built"] - DRAWN_T) < 3e-6
    names = sorted(p.suffix for p in (tmp_path / "corrected").iterdir())
    assert ".dxf" in names and ".step" in names and k["label"] in {p.stem for p in (tmp_path / "corrected").iterdir()}
    text = cli_in_process("calibrate", "concept1", "--fidelity", "live", "--measured", meas[0], "--measured", meas[1],
                          *[x for p in PRIORS for x in ("--uncertain", p)], "--correct", "flexure_thickness", ok=True)
    assert "the corrected design for the next part" in text.stdout and "--set flexure_thickness=" in text.stdout
    assert len(done) == 1  # both runs asked for the one calibration


def test_the_command_line_refuses_bad_correction_options_before_any_work():
    base = ("calibrate", "concept1", "--measured", "engagement=4191rpm+-25rpm", "--uncertain", "mu=0.1:0.35")
    for args, name in ((["--target", "engagement=4000rpm"], "target"),
                       (["--correct", "all", "--process", "plasma", "--out", "x"], "process"),
                       (["--correct", "all", "--process", "laser"], "process"),   # without --out
                       (["--correct", "all", "--process", "waterjet"], "process"),
                       (["--correct", "all", "--target", "slip=4000mm"], "slip"),
                       (["--measured", "p1:slip=4000rpm+-25rpm", "--measured", "p1:engagement=4191rpm+-25rpm"],
                        "slip"),
                       (["--correct", "bogus"], "correct"),  # not an uncertain input: refused, no model built
                       (["--correct", "mu"], "correct")):  # an operating input is not drawn
        out = cli_in_process(*base, *args, ok=False)
        assert out.returncode != 0 and f"'{name}'" in out.stderr, (args, out.stderr)
