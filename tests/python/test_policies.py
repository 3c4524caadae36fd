"""bsg.load_policy and bsg.evaluate against the C++ side, one tiny run per family (on-policy
PPO-Lag, off-policy SAC-Lag, offline BC-All, CPQ, BCQ-Lag and COptiDICE on a dataset `bsg collect`
writes), trained by `bsg train` in a few seconds. Oracles: every observation `bsg eval`'s own
evaluation acted on and the action it took (tests/python/policy_recorder.cpp, a separate C++
process), which Python's actions must equal bit for bit; `bsg eval --json`'s output and the
training's evaluation.json, which bsg.evaluate must repeat; the run's config.yaml and checkpoint
epochs, read as text."""

import json
import pathlib
import subprocess

import numpy as np
import pytest

import bsg

ROOT = pathlib.Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
ENV_ID = "SafetyBallCircle-v0"
FAMILIES = {
    "on_policy": ["alg=ppo-lag", "epochs=2", "steps_per_epoch=500"],
    "off_policy": ["alg=sac-lag", "epochs=2", "steps_per_epoch=200", "num_envs=2", "start_steps=100",
                   "update_every=50", "batch_size=32", "buffer_size=1000", "hidden_sizes=[32, 32]"],
    "offline": ["alg=bc-all", "epochs=2", "updates_per_epoch=5", "batch_size=32",
                "hidden_sizes=[32, 32]"],
    # The offline learners with critics: each acts through its own policy head, on the same
    # dataset standardisation as behaviour cloning.
    "offline_cpq": ["alg=cpq", "epochs=2", "updates_per_epoch=5", "batch_size=32",
                    "hidden_sizes=[32, 32]", "vae_hidden_size=32"],
    "offline_bcq_lag": ["alg=bcq-lag", "epochs=2", "updates_per_epoch=5", "batch_size=32",
                        "hidden_sizes=[32, 32]", "vae_hidden_size=32"],
    "offline_coptidice": ["alg=coptidice", "epochs=2", "updates_per_epoch=5", "batch_size=32",
                          "hidden_sizes=[32, 32]"],
}
OFFLINE = [family for family in FAMILIES if family.startswith("offline")]


