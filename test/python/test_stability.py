"""The stability functions: lk_stability's JSON and chart, to the printed digit."""
import csv
import json
import os

import numpy as np
import pytest

from conftest import SCENARIOS, run_tool

FIG9 = os.path.join(SCENARIOS, "fig9.yaml")


def cli_json(*args):
    _, stdout, _ = run_tool("lk_stability", *args)
    return json.loads(stdout)


def test_critical_delay_is_lk_stability_critical(lk):
    expected = cli_json("critical", "--config", FIG9)
    del expected["wall_s"]
    result = lk.critical_delay(FIG9)
    assert result == expected
    assert result["tau2_critical_s"] == pytest.approx(1.763006e-3, rel=1e-6)
    assert result["frequency_hz"] == pytest.approx(128.898, rel=1e-5)
    assert not result["stable_at_configured"]


def test_critical_delay_under_a_reading_and_with_overrides(lk):
    expected = cli_json("critical", "--config", FIG9, "--set", "actuator.p=4000", "--reading",
                        "aligning_moment_sign_in_f3", "--count", "3")
    del expected["wall_s"]
    assert lk.critical_delay(FIG9, overrides={"actuator.p": 4000}, reading="aligning_moment_sign_in_f3",
                             count=3) == expected
    with pytest.raises(lk.ConfigError, match="reading"):
        lk.critical_delay(FIG9, reading="no_such_reading")


def test_roots_and_boundary_are_lk_stabilitys(lk):
    expected = cli_json("roots", "--config", FIG9)
    assert lk.rightmost_roots(FIG9, as_array=False) == expected
    roots = lk.rightmost_roots(FIG9)
    assert roots.dtype == np.complex128 and roots[0] == complex(expected["rightmost_roots"][0]["re"],
                                                               expected["rightmost_roots"][0]["im"])
    expected = cli_json("boundary", "--config", FIG9, "--param", "tracker.k_y", "--from", "0.01", "--to", "0.3",
                        "--steps", "40", "--tau2", "1e-4")
    result = lk.stability_boundary(FIG9, "tracker.k_y", 0.01, 0.3, steps=40,
                                   overrides={"delays.desired_steering_to_actuator": 1e-4,
                                              "delays.steering_angle_to_actuator": 1e-4})
    assert result == expected and result["critical"] == pytest.approx(0.14050, rel=1e-4)


def test_a_chart_is_lk_stability_charts(lk, tmp_path):
    prefix = str(tmp_path / "chart")
    run_tool("lk_stability", "chart", "--config", FIG9, "--x", "actuator.p:1000:4000:4", "--y", "tau2:0.0005:0.003:3",
             "--threads", "1", "--no-plot", "--out", prefix)
    with open(prefix + ".csv") as f:
        rows = list(csv.DictReader(f))
    chart = lk.stability_chart(FIG9, x=("actuator.p", 1000, 4000, 4), y=("tau2", 0.0005, 0.003, 3), threads=2)
    assert chart["abscissa"].shape == (3, 4) and chart["x_unit"] == "" and chart["y_unit"] == "s"
    for row in rows:
        i = int(np.argmin(np.abs(chart["x"] - float(row["x"]))))
        j = int(np.argmin(np.abs(chart["y"] - float(row["y"]))))
        # The CSV prints 10 significant digits.
        for field, key in (("abscissa", "abscissa"), ("frequency_hz", "frequency_hz"), ("contour_field", "contour_field")):
            assert chart[key][j, i] == pytest.approx(float(row[field]), rel=1e-9, abs=1e-12), (field, row)
        assert chart["unstable_roots"][j, i] == int(row["unstable_roots"])
        assert chart["stable"][j, i] == (row["stable"] == "1")
    assert chart["stable"].any() and not chart["stable"].all()
    # Explicit axis values, one row.
    line = lk.stability_chart(FIG9, x=("tau2", [1.5e-3, 1.9e-3]), y=("tracker.k_psi", [0.8]))
    assert line["stable"].tolist() == [[True, False]]
