"""The low-speed study's launch: the drive torque is limited by engine power, so the spinning wheel
settles where the engine's torque P / omega equals the tire's torque F_x R (omega R = P / F_x)
instead of running away (it reached 300 m/s in 3 s under a constant 3000 N*m)."""

from pathlib import Path

import pandas as pd

from vehdyn.report import run_study

STUDY = Path(__file__).resolve().parents[2] / "studies" / "low_speed.py"


def test_launch_wheel_speed_is_held_by_the_power_limit(tmp_path):
    outcome = run_study(STUDY, tmp_path, quick=True)
    assert outcome.error is None, outcome.error
    checks = pd.read_csv(tmp_path / "low_speed" / "checks.csv", index_col=0).set_index("case")
    spin = checks.loc["launch, spinning rear wheel at 2 s"]
    # closed form of the wheel's torque balance with the engine at full power
    assert abs(spin["relative_difference"]) < 1e-3
    assert 5.0 < spin["model"] < 25.0  # [m/s]: spinning, but held (vehicle at ~10 m/s by then)
    # the limit does not take away the traction-limited launch (mu a / (L - mu h) g, the Fiala tire
    # saturates a little below mu)
    launch = checks.loc["launch, 3000 N*m and 100 kW on the rear axle"]
    assert -0.06 < launch["relative_difference"] < 0.0
    assert any("at most 100 kW" in caption or "100 kW" in caption for kind, _, caption in outcome.items
               if kind == "figure")
