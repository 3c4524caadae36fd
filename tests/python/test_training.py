"""Training from Python (bsg.train, bsg.sweep) against the bsg program: a run started from Python
is byte for byte the run `bsg train` writes from the same configuration (progress.csv with its
timing columns aside, evaluation.json, config.yaml, returns.csv, costs.csv); a run stopped by a
KeyboardInterrupt (raised by the callback, or a real SIGINT while the C++ trainer runs) resumes,
by `bsg train --resume` or bsg.train(resume=...), to the files of an uninterrupted run; bad
configurations raise one ValueError naming the key. The oracle is always the program's own run
of the same configuration, started in another process."""

import csv
import os
import pathlib
import signal
import subprocess
import threading
import time

import pytest

import bsg

ROOT = pathlib.Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
TINY = CONFIGS / "runs" / "tiny_ball_circle_trpo_l.yaml"  # 3 epochs of 1000 steps, 4 evaluation episodes
TIMING = {"time_collect_s", "time_update_s", "time_s", "fps"}  # wall-clock columns (algos/training/epoch_log.h)
SAME_BYTES = ["config.yaml", "evaluation.json", "returns.csv", "costs.csv"]


def cli_train(bsg_binary, *args):
    result = subprocess.run([bsg_binary, "train", "--quiet", *map(str, args)], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    return result


def progress_without_timing(run_dir):
    """progress.csv's text, column by column, without the wall-clock columns."""
    with open(run_dir / "progress.csv", newline="") as f:
        rows = list(csv.reader(f))
    keep = [i for i, name in enumerate(rows[0]) if name not in TIMING]
    return [[row[i] for i in keep] for row in rows]


def assert_same_run(expected_dir, actual_dir, epochs, config_lines=lambda text: text):
    expected = progress_without_timing(expected_dir)
    assert len(expected) == epochs + 1
    assert progress_without_timing(actual_dir) == expected
    for name in SAME_BYTES:
        if name == "config.yaml":
            expected_text, actual_text = ((d / name).read_bytes() for d in (expected_dir, actual_dir))
            assert config_lines(actual_text) == config_lines(expected_text)
        else:
            assert (actual_dir / name).read_bytes() == (expected_dir / name).read_bytes(), name


def test_a_python_run_is_the_cli_run(bsg_binary, tmp_path):
    cli_train(bsg_binary, TINY, "--out", tmp_path / "cli")
    rows = []
    run_dir = bsg.train(TINY, out=tmp_path / "py", callback=rows.append, verbose=False)
    assert run_dir == str(tmp_path / "py")
    assert_same_run(tmp_path / "cli", tmp_path / "py", epochs=3)
    # The callback saw every row as progress.csv holds it (shortest round-trip text of each double).
    written = list(csv.DictReader(open(tmp_path / "py" / "progress.csv", newline="")))
    assert [{k: float(v) for k, v in row.items()} for row in written] == rows


def test_a_dict_and_keywords_are_the_run_file_and_set(bsg_binary, tmp_path):
    cli_train(bsg_binary, "--set", "env_id=SafetyBallRun-v0", "--set", "alg=trpo", "--set", "epochs=2",
              "--set", "steps_per_epoch=500", "--set", "eval_episodes=2", "--set", "hidden_sizes=[16, 16]",
              "--set", "gamma=0.98", "--set", "env.max_episode_steps=250", "--out", tmp_path / "cli")
    bsg.train({"env_id": "SafetyBallRun-v0", "alg": "trpo", "epochs": 2, "steps_per_epoch": 500},
              out=tmp_path / "py", eval_episodes=2, hidden_sizes=(16, 16), gamma=0.98,
              env={"max_episode_steps": 250}, verbose=False)
    assert_same_run(tmp_path / "cli", tmp_path / "py", epochs=2)


def test_an_exception_in_the_callback_stops_with_a_checkpoint_that_resumes_identically(bsg_binary, tmp_path):
    cli_train(bsg_binary, TINY, "--out", tmp_path / "whole")

    def interrupt_after_two(row):
        if row["epoch"] == 1:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt) as stopped:
        bsg.train(TINY, out=tmp_path / "cut", callback=interrupt_after_two, verbose=False)
    assert stopped.value.bsg_run_dir == str(tmp_path / "cut")
    if hasattr(BaseException, "add_note"):  # Python 3.11
        assert any("stopped after 2 of 3 epochs" in note for note in stopped.value.__notes__)
    assert len(progress_without_timing(tmp_path / "cut")) == 3  # header and the two epochs
    assert not (tmp_path / "cut" / "evaluation.json").exists()
    cli_train(bsg_binary, "--resume", tmp_path / "cut")
    assert_same_run(tmp_path / "whole", tmp_path / "cut", epochs=3)


