"""scripts/plot_curves.py on one run directory: the learning-curve PNG and the
summary line, checked against numbers worked out by hand from a progress.csv
written here (the sweep mode is tested end to end in tests/cli/sweep_test.cpp).
"""

import json
import pathlib
import subprocess
import sys

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "plot_curves.py"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def plot(*arguments):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, arguments)], capture_output=True, text=True,
                          timeout=120)


def write_run(run_dir, epochs):
    """progress.csv with return = epoch, cost = 20 - epoch, 2 s per epoch."""
    run_dir.mkdir()
    lines = ["epoch,total_env_steps,episode_return_mean,episode_cost_mean,time_s"]
    lines += [f"{e},{1000 * (e + 1)},{e},{20 - e},{2.0 * (e + 1)}" for e in range(epochs)]
    (run_dir / "progress.csv").write_text("\n".join(lines) + "\n")
    (run_dir / "config.yaml").write_text(
        "# bsg run configuration\nenv_id: SafetyBallCircle-v0  # id\nalg: lag-trpo  # algorithm\n"
        "cost_limit: 25.0  # d\nhidden_sizes: [64, 64]\n")
    (run_dir / "evaluation.json").write_text(json.dumps(
        {"mean_return": 17.25, "mean_cost": 3.5, "episodes": 4, "mean_length": 250}))


def test_run_directory_gets_a_png_and_a_summary_worked_out_by_hand(tmp_path):
    run_dir = tmp_path / "run"
    write_run(run_dir, 20)
    result = plot(run_dir)
    assert result.returncode == 0, result.stderr
    # First and last tenth of 20 epochs: epochs 0-1 and 18-19.
    # Return: (0 + 1) / 2 = 0.5 -> (18 + 19) / 2 = 18.5; cost: 19.5 -> 1.5; time 2 s * 20 epochs.
    expected = ("summary: SafetyBallCircle-v0 TRPO-L, 20 epochs in 40 s: return 0.5 -> 18.5, "
                "cost 19.5 -> 1.5 (limit 25) (means of the first and last 2 epochs); "
                f"final policy J 17.2, H 3.5 over 4 episodes; curves: {run_dir / 'learning_curve.png'}")
    assert result.stdout.strip() == expected
    assert (run_dir / "learning_curve.png").read_bytes()[:8] == PNG_MAGIC


def test_a_short_run_uses_at_least_one_epoch_and_no_evaluation_yet(tmp_path):
    run_dir = tmp_path / "run"
    write_run(run_dir, 3)
    (run_dir / "evaluation.json").unlink()
    result = plot(run_dir, "--smooth", 1, "--out", tmp_path / "png")
    assert result.returncode == 0, result.stderr
    assert "3 epochs in 6 s: return 0.0 -> 2.0, cost 20.0 -> 18.0 (limit 25) (means of the first and last 1 epochs)" \
        in result.stdout
    assert "final policy" not in result.stdout
    assert (tmp_path / "png" / "learning_curve.png").read_bytes()[:8] == PNG_MAGIC


def test_a_run_without_a_logged_epoch_is_an_error_naming_the_file(tmp_path):
    run_dir = tmp_path / "run"
    write_run(run_dir, 0)
    result = plot(run_dir)
    assert result.returncode == 1
    assert f"{run_dir / 'progress.csv'}: no epoch logged yet" in result.stderr
    assert not (run_dir / "learning_curve.png").exists()


def test_all_configs_is_refused_for_a_run_directory(tmp_path):
    run_dir = tmp_path / "run"
    write_run(run_dir, 5)
    result = plot(run_dir, "--all-configs")
    assert result.returncode == 2
    assert "--all-configs applies to a sweep directory" in result.stderr
