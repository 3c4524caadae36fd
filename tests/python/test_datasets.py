"""bsg.datasets (python/bsg/datasets.py): DSRL's normalised score on
hand-computed cases (eps = 1 only at a zero cost limit); a file made by
`bsg collect` read with the keys, shapes and dtypes DSRL's get_dataset
asserts, its episodes starting at the observations the Python environment
gives for the documented seeds (computed here from SplitMix64's formula), and
bad files refused with one line."""

import subprocess

import numpy as np
import pytest

import bsg
from bsg import datasets

h5py = pytest.importorskip("h5py")


def test_normalized_score_by_hand():
    # Rewards between 100 and 300: 150 is a quarter of the way; cost 10 of a limit 20 is one half.
    assert datasets.normalized_score(150.0, 10.0, 20.0, 100.0, 300.0) == (0.25, 0.5)
    # Below the dataset's worst episode, above its best, over the limit.
    assert datasets.normalized_score(50.0, 30.0, 20.0, 100.0, 300.0) == (-0.25, 1.5)
    assert datasets.normalized_score(400.0, 0.0, 20.0, 100.0, 300.0) == (1.5, 0.0)
    # kappa = 0: eps = 1, so cost 0 scores (0 + 1) / (0 + 1) = 1 and cost 3 scores 4.
    assert datasets.normalized_score(100.0, 0.0, 0.0, 100.0, 300.0) == (0.0, 1.0)
    assert datasets.normalized_score(100.0, 3.0, 0.0, 100.0, 300.0) == (0.0, 4.0)
    # kappa = 1: eps = 0, cost 3 scores 3.
    assert datasets.normalized_score(100.0, 3.0, 1.0, 100.0, 300.0)[1] == 3.0
    with pytest.raises(ValueError, match="span no range"):
        datasets.normalized_score(1.0, 1.0, 1.0, 5.0, 5.0)


MASK = (1 << 64) - 1
GAMMA = 0x9E3779B97F4A7C15


def mix(z):
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
    return z ^ (z >> 31)


def derive_seed(seed, stream, rank, index):
    h = mix((seed + GAMMA) & MASK)
    for word in (stream, rank, index):
        h = mix((h + GAMMA * (word + 1)) & MASK)
    return h


def test_collected_file_reads_as_dsrl_reads_it(bsg_binary, tmp_path):
    path = tmp_path / "circle.hdf5"
    subprocess.run([bsg_binary, "collect", "--out", str(path), "--env", "SafetyBallCircle-v0", "--policy",
                    "random", "--episodes", "3", "--seed", "5"], check=True, capture_output=True)
    data = datasets.load(str(path))
    env = bsg.make("SafetyBallCircle-v0")
    T = env.spec.max_episode_steps
    n = 3 * T
    obs_dim = env.observation_space.shape[0]
    act_dim = env.action_space.shape[0]
    assert data["observations"].shape == (n, obs_dim) and data["next_observations"].shape == (n, obs_dim)
    assert data["actions"].shape == (n, act_dim)
    for key in ("rewards", "costs", "terminals", "timeouts"):
        assert data[key].shape == (n,), key
    for key in datasets.REQUIRED_KEYS:
        assert data[key].dtype == np.float32, key
    # Episodes of T steps end by the time limit, never by termination.
    ends = np.flatnonzero(data["timeouts"] == 1)
    assert list(ends) == [T - 1, 2 * T - 1, 3 * T - 1]
    assert not data["terminals"].any()
    # Each episode starts where the environment starts for seed derive_seed(5, environment = 4, 0, e),
    # and within an episode each row's next observation is the following row's observation.
    for e, start in enumerate((0, T, 2 * T)):
        first, _ = env.reset(seed=derive_seed(5, 4, 0, e))
        np.testing.assert_array_equal(data["observations"][start], np.asarray(first, dtype=np.float32))
        np.testing.assert_array_equal(data["next_observations"][start:start + T - 1],
                                      data["observations"][start + 1:start + T])
    # The actions of the random policy lie in the declared bounds; costs are 0 or 1.
    assert data["actions"].min() >= -1.0 and data["actions"].max() <= 1.0
    assert set(np.unique(data["costs"])) <= {0.0, 1.0}
    # The stored constants are the episode returns' range.
    info = datasets.attributes(str(path))
    reward_returns, cost_returns, lengths = datasets.episode_returns(data)
    assert list(lengths) == [T, T, T]
    assert info["min_episode_reward"] == pytest.approx(reward_returns.min(), rel=1e-6)
    assert info["max_episode_reward"] == pytest.approx(reward_returns.max(), rel=1e-6)
    assert info["max_episode_cost"] == pytest.approx(cost_returns.max())
    assert info["env_id"] == "SafetyBallCircle-v0" and info["seed"] == "5"
    r, c = datasets.file_normalized_score(str(path), reward_returns.max(), info["cost_limit"])
    assert r == pytest.approx(1.0) and c == pytest.approx(1.0)


def test_bad_files_are_one_line(tmp_path):
    text = tmp_path / "x.hdf5"
    text.write_text("not hdf5\n")
    with pytest.raises(ValueError, match=r"^dataset file .*x.hdf5: not an HDF5 file$"):
        datasets.load(str(text))
    with pytest.raises(ValueError, match="no such file"):
        datasets.load(str(tmp_path / "missing.hdf5"))
    partial = tmp_path / "partial.hdf5"
    with h5py.File(partial, "w") as f:
        for key in ("observations", "next_observations"):
            f[key] = np.zeros((4, 3), np.float32)
        f["actions"] = np.zeros((4, 2), np.float32)
        for key in ("rewards", "costs", "terminals"):
            f[key] = np.zeros(4, np.float32)
    with pytest.raises(ValueError, match="missing key 'timeouts'"):
        datasets.load(str(partial))


def test_truncated_or_corrupted_files_are_one_line_naming_the_file(bsg_binary, tmp_path):
    whole = tmp_path / "whole.hdf5"
    subprocess.run([bsg_binary, "collect", "--out", str(whole), "--env", "SafetyBallCircle-v0", "--policy",
                    "random", "--episodes", "20", "--seed", "1"], check=True, capture_output=True)
    size = whole.stat().st_size
    # The first half, as `head -c` leaves it.
    half = tmp_path / "half.hdf5"
    subprocess.run(f"head -c {size // 2} {whole} > {half}", shell=True, check=True)
    # The whole length with 4 KiB of its middle overwritten: the gzip chunks there no longer inflate.
    flipped = tmp_path / "flipped.hdf5"
    data = bytearray(whole.read_bytes())
    data[size // 3:size // 3 + 4096] = b"\xab" * 4096
    flipped.write_bytes(bytes(data))
    for damaged in (half, flipped):
        with pytest.raises(ValueError) as caught:
            datasets.load(str(damaged))
        message = str(caught.value)
        assert message.startswith(f"dataset file {damaged}: truncated or corrupted (")
        assert "\n" not in message
    with pytest.raises(ValueError, match=r"^dataset file .*half.hdf5: truncated or corrupted \("):
        datasets.attributes(str(half))
