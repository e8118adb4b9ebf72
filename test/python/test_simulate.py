"""simulate(): the log of lk_simulate --out to the bit, its summary, every way of giving a configuration,
and the core's errors as Python exceptions naming the key."""
import glob
import os

import numpy as np
import pytest

from conftest import REPO, SCENARIOS, csv_text, run_tool


def lk_simulate_csv(tmp_path, name, *args):
    out = str(tmp_path / (name + ".csv"))
    code, stdout, _ = run_tool("lk_simulate", *args, "--out", out)
    with open(out) as f:
        return code, stdout, f.read()


@pytest.mark.parametrize("scenario", sorted(os.path.basename(p) for p in glob.glob(os.path.join(SCENARIOS, "*.yaml"))))
def test_every_scenario_logs_the_same_bits_as_lk_simulate(lk, tmp_path, scenario):
    path = os.path.join(SCENARIOS, scenario)
    code, stdout, text = lk_simulate_csv(tmp_path, scenario, "--config", path)
    run = lk.simulate(path, as_frame=False)
    values = np.column_stack([run.log[c] for c in lk.LOG_COLUMNS])
    assert csv_text(lk.LOG_COLUMNS, values) == text  # every value's %.17g text, so every bit
    assert run.status == ("diverged" if code == 3 else "completed")
    # The summary lk_simulate prints, then its wall time (which differs).
    assert stdout.startswith(run.text)
    assert stdout[len(run.text):].startswith("wall time:")


def test_the_frame_holds_the_logs_numbers(lk, tmp_path):
    import pandas as pd
    path = os.path.join(SCENARIOS, "fig6.yaml")
    _, _, text = lk_simulate_csv(tmp_path, "fig6", "--config", path)
    log, summary = lk.simulate(path)
    assert list(log.columns) == list(lk.LOG_COLUMNS)
    assert log["t"].dtype == np.float64
    assert csv_text(log.columns, log.to_numpy()) == text
    read = pd.read_csv(tmp_path / "fig6.csv", float_precision="round_trip")
    assert np.array_equal(read.to_numpy(), log.to_numpy())
    assert summary["scenario"] == "fig6" and not summary["diverged"]
    assert summary["peak_lateral_offset"] == pytest.approx(1.0, abs=1e-3)
    assert summary["lateral"]["trend"] == "decays" and summary["lateral"]["growth_rate"] < 0


def test_every_form_of_a_configuration_gives_lk_simulates_run(lk, tmp_path):
    path = os.path.join(SCENARIOS, "fig6.yaml")
    _, _, expected = lk_simulate_csv(tmp_path, "set", "--config", path, "--set", "tracker.k_y=0.15",
                                     "--set", "simulation.duration=3")
    with open(path) as f:
        yaml_text = f.read()
    nested = {"simulation": {"name": "fig6", "duration": 20.0, "initial": {"y": 1.0}},
              "tire": {"front": {"model": "brush"}, "rear": {"model": "brush"}},
              "tracker": {"k_psi": 0.8, "k_y": 0.01}, "actuator": {"p": 2000.0},
              "delays": {"pose_to_tracker": 0.2, "desired_steering_to_actuator": 1.0e-4,
                         "steering_angle_to_actuator": 1.0e-4}}
    forms = [
        dict(config=path, overrides={"tracker.k_y": 0.15, "simulation.duration": 3}),
        dict(config=path, overrides=["tracker.k_y=0.15", "simulation.duration=3"]),
        dict(config=yaml_text, overrides={"tracker": {"k_y": 0.15}, "simulation.duration": np.float64(3.0)}),
        dict(config=[nested, {"tracker.k_y": 0.15}, "simulation: {duration: 3}"]),
        dict(config=(path, {"simulation": {"duration": 3}}), overrides={"tracker.k_y": np.float32(0.15).item()}),
    ]
    for i, form in enumerate(forms[:-1]):
        run = lk.simulate(**form, as_frame=False)
        assert csv_text(lk.LOG_COLUMNS, np.column_stack([run.log[c] for c in lk.LOG_COLUMNS])) == expected, i
    # float32(0.15) is another number: the run must differ (the comparison can fail).
    other = lk.simulate(**forms[-1], as_frame=False)
    assert csv_text(lk.LOG_COLUMNS, np.column_stack([other.log[c] for c in lk.LOG_COLUMNS])) != expected


