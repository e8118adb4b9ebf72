"""diagnose(): report.json of lk_gap, from files and from DataFrames; the log reader's errors."""
import json
import os

import numpy as np
import pandas as pd
import pytest

from conftest import REPO, run_tool

NOMINAL = os.path.join(REPO, "config", "scenarios", "sinusoid.yaml")
# A small diagnosis (the module's plumbing is under test, not the diagnosis): two candidates, one thread.
EFFECTS = ["steering_friction", "lateral_disturbance"]
GAP_ARGS = ["--effects", ",".join(EFFECTS), "--threads", "1", "--no-plots", "--quiet"]
OPTIONS = dict(effects=EFFECTS, threads=1)
SCENARIOS = {"train": {"simulation": {"duration": 8, "log_rate": 100, "initial": {"y": 0.8}}},
             "held": {"simulation": {"duration": 8, "log_rate": 100, "initial": {"y": -0.6}}}}


def without_wall_times(report):
    report = dict(report)
    report.pop("wall_seconds")
    return report


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    """The sinusoidal lane with kingpin friction the nominal lacks: a training run and a held-out run from
    another initial offset, each with its scenario file (8 s at 100 Hz)."""
    folder = tmp_path_factory.mktemp("gap")
    runs = {}
    for name, scenario in SCENARIOS.items():
        path, scenario_path = str(folder / (name + ".csv")), str(folder / (name + ".yaml"))
        with open(scenario_path, "w") as f:
            json.dump(scenario, f)  # JSON is YAML
        run_tool("lk_simulate", "--config", NOMINAL, "--config", scenario_path, "--set", "steering.coulomb_friction=5",
                 "--out", path, "--quiet")
        runs[name] = (path, scenario_path)
    return folder, runs


def lk_gap_report(folder, *args):
    report_dir = str(folder / "report")
    code, _, stderr = run_tool("lk_gap", "--config", NOMINAL, *args, "--report", report_dir, *GAP_ARGS, check=False)
    assert code == 0, stderr
    with open(os.path.join(report_dir, "report.json")) as f:
        return json.load(f)


def test_the_report_is_lk_gaps_from_files_and_from_frames(lk, logs):
    folder, runs = logs
    (train, train_scenario), (held, held_scenario) = runs["train"], runs["held"]
    expected = lk_gap_report(folder, "--log", train, "--scenario", train_scenario, "--holdout", held, "--scenario",
                             held_scenario)
    assert expected["verdict"]["effect"] == "steering_friction"  # the comparison below is of a real diagnosis
    from_files = lk.diagnose(NOMINAL, [{"log": train, "scenario": train_scenario}],
                             [{"log": held, "scenario": held_scenario}], **OPTIONS)
    assert without_wall_times(from_files) == without_wall_times(expected)
    # The same runs as DataFrames with the scenarios as dicts: only the sources' names differ.
    frames = {name: pd.read_csv(path, float_precision="round_trip") for name, (path, _) in runs.items()}
    messages = []
    from_frames, series = lk.diagnose(NOMINAL, [{"log": frames["train"], "scenario": SCENARIOS["train"]}],
                                      {"log": frames["held"], "scenario": SCENARIOS["held"]}, **OPTIONS,
                                      progress=messages.append, series=True)
    text = json.dumps(without_wall_times(expected))
    for old, new in ((train_scenario, "logs[0] scenario"), (held_scenario, "holdout[0] scenario"),
                     (train, "DataFrame logs[0]"), (held, "DataFrame holdout[0]")):
        text = text.replace(json.dumps(old)[1:-1], new)
    assert without_wall_times(from_frames) == json.loads(text)
    assert messages, "progress messages"
    residuals = series["residuals"]
    assert list(residuals.columns) == ["t", "tracker", "actuator", "steering", "chassis"]
    assert len(residuals) > 100 and np.isfinite(residuals["steering"]).any()


