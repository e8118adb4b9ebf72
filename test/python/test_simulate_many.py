"""simulate_many(): a batch on threads gives each run's simulate() result to the bit, in order."""
import os

import numpy as np
import pytest

from conftest import SCENARIOS


def runs_equal(a, b):
    return (a.status == b.status and a.summary == b.summary and a.text == b.text
            and all(np.array_equal(a.log[c], b.log[c], equal_nan=True) for c in a.log))


def test_threads_give_the_runs_of_one_thread_and_of_simulate(lk):
    configs = [os.path.join(SCENARIOS, name) for name in ("fig6.yaml", "lane_change.yaml", "sinusoid.yaml",
                                                           "waypoints.yaml", "fig9.yaml", "fig9_stable.yaml")]
    overrides = [{"simulation.duration": 4}] * 4 + [None, None]
    one = lk.simulate_many(configs, overrides=overrides, threads=1, as_frame=False)
    two = lk.simulate_many(configs, overrides=overrides, threads=2, as_frame=False)
    four = lk.simulate_many(configs, overrides=overrides, threads=4, as_frame=False)
    assert [r.summary["scenario"] for r in two] == ["fig6", "lane_change", "sinusoid", "waypoints", "fig9",
                                                    "fig9_stable"]
    for i, (config, override) in enumerate(zip(configs, overrides)):
        alone = lk.simulate(config, overrides=override, as_frame=False)
        assert runs_equal(one[i], alone), configs[i]
        assert runs_equal(two[i], alone), configs[i]
        assert runs_equal(four[i], alone), configs[i]
    # The runs differ from one another (the comparison can fail).
    assert not np.array_equal(two[0].log["e_y"][:100], two[1].log["e_y"][:100])


def test_a_sweep_is_one_configuration_and_a_list_of_overrides(lk):
    base = os.path.join(SCENARIOS, "fig6.yaml")
    k_y = [0.01, 0.05, 0.1, 0.15]
    runs = lk.simulate_many(base, overrides=[{"tracker.k_y": k, "simulation.duration": 2} for k in k_y], threads=2,
                            log=False)
    assert all(r.log is None for r in runs)
    for k, run in zip(k_y, runs):
        alone = lk.simulate(base, overrides={"tracker.k_y": k, "simulation.duration": 2})
        assert run.summary == alone.summary
    assert len({r.summary["peak_steering_angle"] for r in runs}) == len(k_y)


def test_a_bad_configuration_is_named_before_any_run(lk):
    base = os.path.join(SCENARIOS, "fig6.yaml")
    with pytest.raises(lk.ConfigError) as error:
        lk.simulate_many(base, overrides=[{"tracker.k_y": 0.1}, {"vehicle.mass": -1}], threads=2)
    assert "configs[1]" in str(error.value) and "vehicle.mass" in str(error.value)
    assert error.value.problems[0]["key"] == "vehicle.mass"
    with pytest.raises(ValueError, match="2 configurations but 1 overrides"):
        lk.simulate_many([base, base], overrides=[{}])
