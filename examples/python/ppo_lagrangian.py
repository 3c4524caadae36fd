#!/usr/bin/python3
"""PPO-Lagrangian on gymnasium.make("bsg/..."), in the style of CleanRL's
single-file ppo_continuous_action.py, with NumPy alone (no torch needed).

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/ppo_lagrangian.py \
        --env-id bsg/SafetyBallCircle-v0 --total-timesteps 300000 --csv progress.csv

It needs Gymnasium (0.28, 0.29 or 1.x) and prints one line per finished
episode: the global step, the episode's return and cost, and the Lagrange
multiplier. The cost is ``info["cost"]`` (bsg's Gymnasium API); the
multiplier rises while the mean episode cost of a rollout exceeds the
environment's cost limit and weights the cost advantage against the reward
advantage, as in Ray, Achiam and Amodei's PPO-Lagrangian (bsg's ppo-lag).
As CleanRL: one environment, 2048 steps a rollout, GAE (gamma 0.99, lambda
0.95), 10 epochs of 32 minibatches, clip 0.2, Adam at 3e-4 annealed to 0,
gradients clipped to norm 0.5, observations normalised (NormalizeObservation)
and actions clipped (ClipAction); the networks are 64-64 tanh MLPs.
"""

import argparse
import csv
import sys
import time

import numpy as np

try:
    import gymnasium
except ImportError:
    sys.exit("ppo_lagrangian.py needs Gymnasium 0.28, 0.29 or 1.x (not installed); "
             "bsg itself works without it")

import bsg  # noqa: F401  (registers the bsg/ ids)


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--env-id", default="bsg/SafetyBallCircle-v0")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--total-timesteps", type=int, default=300_000)
    p.add_argument("--learning-rate", type=float, default=3e-4)
    p.add_argument("--num-steps", type=int, default=2048, help="steps per rollout")
    p.add_argument("--gamma", type=float, default=0.99)
    p.add_argument("--gae-lambda", type=float, default=0.95)
    p.add_argument("--num-minibatches", type=int, default=32)
    p.add_argument("--update-epochs", type=int, default=10)
    p.add_argument("--clip-coef", type=float, default=0.2)
    p.add_argument("--max-grad-norm", type=float, default=0.5)
    p.add_argument("--cost-limit", type=float, default=None,
                   help="default: the environment's (bsg_spec.cost_limit)")
    p.add_argument("--lagrangian-lr", type=float, default=0.05)
    p.add_argument("--csv", default=None, help="write global_step,return,cost,lambda per episode")
    p.add_argument("--plot", default=None,
                   help="draw return and cost per episode (and their means over 20) as a PNG "
                        "(needs matplotlib: Debian's python3-matplotlib)")
    args = p.parse_args(argv)
    if args.num_steps % args.num_minibatches:
        p.error("--num-steps must be a multiple of --num-minibatches")
    return args


def make_env(env_id, seed):
    env = gymnasium.make(env_id)
    env = gymnasium.wrappers.ClipAction(env)
    env = gymnasium.wrappers.NormalizeObservation(env)
    env.action_space.seed(seed)
    return env


