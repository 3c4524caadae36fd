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
