"""The thesis' printed gains G3, G5 as the controllers ``printed-g3``, ``printed-g5`` of a heave
scene, and the shipped ``problems/heave/ex_6_2_6.toml`` (Huang 1992, 004 sections 6.2.4-6.2.6,
eqs. (6.6), (6.13)-(6.14); Figs. 6.10, 6.14-6.17)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.cli import main
from cable_ocp.errors import CableOCPError
from cable_ocp.heave import regulator as rg
from cable_ocp.heave.printed import printed_gain, printed_run
from cable_ocp.scene.heave import PRINTED_CONTROLLERS, load_scene, scene_from_dict

ROOT = Path(__file__).resolve().parents[2]
EX = ROOT / "problems" / "heave" / "ex_6_2_6.toml"
ROWS = {"passive": "uncontrolled", "printed-g3": "G3", "printed-g5": "G5"}


def test_file_is_the_library_regulator_scene() -> None:
    # The shipped file and cable_ocp.heave.regulator.regulator_scene (what simulate_printed
    # runs) describe the same sea, unit, winch, sample and record: every field equal.
    sc = load_scene(EX)
    lib = rg.regulator_scene(0.0)
    for table in ("sea", "vessel", "winch", "unit", "simulation"):
        assert getattr(sc, table) == getattr(lib, table), table
    assert sc.controller.sample_time == lib.controller.sample_time
    assert sc.controller.controllers == tuple(ROWS)


@pytest.mark.parametrize("name", list(PRINTED_CONTROLLERS))
def test_scene_delays_are_the_gains_design_delays(name: str) -> None:
    # scene/heave.py cannot import heave/: its table of design delays is checked here
    # against the gains' (G3: none, (6.6); G5: 0.2 s, Fig. 6.17). Exact: the same literal.
    assert PRINTED_CONTROLLERS[name] == printed_gain(name).tau
    # and the run uses that delay, whatever the scene's [winch] delay (for the others)
    sc = load_scene(EX, {"winch.delay": 0.3})
    sc_run, ctrl, status, message = printed_run(sc, name)
    assert sc_run.winch.delay == printed_gain(name).tau and sc.winch.delay == 0.3
    assert ctrl.name == name and status == "solved"
    assert f"winch delay {printed_gain(name).tau:g} s" in message


@pytest.fixture(scope="module")
def cli_run(tmp_path_factory: pytest.TempPathFactory) -> dict:
    out = tmp_path_factory.mktemp("ex626") / "out.json"
    csv = out.with_suffix(".csv")
    rc = main(["heave", str(EX), "--duration", "60", "--json", str(out), "--csv", str(csv),
               "--quiet"])
    assert rc == 0
    data = json.loads(out.read_text())
    data["csv_header"] = csv.read_text().splitlines()[0]
    return data


def test_cli_equals_the_library_regulator_run(cli_run: dict) -> None:
    # `cable-ocp heave ex_6_2_6.toml` against cable_ocp.heave.regulator.simulate_printed on
    # the same seed, record and window (60 s, the first 30 s left out): the same record, the
    # same RK4 and controllers through the one closed loop, so the RMS agree to round-off
    # (1e-12 relative: the sums over the window may be taken in another order).
    lib = rg.stated_numbers(rg.simulate_printed(duration=60.0, warmup=30.0))
    ctrl = cli_run["controllers"]
    assert list(ctrl) == list(ROWS)
    for row, key in ROWS.items():
        assert ctrl[row]["status"] == "solved"
        assert ctrl[row]["heave_rms"] == pytest.approx(lib[key]["heave_rms"], rel=1e-12)
    for row, key in (("printed-g3", "G3"), ("printed-g5", "G5")):
        assert ctrl[row]["reduction_pct"] == pytest.approx(lib[key]["reduction_pct"],
                                                           rel=1e-10)
    # the energy index is the Frobenius norm of the printed gain: sqrt(J_c (6.18))
    assert ctrl["printed-g5"]["energy_index"] == pytest.approx(np.sqrt(lib["G5"]["J_c"]),
                                                               rel=1e-12)
    assert "winch delay 0.2 s" in ctrl["printed-g5"]["message"]
    assert "printed-g5_unit_heave [m]" in cli_run["csv_header"]


def test_g5_sampled_too_slowly_is_unstable_and_the_run_confirms_it() -> None:
    # G5's loop on the true 0.2 s delay has a lightly damped pair near 11.5 rad/s
    # (test_thesis_gains); held over 50 ms samples the sampled loop's spectral radius is
    # 1.012 > 1: the design check says "unstable", and the simulated unit leaves the bound
    # (an independent check, the run itself). G3 at 50 ms stays stable and solved.
    from cable_ocp.heave import compare

    sc = load_scene(EX, {"controller.sample_time": 0.05, "simulation.substeps": 5,
                         "simulation.duration": 60.0})
    res = compare(sc)
    assert res.statuses["printed-g3"] == "solved"
    assert res.statuses["printed-g5"] == "unstable"
    assert "spectral radius 1.01" in res.messages["printed-g5"]
    assert "in the run" in res.messages["printed-g5"]
    assert res.metrics["printed-g5"].heave_rms is None


BASE = {"sea": {"modal_frequency": 0.32}}


@pytest.mark.parametrize("doc,match", [
    ({"controller": {"controllers": ["passive", "printed-g4"]}},
     r"printed-g4.*\"printed-g3\", \"printed-g5\""),
    ({"controller": {"controllers": ["printed-g3"]}, "winch": {"model": "second_order"}},
     r'printed-g3\) act on \[x, x\', u\] .*winch.model = "first_order"'),
    ({"controller": {"controllers": ["printed-g5"], "sample_time": 0.03}},
     r"printed-g5 runs on a 0.2 s winch delay, not a whole number of "
     r"controller.sample_time = 0.03 s"),
])
def test_named_errors(doc: dict, match: str) -> None:
    with pytest.raises(CableOCPError, match=match):
        scene_from_dict({**BASE, **doc})


def test_a_loop_that_cannot_be_computed_is_failed_and_the_others_run(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # A non-finite sampled loop (forced here) is the status "failed" with the solver's
    # error, its metrics None; the other controllers of the scene still run (2 s record).
    from cable_ocp.heave import compare, lqr

    def broken(*_: object, **__: object) -> None:
        raise np.linalg.LinAlgError("Array must not contain infs or NaNs")

    monkeypatch.setattr(lqr, "true_discrete_loop", broken)
    sc = load_scene(EX, {"simulation.duration": 2.0, "simulation.warmup": 0.5})
    res = compare(sc)
    for name in ("printed-g3", "printed-g5"):
        assert res.statuses[name] == "failed"
        assert "LinAlgError: Array must not contain infs" in res.messages[name]
        assert res.metrics[name].heave_rms is None
    assert res.statuses["passive"] == "solved" and res.metrics["passive"].heave_rms > 0


def test_printed_gains_on_the_cable_plant_are_a_named_error() -> None:
    with pytest.raises(CableOCPError, match=r'printed-g3\) run on the design model only; give '
                                            r'simulation.plant = "model"'):
        load_scene(ROOT / "problems" / "heave" / "compare_6_2_6_cable.toml",
                   {"controller.controllers": ["passive", "printed-g3"],
                    "controller.sample_time": 0.01})