def test_runtime_changes_as_lk_simulate_change(lk, tmp_path):
    path = os.path.join(SCENARIOS, "sinusoid.yaml")
    _, stdout, expected = lk_simulate_csv(tmp_path, "changes", "--config", path, "--set", "simulation.duration=6",
                                          "--change", "2:steering.coulomb_friction=3", "--change", "4:tracker.k_y=0.05")
    for changes in (["2:steering.coulomb_friction=3", "4:tracker.k_y=0.05"],
                    [(2, "steering.coulomb_friction", 3), (4.0, "tracker.k_y", 0.05)],
                    {2: {"steering.coulomb_friction": 3}, 4: {"tracker.k_y": 0.05}}):
        run = lk.simulate(path, changes, overrides={"simulation.duration": 6}, as_frame=False)
        assert csv_text(lk.LOG_COLUMNS, np.column_stack([run.log[c] for c in lk.LOG_COLUMNS])) == expected
        assert [c["key"] for c in run.changes] == ["steering.coulomb_friction", "tracker.k_y"]
        assert run.changes[0]["t"] == 2.0 and run.changes[0]["new_value"] == "3"
        assert stdout.startswith(run.text)


def test_a_diverging_run_is_a_result(lk):
    run = lk.simulate(os.path.join(SCENARIOS, "fig9.yaml"), overrides={"delays.desired_steering_to_actuator": 0.02,
                                                                       "delays.steering_angle_to_actuator": 0.02})
    code, stdout, _ = run_tool("lk_simulate", "--config", os.path.join(SCENARIOS, "fig9.yaml"), "--set",
                               "delays.desired_steering_to_actuator=0.02", "--set",
                               "delays.steering_angle_to_actuator=0.02")
    assert code == 3 and run.diverged and run.summary["diverged"]
    assert run.message and run.message in stdout
    assert run.end_time < 2.0 and len(run.log) > 0


def test_the_effective_configuration_is_lk_simulates(lk):
    path = os.path.join(SCENARIOS, "fig6.yaml")
    _, stdout, _ = run_tool("lk_simulate", "--config", path, "--set", "tracker.k_y=0.02", "--print-config")
    assert lk.effective_config(path, overrides={"tracker.k_y": 0.02}, docs=True) == stdout


# ---------------------------------------------------------------------------------------------------------
# Errors: the core's messages, as lk_simulate prints them after "lk_simulate: ", as Python exceptions


def lk_simulate_error(*args):
    code, _, stderr = run_tool("lk_simulate", *args, "--quiet", check=False)
    assert code == 2, stderr
    assert stderr.startswith("lk_simulate: ")
    return stderr[len("lk_simulate: "):].rstrip("\n")


