"""examples/python/ppo_lagrangian.py (it needs Gymnasium; skipped where none is found,
gymnasium_import.py): its hand-written gradients equal finite differences of its
losses (the networks' backward pass and PPO's clipped surrogate, clipped and not),
GAE equals the sum it abbreviates, and a short run over gymnasium.make("bsg/...")
logs every episode's return and cost, to stdout, to --csv and as a --plot PNG."""

import csv
import importlib.util
import os
import pathlib
import subprocess
import sys

from gymnasium_import import import_gymnasium

gymnasium = import_gymnasium()

import numpy as np  # noqa: E402
import pytest  # noqa: E402

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "ppo_lagrangian.py"
spec = importlib.util.spec_from_file_location("ppo_lagrangian", EXAMPLE)
ppo = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ppo)


def numeric_gradient(f, params, h=1e-6):
    grads = []
    for p in params:
        g = np.zeros_like(p)
        for idx in np.ndindex(p.shape):
            old = p[idx]
            p[idx] = old + h
            up = f()
            p[idx] = old - h
            down = f()
            p[idx] = old
            g[idx] = (up - down) / (2 * h)
        grads.append(g)
    return grads


def test_mlp_backward_equals_finite_differences():
    rng = np.random.default_rng(0)
    mlp = ppo.MLP([5, 7, 6, 3], rng, out_scale=1.0)
    x, w = rng.standard_normal((4, 5)), rng.standard_normal((4, 3))
    loss = lambda: float((mlp.forward(x) * w).sum())  # noqa: E731  dLoss/dOutput = w
    loss()
    analytic = mlp.backward(w)
    for a, n in zip(analytic, numeric_gradient(loss, mlp.params)):
        np.testing.assert_allclose(a, n, rtol=1e-6, atol=1e-8)


@pytest.mark.parametrize("shift", [0.0, 0.5])  # 0.5: ratios far from 1, many terms clipped
def test_policy_gradient_equals_finite_differences_of_the_clipped_surrogate(shift):
    rng = np.random.default_rng(1)
    agent = ppo.Agent(4, 2, rng)
    agent.log_std[:] = [-0.3, 0.2]
    obs = rng.standard_normal((16, 4))
    actions = rng.standard_normal((16, 2))
    old_logp = agent.log_prob(agent.actor.forward(obs), actions) + rng.uniform(-shift, shift, 16)
    advantage = rng.standard_normal(16)
    loss = lambda: ppo.policy_loss_and_gradients(  # noqa: E731
        agent, obs, actions, old_logp, advantage, 0.2)[0]
    _, analytic = ppo.policy_loss_and_gradients(agent, obs, actions, old_logp, advantage, 0.2)
    numeric = numeric_gradient(loss, agent.actor.params + [agent.log_std])
    if shift:
        ratio = np.exp(agent.log_prob(agent.actor.forward(obs), actions) - old_logp)
        assert np.sum(np.abs(ratio - 1) > 0.2) >= 4, "some terms are clipped"
    for a, n in zip(analytic, numeric):
        np.testing.assert_allclose(a, n, rtol=1e-5, atol=1e-8)


def test_gae_equals_its_sum_of_discounted_td_errors():
    rng = np.random.default_rng(2)
    rewards, values = rng.standard_normal(7), rng.standard_normal(7)
    dones = np.array([0, 0, 1, 0, 0, 0, 0], float)
    gamma, lam, last = 0.9, 0.8, 0.37
    advantages, returns = ppo.gae(rewards, values, dones, last, gamma, lam)
    next_values = np.append(values[1:], last) * (1 - dones)
    delta = rewards + gamma * next_values - values
    for t in range(7):
        end = 3 if t <= 2 else 7  # the episode ends at step 2
        expected = sum((gamma * lam) ** (k - t) * delta[k] for k in range(t, end))
        assert advantages[t] == pytest.approx(expected, rel=1e-12, abs=1e-12)
    np.testing.assert_allclose(returns, advantages + values)


def test_a_short_run_logs_return_and_cost_of_every_episode(tmp_path):
    # The subprocess finds the same gymnasium this test found.
    path = os.pathsep.join([str(pathlib.Path(gymnasium.__file__).parents[1])] + sys.path)
    out = subprocess.run(
        [sys.executable, str(EXAMPLE), "--env-id", "bsg/SafetyBallCircle-v0",
         "--total-timesteps", "1024", "--num-steps", "512", "--update-epochs", "2",
         "--csv", str(tmp_path / "progress.csv"), "--plot", str(tmp_path / "curve.png")],
        check=True, capture_output=True, text=True,
        env={**os.environ, "PYTHONPATH": path}).stdout
    lines = [line for line in out.splitlines() if line.startswith("global_step=")]
    assert len(lines) == 4  # 1024 steps of 250-step episodes
    assert all("episodic_return=" in line and "episodic_cost=" in line for line in lines)
    assert f"gymnasium {gymnasium.__version__}" in out
    rows = list(csv.DictReader(open(tmp_path / "progress.csv")))
    assert [int(r["global_step"]) for r in rows] == [250, 500, 750, 1000]
    assert all(float(r["episodic_cost"]) >= 0 for r in rows)
    assert (tmp_path / "curve.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