def test_the_folds_and_forms_switches_are_lk_gaps(lk, logs):
    """two_folds / leader_forms / closed_loop_placement off are lk_gap's --one-fold / --candidate-forms-only /
    --no-closed-loop-placement; the leader's LuGre form is fitted (its note) only when they are on."""
    folder, runs = logs
    (train, train_scenario), (held, held_scenario) = runs["train"], runs["held"]
    expected = lk_gap_report(folder, "--log", train, "--scenario", train_scenario, "--holdout", held, "--scenario",
                             held_scenario, "--one-fold", "--candidate-forms-only", "--no-closed-loop-placement")
    assert expected["verdict"]["effect"] == "steering_friction"
    assert not any("leader's forms" in n for n in expected["notes"])
    assert not any("by the closed loop" in n for n in expected["notes"])
    off = lk.diagnose(NOMINAL, [{"log": train, "scenario": train_scenario}], [{"log": held, "scenario": held_scenario}],
                      two_folds=False, leader_forms=False, closed_loop_placement=False, **OPTIONS)
    assert without_wall_times(off) == without_wall_times(expected)
    on = lk.diagnose(NOMINAL, [{"log": train, "scenario": train_scenario}], [{"log": held, "scenario": held_scenario}],
                     **OPTIONS)
    assert any(n.startswith("steering_friction: the leader's forms") for n in on["notes"])


def test_every_fold_is_lk_gaps(lk, logs):
    """every_fold is lk_gap's --every-fold: each run held out in turn and both folds listed, though the held-out
    run alone detects the gap."""
    folder, runs = logs
    (train, train_scenario), (held, held_scenario) = runs["train"], runs["held"]
    expected = lk_gap_report(folder, "--log", train, "--scenario", train_scenario, "--holdout", held, "--scenario",
                             held_scenario, "--every-fold")
    assert expected["detection"]["heldout"]["detected"]
    folds = expected["folds"]
    assert len(folds) == 2
    assert folds[0]["heldout"] == folds[1]["training"] and folds[1]["heldout"] == folds[0]["training"]
    got = lk.diagnose(NOMINAL, [{"log": train, "scenario": train_scenario}], [{"log": held, "scenario": held_scenario}],
                      every_fold=True, **OPTIONS)
    assert without_wall_times(got) == without_wall_times(expected)


def test_measured_corrections_is_lk_gaps(lk, tmp_path):
    """measured_corrections=False is lk_gap's --no-measured-corrections: a gyro drifting 0.008 rad/s from the heading
    is measured before any model, corrected and named by default, reported only when off, the same from Python as
    from the tool."""
    log, scenario = str(tmp_path / "bias.csv"), str(tmp_path / "bias.yaml")
    with open(scenario, "w") as f:
        json.dump({"simulation": {"duration": 12, "log_rate": 100}}, f)
    run_tool("lk_simulate", "--config", NOMINAL, "--config", scenario, "--set", "sensors.yaw_rate_bias=0.008",
             "--out", log, "--quiet")
    report_dir = str(tmp_path / "report")
    args = ["--effects", "sensor_offset,lateral_disturbance", "--threads", "1", "--no-plots", "--quiet"]
    code, _, stderr = run_tool("lk_gap", "--config", NOMINAL, "--log", log, "--scenario", scenario,
                               "--report", report_dir, *args, check=False)
    assert code == 0, stderr
    with open(os.path.join(report_dir, "report.json")) as f:
        expected = json.load(f)
    first = expected["verdict"]["effects"][0]
    assert first["measured"] and first["effect"] == "sensor_offset" and first["form"] == "yaw_rate"
    assert abs(first["params"]["bias"] - 0.008) < 0.0005
    got = lk.diagnose(NOMINAL, [{"log": log, "scenario": scenario}], effects=["sensor_offset", "lateral_disturbance"],
                      threads=1)
    assert without_wall_times(got) == without_wall_times(expected)
    # Off: the finding is an input check, and no effect is "measured"; the same as the tool's.
    off = lk.diagnose(NOMINAL, [{"log": log, "scenario": scenario}], effects=["sensor_offset", "lateral_disturbance"],
                      threads=1, measured_corrections=False)
    code, _, stderr = run_tool("lk_gap", "--config", NOMINAL, "--log", log, "--scenario", scenario,
                               "--no-measured-corrections", "--report", report_dir, *args, check=False)
    assert code == 0, stderr
    with open(os.path.join(report_dir, "report.json")) as f:
        assert without_wall_times(off) == without_wall_times(json.load(f))
    assert any(c["kind"] == "bias" and c["channel"] == "yaw_rate" for c in off["input_checks"])
    assert not any(e.get("measured") for e in off["verdict"]["effects"])