class MLP:
    """tanh MLP with a linear output; forward keeps what backward needs."""

    def __init__(self, sizes, rng, out_scale):
        self.params = []
        for i, (n_in, n_out) in enumerate(zip(sizes[:-1], sizes[1:])):
            scale = out_scale if i == len(sizes) - 2 else np.sqrt(2)
            q, _ = np.linalg.qr(rng.standard_normal((max(n_in, n_out), min(n_in, n_out))))
            w = (q if n_in >= n_out else q.T)[:n_in, :n_out] * scale  # orthogonal, as CleanRL
            self.params += [w, np.zeros(n_out)]

    def forward(self, x):
        self.inputs = [x]
        for i in range(0, len(self.params), 2):
            x = x @ self.params[i] + self.params[i + 1]
            if i + 2 < len(self.params):
                x = np.tanh(x)
            self.inputs.append(x)
        return x

    def backward(self, grad_out):
        """Gradients of the parameters for dLoss/dOutput = grad_out (after forward)."""
        grads = [None] * len(self.params)
        g = grad_out
        for i in range(len(self.params) - 2, -1, -2):
            grads[i] = self.inputs[i // 2].T @ g
            grads[i + 1] = g.sum(axis=0)
            if i > 0:
                g = (g @ self.params[i].T) * (1 - self.inputs[i // 2] ** 2)
        return grads


class Adam:
    def __init__(self, params, lr, max_grad_norm):
        self.params, self.lr, self.max_grad_norm = params, lr, max_grad_norm
        self.m = [np.zeros_like(p) for p in params]
        self.v = [np.zeros_like(p) for p in params]
        self.t = 0

    def step(self, grads):
        norm = np.sqrt(sum(float((g ** 2).sum()) for g in grads))
        scale = min(1.0, self.max_grad_norm / (norm + 1e-6))
        self.t += 1
        for p, g, m, v in zip(self.params, grads, self.m, self.v):
            g = g * scale
            m[:] = 0.9 * m + 0.1 * g
            v[:] = 0.999 * v + 0.001 * g * g
            p -= self.lr * (m / (1 - 0.9 ** self.t)) / (np.sqrt(v / (1 - 0.999 ** self.t)) + 1e-5)


class Agent:
    """Gaussian policy (state-independent log std) and two critics: reward and cost."""

    def __init__(self, obs_dim, act_dim, rng):
        self.actor = MLP([obs_dim, 64, 64, act_dim], rng, out_scale=0.01)
        self.log_std = np.zeros(act_dim)
        self.critic = MLP([obs_dim, 64, 64, 1], rng, out_scale=1.0)
        self.cost_critic = MLP([obs_dim, 64, 64, 1], rng, out_scale=1.0)

    def log_prob(self, mean, action):
        z = (action - mean) / np.exp(self.log_std)
        return (-0.5 * z ** 2 - self.log_std - 0.5 * np.log(2 * np.pi)).sum(axis=-1)

    def act(self, obs, rng):
        mean = self.actor.forward(obs[None])[0]
        action = mean + np.exp(self.log_std) * rng.standard_normal(mean.shape)
        values = (self.critic.forward(obs[None])[0, 0], self.cost_critic.forward(obs[None])[0, 0])
        return action, self.log_prob(mean, action), values


def gae(rewards, values, dones, last_value, gamma, lam):
    """Generalised advantage estimates and returns; dones[t]: the episode ended at step t."""
    advantages = np.zeros_like(rewards)
    last = 0.0
    for t in reversed(range(len(rewards))):
        next_value = last_value if t == len(rewards) - 1 else values[t + 1]
        alive = 1.0 - dones[t]
        delta = rewards[t] + gamma * next_value * alive - values[t]
        last = delta + gamma * lam * alive * last
        advantages[t] = last
    return advantages, advantages + values


def policy_loss_and_gradients(agent, obs, actions, old_logp, advantage, clip_coef):
    """PPO's clipped surrogate loss, mean of -min(r A, clip(r, 1 - c, 1 + c) A) with
    r = pi(a|s) / pi_old(a|s), and its gradients (the actor's, then log_std's)."""
    mean = agent.actor.forward(obs)
    ratio = np.exp(agent.log_prob(mean, actions) - old_logp)
    clipped = np.clip(ratio, 1 - clip_coef, 1 + clip_coef)
    loss = -np.minimum(ratio * advantage, clipped * advantage).mean()
    # d loss / d log pi = -r A / n where the unclipped term is the smaller, else 0.
    active = ratio * advantage <= clipped * advantage
    dlogp = np.where(active, -ratio * advantage, 0.0) / len(obs)
    std2 = np.exp(2 * agent.log_std)
    diff = actions - mean
    grads = agent.actor.backward(dlogp[:, None] * diff / std2)
    grads.append((dlogp[:, None] * (diff ** 2 / std2 - 1)).sum(axis=0))
    return loss, grads


def ppo_update(agent, optimizers, batch, args, multiplier, rng):
    obs, actions, old_logp, adv_r, ret_r, adv_c, ret_c = batch
    n = len(obs)
    size = n // args.num_minibatches
    for _ in range(args.update_epochs):
        order = rng.permutation(n)
        for start in range(0, n, size):
            idx = order[start:start + size]
            a_r = (adv_r[idx] - adv_r[idx].mean()) / (adv_r[idx].std() + 1e-8)
            a_c = adv_c[idx] - adv_c[idx].mean()
            advantage = (a_r - multiplier * a_c) / (1 + multiplier)
            _, grads = policy_loss_and_gradients(agent, obs[idx], actions[idx], old_logp[idx],
                                                 advantage, args.clip_coef)
            optimizers["actor"].step(grads)
            for name, critic, target in (("critic", agent.critic, ret_r),
                                         ("cost_critic", agent.cost_critic, ret_c)):
                value = critic.forward(obs[idx])[:, 0]
                optimizers[name].step(critic.backward(((value - target[idx]) / len(idx))[:, None]))


def plot(path, rows, env_id, cost_limit):
    """Return and cost of every episode against the global step, with running means."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    steps, returns, costs = (np.array([row[i] for row in rows]) for i in range(3))
    window = min(20, len(rows))
    smooth = lambda y: np.convolve(y, np.ones(window) / window, mode="valid")  # noqa: E731
    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for ax, values, name in ((axes[0], returns, "episodic return"), (axes[1], costs, "episodic cost")):
        ax.plot(steps, values, ".", ms=2, alpha=0.35, color="tab:blue" if ax is axes[0] else "tab:red")
        ax.plot(steps[window - 1:], smooth(values), color="black", lw=1.5,
                label=f"mean of {window} episodes")
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    axes[1].axhline(cost_limit, color="tab:green", ls="--", label=f"cost limit {cost_limit:g}")
    axes[0].legend(loc="lower right")
    axes[1].legend(loc="upper right")
    axes[1].set_xlabel("environment steps")
    axes[0].set_title(f"ppo_lagrangian.py on {env_id}", fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None):
    args = parse_args(argv)
    rng = np.random.default_rng(args.seed)
    env = make_env(args.env_id, args.seed)
    cost_limit = (args.cost_limit if args.cost_limit is not None
                  else float(env.unwrapped.bsg_spec.cost_limit))
    obs_dim, act_dim = env.observation_space.shape[0], env.action_space.shape[0]
    agent = Agent(obs_dim, act_dim, rng)
    optimizers = {"actor": Adam(agent.actor.params + [agent.log_std], args.learning_rate,
                                args.max_grad_norm),
                  "critic": Adam(agent.critic.params, args.learning_rate, args.max_grad_norm),
                  "cost_critic": Adam(agent.cost_critic.params, args.learning_rate,
                                      args.max_grad_norm)}
    multiplier = 0.0
    writer, rows = None, []
    if args.csv:
        csv_file = open(args.csv, "w", newline="")
        writer = csv.writer(csv_file)
        writer.writerow(["global_step", "episodic_return", "episodic_cost", "lagrange_multiplier"])
    print(f"{args.env_id}: cost limit {cost_limit:g}, gymnasium {gymnasium.__version__}")
    obs, _ = env.reset(seed=args.seed)
    episode_return = episode_cost = 0.0
    global_step, started = 0, time.time()
    num_updates = args.total_timesteps // args.num_steps
    for update in range(num_updates):
        fraction = 1.0 - update / num_updates  # linear annealing, as CleanRL
        for optimizer in optimizers.values():
            optimizer.lr = fraction * args.learning_rate
        T = args.num_steps
        buf = {k: np.zeros((T, obs_dim) if k == "obs" else (T, act_dim) if k == "actions" else T)
               for k in ("obs", "actions", "logp", "rewards", "costs", "dones", "values", "cvalues")}
        episode_costs = []
        for t in range(T):
            global_step += 1
            action, logp, (value, cvalue) = agent.act(obs, rng)
            buf["obs"][t], buf["actions"][t], buf["logp"][t] = obs, action, logp
            buf["values"][t], buf["cvalues"][t] = value, cvalue
            obs, reward, terminated, truncated, info = env.step(action)
            buf["rewards"][t], buf["costs"][t] = reward, info["cost"]
            buf["dones"][t] = terminated or truncated
            episode_return += reward
            episode_cost += info["cost"]
            if terminated or truncated:
                print(f"global_step={global_step}, episodic_return={episode_return:.1f}, "
                      f"episodic_cost={episode_cost:.0f}, lambda={multiplier:.3f}", flush=True)
                rows.append((global_step, episode_return, episode_cost, multiplier))
                if writer:
                    writer.writerow(rows[-1])
                episode_costs.append(episode_cost)
                episode_return = episode_cost = 0.0
                obs, _ = env.reset()
        last_value = agent.critic.forward(obs[None])[0, 0]
        last_cvalue = agent.cost_critic.forward(obs[None])[0, 0]
        adv_r, ret_r = gae(buf["rewards"], buf["values"], buf["dones"], last_value,
                           args.gamma, args.gae_lambda)
        adv_c, ret_c = gae(buf["costs"], buf["cvalues"], buf["dones"], last_cvalue,
                           args.gamma, args.gae_lambda)
        if episode_costs:  # gradient ascent on lambda (J_c - d), kept >= 0
            multiplier = max(0.0, multiplier + args.lagrangian_lr *
                             (np.mean(episode_costs) - cost_limit))
        ppo_update(agent, optimizers, (buf["obs"], buf["actions"], buf["logp"], adv_r, ret_r,
                                       adv_c, ret_c), args, multiplier, rng)
    if writer:
        csv_file.close()
    print(f"{global_step} steps in {time.time() - started:.0f} s")
    if args.plot and rows:
        plot(args.plot, rows, args.env_id, cost_limit)
        print(f"plot {args.plot}")
    env.close()


if __name__ == "__main__":
    main()
