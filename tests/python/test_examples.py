"""The examples under examples/python run to completion and print what they
promise (one line per episode)."""

import os
import pathlib
import subprocess
import sys

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python"


def run(script, *args):
    return subprocess.run([sys.executable, str(EXAMPLES / script), *args], check=True,
                          capture_output=True, text=True, env=os.environ).stdout


def test_random_agent_prints_three_episodes():
    out = run("random_agent.py", "SafetyBallCircle-v0")
    assert sum(line.startswith("episode ") for line in out.splitlines()) == 3


def test_vector_episodes_logs_every_finished_episode():
    out = run("vector_episodes.py", "--env", "SafetyBallRun-v0", "--num-envs", "3",
              "--episodes", "5", "--threads", "2")
    assert sum(line.startswith("episode ") for line in out.splitlines()) >= 5


def test_train_evaluate_film_trains_evaluates_and_films_one_episode(tmp_path):
    out = run("train_evaluate_film.py", "--out", str(tmp_path / "run"), "--epochs", "2",
              "--steps-per-epoch", "500", "--film-size", "160x120")
    assert f"trained: {tmp_path / 'run'}" in out
    assert "evaluation over 4 episodes" in out
    # One SafetyBallCircle-v0 episode is 250 steps (never terminated early): 251 frames with the first.
    assert "(251 frames" in out
    video = tmp_path / "run" / "episode.mp4"
    assert video.read_bytes()[4:8] == b"ftyp"  # an MP4 (ISO base media) file
    assert (tmp_path / "run" / "evaluation.json").exists()