def run(command):
    result = subprocess.run(command, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout


@pytest.fixture(scope="module")
def runs(tmp_path_factory, bsg_binary):
    """family -> run directory of a finished tiny run (2 evaluation episodes)."""
    root = tmp_path_factory.mktemp("runs")
    dataset = root / "random.hdf5"
    run([bsg_binary, "collect", "--out", str(dataset), "--env", ENV_ID, "--policy", "random",
         "--episodes", "2", "--seed", "3"])
    directories = {}
    for family, settings in FAMILIES.items():
        directory = root / family
        if family in OFFLINE:
            settings = settings + [f"dataset={dataset}"]
        arguments = [bsg_binary, "train", "--configs", str(CONFIGS), "--quiet", "--out", str(directory)]
        for setting in [f"env_id={ENV_ID}", "seed=4", "eval_episodes=2"] + settings:
            arguments += ["--set", setting]
        run(arguments)
        directories[family] = directory
    return directories


def recorded(policy_recorder, run_dir, tmp_path, actions="mean", episodes=1):
    """(observations [T, obs], actions [T, act]) of `bsg eval`'s evaluation, from C++."""
    output = tmp_path / "record.bin"
    run([policy_recorder, str(run_dir), str(episodes), actions, str(output)])
    values = np.fromfile(output, dtype=np.float64)
    obs_dim, act_dim = int(values[0]), int(values[1])
    rows = values[2:].reshape(-1, obs_dim + act_dim)
    return rows[:, :obs_dim], rows[:, obs_dim:]


@pytest.mark.parametrize("family", FAMILIES)
def test_actions_equal_the_cpp_evaluations_bit_for_bit(family, runs, policy_recorder, tmp_path):
    observations, actions = recorded(policy_recorder, runs[family], tmp_path)
    assert len(observations) > 0
    policy = bsg.load_policy(runs[family])
    batch = policy.act(observations)
    assert batch.dtype == np.float64 and batch.shape == actions.shape
    assert np.array_equal(batch, actions)
    # One observation at a time: the same numbers, as a [act_dim] array.
    for row in (0, len(observations) // 2, len(observations) - 1):
        single = policy.act(observations[row])
        assert single.shape == (actions.shape[1],)
        assert np.array_equal(single, actions[row])
    # A list of numbers and a float32 array are accepted like any action input.
    assert np.array_equal(policy.act(observations[0].tolist()), actions[0])


def test_sampled_actions_continue_the_sampled_evaluations_stream(runs, policy_recorder, tmp_path):
    observations, actions = recorded(policy_recorder, runs["on_policy"], tmp_path, "sampled")
    policy = bsg.load_policy(runs["on_policy"])
    sampled = np.array([policy.act(o, deterministic=False) for o in observations])
    assert np.array_equal(sampled, actions)
    assert not np.array_equal(sampled, policy.act(observations))


@pytest.mark.parametrize("family", FAMILIES)
def test_the_policy_knows_its_run(family, runs):
    policy = bsg.load_policy(runs[family])
    config = (runs[family] / "config.yaml").read_text()
    assert policy.env_id == ENV_ID and f"env_id: {ENV_ID}" in config
    assert f"alg: {policy.alg}" in config
    assert policy.epoch == policy.epochs == 2
    assert policy.config["alg"] == policy.alg
    spec = bsg.make(ENV_ID).spec
    assert policy.observation_space.shape == (spec.observation_dim,)
    assert policy.action_space.shape == (spec.action_dim,)
    assert str(policy.run_dir) == str(runs[family])
    assert ENV_ID in repr(policy)


def test_observation_normalization_is_what_the_policy_applies(runs):
    """What each family's policy says of its standardisation: the on-policy running statistics
    (s - m)/(std + 1e-5), none for the off-policy actors (raw observations), and for behaviour
    cloning the dataset's own mean, computed here from the file."""
    norm = bsg.load_policy(runs["on_policy"]).observation_normalization
    assert set(norm) == {"mean", "std", "std_epsilon", "clip"}
    assert norm["mean"].shape == norm["std"].shape == (bsg.make(ENV_ID).spec.observation_dim,)
    assert norm["std_epsilon"] == 1e-5
    assert np.all(norm["std"] > 0)
    assert bsg.load_policy(runs["off_policy"]).observation_normalization is None
    # The offline standardisation is the dataset's: its observations' mean and population std.
    data = bsg.datasets.load(runs["offline"].parent / "random.hdf5")
    observations = np.asarray(data["observations"], dtype=np.float64)
    for family in OFFLINE:
        offline = bsg.load_policy(runs[family]).observation_normalization
        assert offline["std_epsilon"] == 0 and offline["clip"] is None, family
        assert np.allclose(offline["mean"], observations.mean(axis=0), rtol=1e-6, atol=1e-6), family


@pytest.mark.parametrize("family", FAMILIES)
def test_evaluate_repeats_bsg_eval_and_the_training_evaluation(family, runs, bsg_binary):
    result = bsg.evaluate(runs[family])
    printed = json.loads(run([bsg_binary, "eval", str(runs[family]), "--json"]))
    assert {k: result[k] for k in printed} == printed
    trained = json.loads((runs[family] / "evaluation.json").read_text())
    for key in ("mean_return", "mean_cost", "episodes", "mean_length"):
        assert result[key] == trained[key]
    assert result["epoch"] == result["epochs"] == 2
    # Another number of episodes and another seed, as `bsg eval --episodes` would and other episodes.
    three = bsg.evaluate(runs[family], episodes=3)
    assert three["episodes"] == 3 and three["returns"][:2] == result["returns"]
    assert bsg.evaluate(runs[family], episodes=2, seed=99)["returns"] != result["returns"]


def test_evaluate_films_the_episodes(runs, tmp_path):
    video = tmp_path / "episode.mp4"
    try:
        result = bsg.evaluate(runs["on_policy"], episodes=1, render=video, width=64, height=48)
    except RuntimeError as error:
        if "EGL" in str(error):
            pytest.skip(f"no EGL driver to render with: {error}")
        raise
    # An episode of n steps gives n + 1 frames (render/episode_recorders.h).
    assert result["video_frames"] == result["lengths"][0] + 1
    assert video.stat().st_size > 0


@pytest.mark.parametrize("make_bad", [
    lambda root: root / "missing",
    lambda root: root,  # a directory without a run
    lambda root: (root / "config.yaml").write_text("env_id: [") and root,
])
def test_bad_run_directories_raise_one_clear_runtime_error(make_bad, tmp_path):
    bad = make_bad(tmp_path)
    for call in (bsg.load_policy, bsg.evaluate):
        with pytest.raises(RuntimeError) as error:
            call(bad)
        message = str(error.value)
        assert "\n" not in message.strip() and str(tmp_path) in message


def test_a_corrupt_checkpoint_is_named(runs, tmp_path):
    import shutil
    copy = tmp_path / "copy"
    shutil.copytree(runs["on_policy"], copy)
    (copy / "checkpoint.bin").write_bytes(b"not a checkpoint")
    with pytest.raises(RuntimeError, match="checkpoint.bin"):
        bsg.load_policy(copy)


def test_bad_observations_and_arguments_raise_value_or_type_errors(runs):
    policy = bsg.load_policy(runs["on_policy"])
    with pytest.raises(ValueError, match=r"\(2,\)|shape"):
        policy.act(np.zeros(2))
    with pytest.raises(ValueError):
        policy.act(np.zeros((2, 3, 4)))
    with pytest.raises(ValueError, match="mean' or 'sampled"):
        bsg.evaluate(runs["on_policy"], actions="greedy")
    with pytest.raises(TypeError):
        bsg.evaluate(runs["on_policy"], render=True)
    with pytest.raises(RuntimeError, match="sampled evaluation actions"):
        bsg.evaluate(runs["off_policy"], actions="sampled")