def test_targeted_test_is_lk_gaps(lk, tmp_path):
    """targeted_test=False is lk_gap's --no-targeted-test: on a run with nothing wrong the replays' test sees no gap, so
    by default the actuation delay's fit is tested against the draws (a note says so, and names nothing here); off,
    it is not, the same from Python as from the tool."""
    log, scenario = str(tmp_path / "clean.csv"), str(tmp_path / "clean.yaml")
    with open(scenario, "w") as f:
        json.dump({"simulation": {"duration": 8, "log_rate": 100}}, f)
    run_tool("lk_simulate", "--config", NOMINAL, "--config", scenario, "--out", log, "--quiet")
    run = [{"log": log, "scenario": scenario}]

    def tested(report):
        return any(n.startswith("targeted test of actuation_delay") for n in report["notes"])

    on = lk.diagnose(NOMINAL, run, effects=["actuation_delay"], threads=1)
    assert on["verdict"]["effect"] == "unexplained" and tested(on), on["notes"]
    off = lk.diagnose(NOMINAL, run, effects=["actuation_delay"], threads=1, targeted_test=False)
    assert not tested(off)
    report_dir = str(tmp_path / "report")
    code, _, stderr = run_tool("lk_gap", "--config", NOMINAL, "--log", log, "--scenario", scenario, "--effects",
                               "actuation_delay", "--threads", "1", "--no-targeted-test", "--no-plots", "--quiet",
                               "--report", report_dir, check=False)
    assert code == 0, stderr
    with open(os.path.join(report_dir, "report.json")) as f:
        assert without_wall_times(off) == without_wall_times(json.load(f))


def test_a_frames_bad_rows_are_named(lk, logs):
    _, runs = logs
    train = runs["train"][0]
    frame = pd.read_csv(train, float_precision="round_trip")
    frame.loc[5, "t"] = frame.loc[3, "t"]
    with pytest.raises(lk.InputError, match=r"DataFrame logs\[0\] row 5: column 't': time not strictly increasing"):
        lk.diagnose(NOMINAL, frame, **OPTIONS)
    frame = pd.read_csv(train, float_precision="round_trip").drop(columns=["t"])
    with pytest.raises(lk.InputError, match=r"DataFrame logs\[0\]: missing required column t"):
        lk.diagnose(NOMINAL, [frame], **OPTIONS)
    with pytest.raises(lk.ConfigError, match="not_an_effect"):
        lk.diagnose(NOMINAL, [train], effects=["not_an_effect"])
    with pytest.raises(lk.ConfigError, match="tracker.k_y"):
        lk.diagnose(NOMINAL, [{"log": train, "scenario": {"tracker": {"k_y": 0.1}}}], **OPTIONS)
    assert "steering_friction" in lk.candidate_effects()


def test_how_far_measures_a_change_as_the_diagnosis_measures_its_verdict(lk, logs):
    """how_far(): the closed loop with a change of one's own against the logs, on the diagnosis' own terms: the
    same nominal closed loop before (report["how_far"]), the change's after; the logs' own friction closes the
    gap, half of it part of it; a bad key is named before any replay."""
    _, runs = logs
    (train, train_scenario), (held, held_scenario) = runs["train"], runs["held"]
    training = [{"log": train, "scenario": train_scenario}]
    holdout = [{"log": held, "scenario": held_scenario}]
    truth = lk.how_far(NOMINAL, training, holdout, change={"steering.coulomb_friction": 5}, threads=1)
    half = lk.how_far(NOMINAL, training, holdout, change=["steering.coulomb_friction=2.5"], threads=1)
    report = lk.diagnose(NOMINAL, training, holdout, **OPTIONS)
    print(f"[ measured ] closed-loop gap {truth['before']:.4g} -> {truth['after']:.4g} with the logs' friction, "
          f"-> {half['after']:.4g} with half of it")
    assert "not_run" not in truth
    assert truth["before"] == report["how_far"]["before"]
    assert truth["net_before"] == report["how_far"]["net_before"]
    assert truth["after"] < 0.05 * truth["before"]  # the logs were simulated with it, without noise
    assert truth["after"] < half["after"] < half["before"]
    assert truth["net_shrink"] > 0.95
    with pytest.raises(lk.ConfigError, match="coulomb_frictio"):
        lk.how_far(NOMINAL, training, change={"steering.coulomb_frictio": 1.0})
    with pytest.raises(lk.ConfigError, match="no key=value"):
        lk.how_far(NOMINAL, training, change=[])
    with pytest.raises(TypeError, match="dotted keys"):
        lk.how_far(NOMINAL, training, change={"steering": {"coulomb_friction": 5}})
