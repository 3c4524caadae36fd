"""scripts/cost_oscillation.py on a sweep-shaped folder written here, against
numbers worked out by hand, and its errors for bad input."""

import csv
import pathlib
import subprocess
import sys

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "cost_oscillation.py"


def oscillation(*arguments):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, arguments)], capture_output=True, text=True,
                          timeout=60)


def write_run(run_dir, costs, returns, cost_limit=25.0):
    run_dir.mkdir(parents=True)
    lines = ["epoch,episode_return_mean,episode_cost_mean"]
    lines += [f"{e},{r},{c}" for e, (r, c) in enumerate(zip(returns, costs))]
    (run_dir / "progress.csv").write_text("\n".join(lines) + "\n")
    (run_dir / "config.yaml").write_text(f"env_id: SafetyBallCircle-v0  # id\ncost_limit: {cost_limit}  # d\n")


def test_second_half_statistics_worked_out_by_hand(tmp_path):
    configuration = tmp_path / "sweep" / "SafetyBallCircle-v0" / "lag-trpo" / "pid_kp=0.1"
    # seed=0: second half costs 20, 30 -> mean 25, population std 5; returns 10, 20 -> 15.
    write_run(configuration / "seed=0", costs=[100, 100, 20, 30], returns=[0, 0, 10, 20])
    # seed=1: second half costs 24, 24 -> mean 24, std 0; returns 5, 5 -> 5.
    write_run(configuration / "seed=1", costs=[0, 0, 24, 24], returns=[9, 9, 5, 5])
    table = tmp_path / "runs.csv"
    result = oscillation(tmp_path / "sweep", "--csv", table)
    assert result.returncode == 0, result.stderr
    # Means over the two runs: std (5 + 0) / 2 = 2.5, cost (25 + 24) / 2 = 24.5, i.e. -2.0 % of d = 25,
    # return (15 + 5) / 2 = 10.
    assert "2 run(s), epochs 4, window from epoch 2" in result.stdout
    assert "cost std 2.50  cost mean 24.50 (-2.0 % of d = 25)  return 10.00" in result.stdout
    assert "cost std per run: seed=0 5.00, seed=1 0.00" in result.stdout
    with table.open() as handle:
        rows = {row["run"]: row for row in csv.DictReader(handle)}
    assert float(rows["seed=0"]["cost_std"]) == 5.0
    assert float(rows["seed=1"]["cost_mean"]) == 24.0


def test_the_window_start_is_an_option(tmp_path):
    # --from 0: all four epochs of costs 0, 0, 24, 24 -> mean 12, std 12.
    write_run(tmp_path / "c" / "seed=0", costs=[0, 0, 24, 24], returns=[1, 2, 3, 4])
    result = oscillation(tmp_path, "--from", "0")
    assert result.returncode == 0, result.stderr
    assert "cost std 12.00  cost mean 12.00 (-52.0 % of d = 25)  return 2.50" in result.stdout


def test_bad_input_is_named(tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    result = oscillation(empty)
    assert result.returncode == 1 and f"no progress.csv below {empty}" in result.stderr
    result = oscillation(tmp_path / "missing")
    assert result.returncode == 1 and "is not a directory" in result.stderr
    result = oscillation(empty, "--from", "1")
    assert result.returncode == 1 and "--from must be in [0, 1)" in result.stderr
    run = tmp_path / "bad" / "seed=0"
    run.mkdir(parents=True)
    (run / "progress.csv").write_text("epoch,episode_return_mean\n0,1\n1,2\n")
    result = oscillation(tmp_path / "bad")
    assert result.returncode == 1 and "no column episode_cost_mean" in result.stderr
