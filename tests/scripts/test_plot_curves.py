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


def write_interval_files(sweep):
    """The files of `bsg table --ci` for two environments, hand-made."""
    sweep.mkdir()
    curves = ["env_id,column,config,metric,epoch,seeds,mean,low,high,confidence"]
    for env in ("SafetyBallCircle-v0", "SafetyBallRun-v0"):
        for metric in ("return", "cost", "cost_rate", "cumulative_cost"):
            curves += [f"{env},TRPO-L,default,{metric},{e},3,{e},{e - 1},{e + 1},0.95" for e in range(5)]
    (sweep / "curves.csv").write_text("\n".join(curves) + "\n")
    (sweep / "profiles.csv").write_text(
        "column,metric,environments,seeds,tau,fraction_above,low,high,confidence\n"
        "TRPO-L,feasibility_margin,2,6,-1,1,1,1,0.95\nTRPO-L,feasibility_margin,2,6,1,0,0,0,0.95\n")
    (sweep / "aggregates.csv").write_text(
        "env_id,column,config,config_dir,cost_limit,selected,environments,seeds,metric,statistic,point,low,high,"
        "confidence\n,TRPO-L,,,25,true,2,6,feasible,proportion,0.5,0.2,0.8,0.95\n")
    (sweep / "frontier.csv").write_text(
        "env_id,column,family,config,constraint,cost_limit,seeds,mean_return,return_low,return_high,mean_cost,"
        "cost_low,cost_high,feasible,feasible_low,feasible_high,confidence\n"
        "SafetyBallCircle-v0,TRPO-L,default,cost_limit=5,1,5,3,100,90,110,6,4,8,0.33,0.06,0.79,0.95\n"
        "SafetyBallCircle-v0,TRPO-L,default,cost_limit=25,1,25,3,300,280,320,24,20,28,0.67,0.21,0.94,0.95\n")


def test_ci_figures_each_get_the_rows_they_drew_as_csv_beside_them(tmp_path):
    sweep = tmp_path / "sweep"
    write_interval_files(sweep)
    result = plot(sweep, "--ci")
    assert result.returncode == 0, result.stderr
    plots = sweep / "plots"
    names = sorted(p.name for p in plots.iterdir())
    assert names == sorted(["SafetyBallCircle-v0_ci.png", "SafetyBallCircle-v0_ci.csv", "SafetyBallRun-v0_ci.png",
                            "SafetyBallRun-v0_ci.csv", "profiles.png", "profiles.csv", "aggregates.png",
                            "aggregates.csv", "frontier_SafetyBallCircle-v0.png", "frontier_SafetyBallCircle-v0.csv"])
    for png in plots.glob("*.png"):
        assert png.read_bytes()[:8] == PNG_MAGIC
    # One environment's curves: its 4 metrics x 5 epochs, none of the other's.
    run_rows = (plots / "SafetyBallRun-v0_ci.csv").read_text().splitlines()
    assert len(run_rows) == 1 + 20
    assert all(row.startswith("SafetyBallRun-v0,") for row in run_rows[1:])
    frontier = (plots / "frontier_SafetyBallCircle-v0.csv").read_text().splitlines()
    assert [row.split(",")[5] for row in frontier[1:]] == ["5", "25"]


def test_ci_without_bsg_table_ci_says_what_to_run(tmp_path):
    sweep = tmp_path / "sweep"
    sweep.mkdir()
    result = plot(sweep, "--ci")
    assert result.returncode == 1
    assert "curves.csv not found: run 'bsg table" in result.stderr and "--ci' first" in result.stderr


def test_several_run_directories_share_one_png_with_a_summary_line_each(tmp_path):
    first, second = tmp_path / "seed_0", tmp_path / "seed_1"
    write_run(first, 20)
    write_run(second, 10)
    (second / "evaluation.json").unlink()
    result = plot(first, second, "--out", tmp_path / "png")
    assert result.returncode == 0, result.stderr
    path = tmp_path / "png" / "learning_curves.png"
    # seed_1: 10 epochs, first and last tenth are epochs 0 and 9: return 0 -> 9, cost 20 -> 11, 20 s.
    assert result.stdout.splitlines() == [
        "summary: SafetyBallCircle-v0 TRPO-L, 20 epochs in 40 s: return 0.5 -> 18.5, cost 19.5 -> 1.5 (limit 25) "
        f"(means of the first and last 2 epochs); final policy J 17.2, H 3.5 over 4 episodes; curves: {path}",
        "summary: SafetyBallCircle-v0 TRPO-L, 10 epochs in 20 s: return 0.0 -> 9.0, cost 20.0 -> 11.0 (limit 25) "
        f"(means of the first and last 1 epochs); curves: {path}"]
    assert path.read_bytes()[:8] == PNG_MAGIC


def test_several_directories_need_out_and_must_all_be_runs(tmp_path):
    first, second = tmp_path / "seed_0", tmp_path / "seed_1"
    write_run(first, 5)
    write_run(second, 5)
    result = plot(first, second)
    assert result.returncode == 2
    assert "several run directories need --out DIR" in result.stderr
    result = plot(first, tmp_path, "--out", tmp_path / "png")
    assert result.returncode == 2
    assert f"{tmp_path} is not a run directory (no progress.csv)" in result.stderr


def test_labels_and_colours_are_read_from_the_program_table(tmp_path):
    """The plots' labels come from common/algorithms.h's rows, checked against a table written here."""
    import importlib.util
    spec = importlib.util.spec_from_file_location("plot_curves", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    table = tmp_path / "algorithms.h"
    table.write_text(
        '    {Algorithm::trpo,     "trpo",     "TRPO",     "",           AlgorithmFamily::trust_region, false, false,'
        ' false, "tab:blue"},\n'
        '    // a comment between rows\n'
        '    {Algorithm::sac_lag,  "sac-lag",  "SAC-Lag",  "SAC-PID",    AlgorithmFamily::off_policy,   true,  true,'
        '  false, "teal"},\n')
    labels, order, colours = module.read_algorithm_table(table)
    assert labels == {"trpo": "TRPO", "sac-lag": "SAC-Lag"}
    assert order == ["trpo", "sac-lag"]
    assert colours == {"trpo": "tab:blue", "sac-lag": "teal"}
    # The shipped table: every algorithm has a label and its own colour, the off-policy ones included.
    assert module.ALGORITHM_LABELS["ddpg-lag"] == "DDPG-Lag"
    assert len(set(module.ALGORITHM_COLORS.values())) == len(module.ALGORITHM_COLORS)
