#!/usr/bin/env python3
"""The off-policy benchmark's comparison (docs/algorithms.md#off-policy-learners): one SAC-Lag
gradient step in PyTorch on one thread, with the shapes and the arithmetic of
bsg_off_policy_update_bench: SafetyBallCircle-v0's 8 observations and 2 actions, batch 256, ReLU
(FSRL's) and tanh networks of 64, 128 and 256 units, twin reward critics, one cost critic, the squashed Gaussian
actor and the temperature, Adam on each, Polyak targets. Prints milliseconds per step (wall and
process CPU time). Optional: torch is not a dependency of bsg; where it is missing this prints
SKIPPED and exits 0.

Usage: /usr/bin/python3 tests/bench/torch_sac_lag_update.py [--serve]
--serve: after the banner line, read requests "ACTIVATION HIDDEN SECONDS" (e.g. "relu 128 1.0") one per
line on standard input and answer each with one line "WALL_MS CPU_MS STEPS", so that
bsg_off_policy_update_bench --torch can alternate its own rounds with PyTorch's.
"""
import math
import os
import sys
import time

# One thread everywhere: Debian's torch calls the system BLAS (OpenBLAS with libopenblas0-pthread),
# whose own thread pool torch.set_num_threads does not govern.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

try:
    import torch
    from torch import nn
except ImportError:  # torch is an optional comparison
    print("  torch SKIPPED: PyTorch is not installed (Debian: python3-torch with libopenblas0-pthread)")
    raise SystemExit(0)

OBSERVATIONS, ACTIONS, BATCH = 8, 2, 256


def mlp(inputs, hidden, outputs, activation):
    return nn.Sequential(nn.Linear(inputs, hidden), activation(), nn.Linear(hidden, hidden), activation(),
                         nn.Linear(hidden, outputs))


class SacLag:
    def __init__(self, hidden, activation):
        self.actor = mlp(OBSERVATIONS, hidden, 2 * ACTIONS, activation)
        self.critics = [mlp(OBSERVATIONS + ACTIONS, hidden, 1, activation) for _ in range(3)]  # Q1, Q2, Q_C
        self.targets = [mlp(OBSERVATIONS + ACTIONS, hidden, 1, activation) for _ in range(3)]
        for target, critic in zip(self.targets, self.critics):
            target.load_state_dict(critic.state_dict())
            for p in target.parameters():
                p.requires_grad_(False)
        self.actor_opt = torch.optim.Adam(self.actor.parameters(), lr=3e-4)
        self.critic_opts = [torch.optim.Adam(c.parameters(), lr=1e-3) for c in self.critics]
        self.log_alpha = torch.tensor([math.log(0.2)], requires_grad=True)
        self.alpha_opt = torch.optim.Adam([self.log_alpha], lr=3e-4)
        self.lam = 0.5

    def sample(self, obs):
        out = self.actor(obs)
        mu, log_std = out[:, :ACTIONS], out[:, ACTIONS:].clamp(-20, 2)
        std = log_std.exp()
        eps = torch.randn_like(mu)
        u = mu + std * eps
        a = torch.tanh(u)
        log_prob = (-0.5 * eps.pow(2) - log_std - 0.5 * math.log(2 * math.pi)).sum(-1)
        log_prob -= (2 * (math.log(2) - u - nn.functional.softplus(-2 * u))).sum(-1)
        return a, log_prob

    def update(self, batch):
        obs, act, rew, cost, nxt, disc, term = batch
        alpha = self.log_alpha.exp().detach()
        with torch.no_grad():
            a2, logp2 = self.sample(nxt)
            x2 = torch.cat([nxt, a2], -1)
            q_next = torch.min(self.targets[0](x2), self.targets[1](x2)).squeeze(-1) - alpha * logp2
            y = rew + disc * (1 - term) * q_next
            yc = cost + disc * (1 - term) * self.targets[2](x2).squeeze(-1)
        x = torch.cat([obs, act], -1)
        for critic, opt, target in zip(self.critics, self.critic_opts, (y, y, yc)):
            loss = (critic(x).squeeze(-1) - target).pow(2).mean()
            opt.zero_grad()
            loss.backward()
            opt.step()
        a, logp = self.sample(obs)
        xa = torch.cat([obs, a], -1)
        q = torch.min(self.critics[0](xa), self.critics[1](xa)).squeeze(-1)
        qc = self.critics[2](xa).squeeze(-1)
        actor_loss = ((alpha * logp - q + self.lam * qc) / (1 + self.lam)).mean()
        self.actor_opt.zero_grad()
        actor_loss.backward()
        self.actor_opt.step()
        alpha_loss = -(self.log_alpha * (logp.detach() + (-ACTIONS))).mean()
        self.alpha_opt.zero_grad()
        alpha_loss.backward()
        self.alpha_opt.step()
        with torch.no_grad():
            for target, critic in zip(self.targets, self.critics):
                for pt, p in zip(target.parameters(), critic.parameters()):
                    pt.mul_(0.995).add_(0.005 * p)


ACTIVATIONS = {"relu": nn.ReLU, "tanh": nn.Tanh}


def make_learner(name, hidden):
    learner = SacLag(hidden, ACTIVATIONS[name])
    batch = (torch.rand(BATCH, OBSERVATIONS) * 2 - 1, torch.rand(BATCH, ACTIONS) * 2 - 1, torch.rand(BATCH),
             torch.rand(BATCH), torch.rand(BATCH, OBSERVATIONS) * 2 - 1, torch.full((BATCH,), 0.99),
             torch.zeros(BATCH))
    for _ in range(20):  # warm-up
        learner.update(batch)
    return learner, batch


def time_steps(learner, batch, seconds):
    """(wall ms, process CPU ms, steps) per step over at least `seconds`."""
    steps, start, cpu_start = 0, time.perf_counter(), time.process_time()
    while time.perf_counter() - start < seconds:
        for _ in range(10):
            learner.update(batch)
        steps += 10
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu_start
    return 1e3 * wall / steps, 1e3 * cpu / steps, steps


def serve():
    learners = {}
    for line in sys.stdin:
        fields = line.split()
        if not fields:
            continue
        if len(fields) != 3 or fields[0] not in ACTIVATIONS or not fields[1].isdigit():
            print(f"error: bad request {line.strip()!r}, expected ACTIVATION HIDDEN SECONDS", flush=True)
            continue
        key = (fields[0], int(fields[1]))
        if key not in learners:
            learners[key] = make_learner(*key)
        wall, cpu, steps = time_steps(*learners[key], float(fields[2]))
        print(f"{wall:.6f} {cpu:.6f} {steps}", flush=True)


def main():
    torch.set_num_threads(1)
    torch.manual_seed(1)
    blas = "unknown"
    try:
        with open("/proc/self/maps", encoding="utf-8") as maps:
            loaded = maps.read()
        blas = "OpenBLAS" if "openblas" in loaded else ("netlib (generic)" if "libblas" in loaded else blas)
    except OSError:
        pass
    print(f"  torch {torch.__version__}, {torch.get_num_threads()} thread, BLAS loaded: {blas}", flush=True)
    if "--serve" in sys.argv[1:]:
        serve()
        return
    for name in ACTIVATIONS:
        for hidden in (64, 128, 256):
            wall, cpu, steps = time_steps(*make_learner(name, hidden), 2.0)
            print(f"  torch float32 {name:<4} {hidden:3d} x {hidden:<3d}  {wall:7.3f} ms wall  "
                  f"{cpu:7.3f} ms cpu  ({steps} steps)", flush=True)


if __name__ == "__main__":
    main()