def test_a_real_sigint_stops_between_epochs_and_bsg_train_resume_finishes(bsg_binary, tmp_path):
    # 12 epochs of 1000 steps (about a second): the signal, sent 20 ms into the first epoch's
    # callback, reaches Python's handler while the C++ trainer runs without the GIL.
    keys = ["--set", "epochs=12"]
    cli_train(bsg_binary, TINY, *keys, "--out", tmp_path / "whole")

    def send_sigint_soon(row):
        if row["epoch"] == 0:
            threading.Timer(0.02, os.kill, (os.getpid(), signal.SIGINT)).start()

    with pytest.raises(KeyboardInterrupt) as stopped:
        bsg.train(TINY, out=tmp_path / "cut", epochs=12, callback=send_sigint_soon, verbose=False)
    assert stopped.value.bsg_run_dir == str(tmp_path / "cut")
    epochs_done = len(progress_without_timing(tmp_path / "cut")) - 1
    assert 1 <= epochs_done < 12
    cli_train(bsg_binary, "--resume", tmp_path / "cut")
    assert_same_run(tmp_path / "whole", tmp_path / "cut", epochs=12)


def test_a_python_resume_finishes_a_cli_run_stopped_early(bsg_binary, tmp_path):
    cli_train(bsg_binary, TINY, "--out", tmp_path / "whole")
    cli_train(bsg_binary, TINY, "--out", tmp_path / "cut", "--stop-after", "1")
    assert bsg.train(resume=tmp_path / "cut", verbose=False) == str(tmp_path / "cut")
    assert_same_run(tmp_path / "whole", tmp_path / "cut", epochs=3)


@pytest.mark.parametrize("config, keywords, expected", [
    ({"env_id": "SafetyBallCircle-v0", "alg": "sac-lag", "tau": 0.01}, {},
     r"config\['tau'\]: unknown key 'tau'.*polyak"),
    (TINY, {"epochz": 3}, r"bsg.train\(epochz=...\): unknown key 'epochz'.*epochs"),
    (TINY, {"epochs": "ten"}, r"bsg.train\(epochs=...\).*epochs"),
    (TINY, {"epochs": 0}, r"epochs"),
    ({"env_id": "SafetyBallCircle-v0"}, {}, r"no 'alg' given \(the config dict does not name it\)"),
    ({"env_id": "SafetyBallCirle-v0", "alg": "trpo"}, {}, r"SafetyBallCirle-v0"),
    (ROOT / "no_such_run.yaml", {}, r"run file .*no_such_run.yaml does not exist"),
])
def test_a_bad_config_raises_one_value_error_naming_it(tmp_path, config, keywords, expected):
    with pytest.raises(ValueError, match=expected) as error:
        bsg.train(config, out=tmp_path / "run", verbose=False, **keywords)
    assert "\n" not in str(error.value)
    assert not (tmp_path / "run").exists()


def test_bad_arguments_raise_type_errors(tmp_path):
    with pytest.raises(TypeError, match=r"config\['seed'\]: a value of type object"):
        bsg.train({"env_id": "SafetyBallCircle-v0", "alg": "trpo", "seed": object()}, out=tmp_path / "a")
    with pytest.raises(TypeError, match="callback must be callable"):
        bsg.train(TINY, out=tmp_path / "b", callback=3)
    with pytest.raises(ValueError, match="resume takes the configuration from the run directory"):
        bsg.train(TINY, resume=tmp_path / "c")
    with pytest.raises(RuntimeError, match="not_a_run does not exist"):
        bsg.train(resume=tmp_path / "not_a_run", verbose=False)


def test_a_python_sweep_stopped_by_ctrl_c_and_run_again_is_the_cli_sweep(bsg_binary, tmp_path):
    grid = CONFIGS / "grids" / "quick.yaml"  # trpo x seeds 0, 1: 6 epochs of 1000 steps each
    result = subprocess.run([bsg_binary, "sweep", str(grid), "--alg", "trpo", "--jobs", "2", "--out",
                             str(tmp_path / "cli")], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    # Ctrl-C (a real SIGINT) once a run has written its first epoch: the running runs stop with a
    # checkpoint, bsg.sweep raises KeyboardInterrupt, and the same call again finishes them.
    first_rows = tmp_path / "py" / "SafetyBallCircle-v0" / "trpo" / "target_kl=0.01"

    def interrupt_after_the_first_epoch():
        while not any(len(p.read_text().splitlines()) >= 2 for p in first_rows.glob("*/progress.csv")):
            time.sleep(0.01)
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=interrupt_after_the_first_epoch, daemon=True).start()
    with pytest.raises(KeyboardInterrupt) as stopped:
        bsg.sweep(grid, out=tmp_path / "py", alg="trpo", jobs=2, program=bsg_binary)
    assert stopped.value.bsg_sweep_dir == str(tmp_path / "py")
    assert not list((tmp_path / "py").rglob("evaluation.json"))
    assert bsg.sweep(grid, out=tmp_path / "py", alg="trpo", jobs=2, program=bsg_binary) == str(tmp_path / "py")
    runs = sorted(p.parent.relative_to(tmp_path / "cli") for p in (tmp_path / "cli").rglob("evaluation.json"))
    assert len(runs) == 2
    for run in runs:
        # A sweep's runs name the sweep directory as their log_dir, and nothing else differs.
        assert_same_run(tmp_path / "cli" / run, tmp_path / "py" / run, epochs=6,
                        config_lines=lambda text: [line for line in text.splitlines() if not line.startswith(b"log_dir:")])
    with pytest.raises(ValueError, match="no_such_alg"):
        bsg.sweep(grid, out=tmp_path / "bad", alg="no_such_alg", program=bsg_binary)