def test_a_bad_file_raises_lk_simulates_message_naming_every_key(lk, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("vehicle:\n  mass: -1100\n  speed: -3\n")
    expected = lk_simulate_error("--config", str(bad))
    with pytest.raises(lk.ConfigError) as error:
        lk.simulate(str(bad))
    assert str(error.value) == expected
    problems = {p["key"]: p for p in error.value.problems}
    assert set(problems) == {"vehicle.mass", "vehicle.speed"}
    assert problems["vehicle.mass"]["location"] == f"{bad}:2"
    assert "must be > 0" in problems["vehicle.mass"]["message"]
    assert isinstance(error.value, ValueError) and isinstance(error.value, lk.LaneKeepingError)
    # An unknown key (a typo) is named with its line.
    bad.write_text("tracker:\n  k_yy: 0.1\n")
    expected = lk_simulate_error("--config", str(bad))
    with pytest.raises(lk.ConfigError) as error:
        lk.simulate(str(bad))
    assert str(error.value) == expected and "tracker.k_yy is not a known parameter" in expected
    assert error.value.problems == [{"key": "tracker.k_yy", "location": f"{bad}:2",
                                     "message": "is not a known parameter (typo?)"}]


def test_a_bad_dict_names_the_key_and_the_dict(lk):
    with pytest.raises(lk.ConfigError) as error:
        lk.simulate({"vehicle": {"mass": -1100}, "vehicle.speed": -3})
    problems = {p["key"]: p for p in error.value.problems}
    assert set(problems) == {"vehicle.mass", "vehicle.speed"}
    assert problems["vehicle.mass"]["location"] == "<dict>"
    assert "<dict>: vehicle.mass = -1100 kg, must be > 0 kg" in str(error.value)
    with pytest.raises(lk.ConfigError, match="tracker.k_yy is not a known parameter"):
        lk.simulate(overrides={"tracker.k_yy": 0.1})
    with pytest.raises(lk.ConfigError, match="<dict>: tracker.k_y = 'fast': expected a number in 1/m"):
        lk.simulate({"tracker": {"k_y": "fast"}})
    with pytest.raises(lk.ConfigError, match=r"<dict>: tracker.k_y = <object .*> \(object\) is not a number"):
        lk.simulate({"tracker": {"k_y": object()}})
    with pytest.raises(lk.ConfigError, match="<overrides>: vehicle.speed = nan m/s, must be > 0 m/s"):
        lk.simulate(overrides={"vehicle.speed": float("nan")})


def test_missing_files_malformed_yaml_and_bad_changes(lk):
    expected = lk_simulate_error("--config", "/nonexistent/fig6.yaml")
    with pytest.raises(lk.ConfigError) as error:
        lk.simulate("/nonexistent/fig6.yaml")
    assert str(error.value) == expected
    with pytest.raises(lk.ConfigError, match=r"<yaml>:3:1: malformed YAML"):
        lk.simulate("tracker:\n  k_y: [0.1\n")
    expected = lk_simulate_error("--change", "-1:tracker.k_y=0.1")
    with pytest.raises(lk.ConfigError) as error:
        lk.simulate(changes=["-1:tracker.k_y=0.1"])
    assert str(error.value) == expected
    expected = lk_simulate_error("--change", "1:vehicle.mass=-3")
    with pytest.raises(lk.ConfigError) as error:
        lk.simulate(changes=[(1, "vehicle.mass", -3)])
    assert str(error.value) == expected
    with pytest.raises(TypeError):
        lk.simulate(42)


def test_a_schedule_without_lookahead_raises_schedule_error(lk):
    args = ["--set", "delays.steering_angle_to_actuator=0", "--set", "delays.desired_steering_to_actuator=0",
            "--set", "delays.torque_to_plant=0"]
    code, _, stderr = run_tool("lk_simulate", *args, "--quiet", check=False)
    # A configuration the loop cannot run: lk_simulate exits 2 (bad configuration, issue 48), and says so.
    assert code == 2 and "lockstep schedule cannot advance" in stderr
    with pytest.raises(lk.ScheduleError) as error:
        lk.simulate(overrides=[a for a in args if a != "--set"])
    assert str(error.value) == stderr[len("lk_simulate: invalid configuration: "):].rstrip("\n")
    assert isinstance(error.value, RuntimeError)


def test_a_lane_given_as_a_numpy_array(lk, tmp_path):
    path = os.path.join(SCENARIOS, "waypoints.yaml")
    _, _, expected = lk_simulate_csv(tmp_path, "waypoints", "--config", path, "--set", "simulation.duration=4")
    points = np.array([[0.0, 0.0], [40.0, 0.0], [80.0, 1.0], [120.0, 2.0], [160.0, 2.0], [260.0, 2.0]])
    run = lk.simulate([path, {"path": {"waypoints": points}}], overrides={"simulation.duration": 4}, as_frame=False)
    assert csv_text(lk.LOG_COLUMNS, np.column_stack([run.log[c] for c in lk.LOG_COLUMNS])) == expected
    # The log written by simulate(out=...) is lk_simulate's file, byte for byte.
    written = tmp_path / "written.csv"
    lk.simulate(path, overrides={"simulation.duration": 4}, log=False, out=written)
    assert written.read_text() == expected
