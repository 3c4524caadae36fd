#!/usr/bin/env python3
"""The offline benchmark's comparison (docs/datasets.md, each learner's "Speed"): one gradient step of
CPQ, BCQ-Lag and COptiDICE in PyTorch on one thread, as OSRL's algorithms/{cpq,bcql,coptidice}.py
take it (the same networks, losses and optimiser steps, in their order; written here from that math),
at the shapes of OSRL's Bullet configs (examples/configs/*_configs.py): SafetyBallCircle-v0's 8
observations and 2 actions, batch 512, actor and critics 256 x 256, the VAE 400 x 400 with a latent of
2|A|, 10 sampled actions, num_q = num_qc = 2 (BCQ-Lag: two heads of two critics each, OSRL's
EnsembleDoubleQCritic), num_nu = num_chi = 2. Prints microseconds per step (medians over the steps,
wall and process CPU time) in float32 and float64. Optional: torch is not a dependency of bsg; where it
is missing this prints SKIPPED and exits 0.

Usage: /usr/bin/python3 tests/bench/torch_offline_updates.py [--serve]
--serve: after the banner line, read requests "LEARNER DTYPE SECONDS" (e.g. "cpq float32 1.0";
learners cpq, bcq-lag, coptidice) one per line on standard input and answer each with one line
"WALL_US CPU_US STEPS", so that bsg_offline_update_bench --torch can alternate its rounds with PyTorch's.
"""
import copy
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
    from torch.nn import functional as F
except ImportError:  # torch is an optional comparison
    print("  torch SKIPPED: PyTorch is not installed (Debian: python3-torch with libopenblas0-pthread)")
    raise SystemExit(0)

OBSERVATIONS, ACTIONS, BATCH = 8, 2, 512
HIDDEN, VAE_HIDDEN, LATENT, SAMPLED = 256, 400, 2 * ACTIONS, 10
GAMMA, TAU, BETA = 0.99, 0.005, 0.5
COST_THRESHOLD = 10 * (1 - GAMMA**200) / (1 - GAMMA) / 200  # OSRL's for cost limit 10, T = 200


def mlp(inputs, outputs, activation=nn.ReLU, output_activation=None):
    layers = [nn.Linear(inputs, HIDDEN), activation(), nn.Linear(HIDDEN, HIDDEN), activation(),
              nn.Linear(HIDDEN, outputs)]
    return nn.Sequential(*(layers + ([output_activation()] if output_activation else [])))


def frozen_copy(module):
    target = copy.deepcopy(module)
    for p in target.parameters():
        p.requires_grad_(False)
    return target


def soft_update(target, source):
    with torch.no_grad():
        for pt, p in zip(target.parameters(), source.parameters()):
            pt.mul_(1 - TAU).add_(TAU * p)


def set_requires_grad(modules, flag):
    for module in modules:
        for p in module.parameters():
            p.requires_grad_(flag)


class SquashedGaussian(nn.Module):
    """s -> trunk -> (mu, log sigma), a = tanh(mu + sigma eps) (OSRL's SquashedGaussianMLPActor)."""

    def __init__(self):
        super().__init__()
        self.trunk = nn.Sequential(nn.Linear(OBSERVATIONS, HIDDEN), nn.ReLU(), nn.Linear(HIDDEN, HIDDEN), nn.ReLU())
        self.mu = nn.Linear(HIDDEN, ACTIONS)
        self.log_std = nn.Linear(HIDDEN, ACTIONS)

    def distribution(self, obs):
        h = self.trunk(obs)
        return self.mu(h), self.log_std(h).clamp(-20, 2).exp()

    def sample(self, obs):
        mu, std = self.distribution(obs)
        u = mu + std * torch.randn_like(mu)
        log_prob = (-0.5 * ((u - mu) / std).pow(2) - std.log() - 0.5 * math.log(2 * math.pi)).sum(-1)
        log_prob -= (2 * (math.log(2) - u - F.softplus(-2 * u))).sum(-1)
        return torch.tanh(u), log_prob


class Vae(nn.Module):
    """OSRL's conditional VAE: encoder [s, a] -> 400 -> 400 -> (mean, log std), decoder [s, z] -> 400 -> 400 -> A."""

    def __init__(self):
        super().__init__()
        self.encoder = nn.Sequential(nn.Linear(OBSERVATIONS + ACTIONS, VAE_HIDDEN), nn.ReLU(),
                                     nn.Linear(VAE_HIDDEN, VAE_HIDDEN), nn.ReLU())
        self.mean = nn.Linear(VAE_HIDDEN, LATENT)
        self.log_std = nn.Linear(VAE_HIDDEN, LATENT)
        self.decoder = nn.Sequential(nn.Linear(OBSERVATIONS + LATENT, VAE_HIDDEN), nn.ReLU(),
                                     nn.Linear(VAE_HIDDEN, VAE_HIDDEN), nn.ReLU(), nn.Linear(VAE_HIDDEN, ACTIONS))

    def forward(self, obs, act):
        h = self.encoder(torch.cat([obs, act], 1))
        mean, std = self.mean(h), self.log_std(h).clamp(-4, 15).exp()
        return self.decode(obs, mean + std * torch.randn_like(std)), mean, std

    def decode(self, obs, z=None):
        if z is None:
            z = torch.randn(obs.shape[0], LATENT, dtype=obs.dtype).clamp(-0.5, 0.5)
        return torch.tanh(self.decoder(torch.cat([obs, z], 1)))

    def step(self, optimiser, obs, act):
        recon, mean, std = self(obs, act)
        kl = -0.5 * (1 + std.pow(2).log() - mean.pow(2) - std.pow(2)).mean()
        loss = F.mse_loss(recon, act) + BETA * kl
        optimiser.zero_grad()
        loss.backward()
        optimiser.step()


def ensemble(count, inputs, **kwargs):
    return nn.ModuleList([mlp(inputs, 1, **kwargs) for _ in range(count)])


def values(nets, x):
    return [net(x).squeeze(-1) for net in nets]


def minimum(nets, x):
    return torch.stack(values(nets, x)).min(0).values


def adam(module, lr):
    return torch.optim.Adam(module.parameters(), lr=lr)


class Cpq:
    """OSRL's CPQ.train_one_step: VAE, reward critics, cost critics (with alpha), actor, targets."""

    def __init__(self):
        self.actor, self.vae = SquashedGaussian(), Vae()
        self.critics, self.cost_critics = ensemble(2, OBSERVATIONS + ACTIONS), ensemble(2, OBSERVATIONS + ACTIONS)
        self.actor_old = frozen_copy(self.actor)
        self.critics_old, self.cost_critics_old = frozen_copy(self.critics), frozen_copy(self.cost_critics)
        self.actor_opt, self.vae_opt = adam(self.actor, 1e-4), adam(self.vae, 1e-3)
        self.critic_opt, self.cost_critic_opt = adam(self.critics, 1e-3), adam(self.cost_critics, 1e-3)
        self.log_alpha, self.alpha_lr, self.qc_threshold = torch.tensor(0.0), 1e-4, 1.5 * COST_THRESHOLD

    def modules(self):
        return [self.actor, self.vae, self.critics, self.cost_critics, self.actor_old, self.critics_old,
                self.cost_critics_old]

    def update(self, batch):
        obs, nxt, act, rew, cost, done, _ = batch
        self.vae.step(self.vae_opt, obs, act)
        x = torch.cat([obs, act], -1)
        q_list = values(self.critics, x)
        with torch.no_grad():
            a2, _ = self.actor.sample(nxt)
            x2 = torch.cat([nxt, a2], -1)
            safe = minimum(self.cost_critics_old, x2) <= COST_THRESHOLD
            backup = rew + GAMMA * (1 - done) * safe * minimum(self.critics_old, x2)
        loss = sum(((q - backup) ** 2).mean() for q in q_list)
        self.critic_opt.zero_grad()
        loss.backward()
        self.critic_opt.step()

        qc_list = values(self.cost_critics, x)
        with torch.no_grad():
            a2, _ = self.actor.sample(nxt)
            backup = cost + GAMMA * minimum(self.cost_critics_old, torch.cat([nxt, a2], -1))
            mu, std = self.actor.distribution(obs)
            sampled = (mu + std * torch.randn(SAMPLED, *mu.shape, dtype=mu.dtype)).reshape(-1, ACTIONS)
            stacked = obs.repeat(SAMPLED, 1)
            qc_sampled = minimum(self.cost_critics_old, torch.cat([stacked, sampled], -1)).reshape(SAMPLED, -1)
            _, mean, std = self.vae(stacked, sampled)
            kl = -0.5 * (1 + std.pow(2).log() - mean.pow(2) - std.pow(2)).mean(-1).reshape(SAMPLED, -1)
            qc_ood = ((kl >= torch.quantile(kl, 0.75)) * qc_sampled).mean(0)
        loss = sum(((q - backup) ** 2).mean() for q in qc_list) - self.log_alpha.exp() * (qc_ood.mean() -
                                                                                          self.qc_threshold)
        self.cost_critic_opt.zero_grad()
        loss.backward()
        self.cost_critic_opt.step()
        self.log_alpha += self.alpha_lr * self.log_alpha.exp() * (self.qc_threshold - qc_ood.mean())
        self.log_alpha.clamp_(-5.0, 5.0)

        set_requires_grad([self.critics, self.cost_critics], False)
        a, _ = self.actor.sample(obs)
        xa = torch.cat([obs, a], -1)
        loss = -((minimum(self.cost_critics, xa) <= COST_THRESHOLD) * minimum(self.critics, xa)).mean()
        self.actor_opt.zero_grad()
        loss.backward()
        self.actor_opt.step()
        set_requires_grad([self.critics, self.cost_critics], True)

        soft_update(self.critics_old, self.critics)
        soft_update(self.cost_critics_old, self.cost_critics)
        soft_update(self.actor_old, self.actor)


class Perturbation(nn.Module):
    """BCQ's actor: clamp(a + phi tanh(xi([s, a])), -1, 1), tanh hidden layers (OSRL's)."""

    def __init__(self):
        super().__init__()
        self.net = mlp(OBSERVATIONS + ACTIONS, ACTIONS, activation=nn.Tanh, output_activation=nn.Tanh)

    def forward(self, obs, act):
        return (act + 0.05 * self.net(torch.cat([obs, act], 1))).clamp(-1, 1)


class BcqLag:
    """OSRL's BCQL.train_one_step: VAE, reward critics, cost critics, actor with the PID multiplier, targets."""

    def __init__(self):
        self.actor, self.vae = Perturbation(), Vae()
        # Two heads of num_q = 2 critics each (OSRL's EnsembleDoubleQCritic): four nets, and four for the cost.
        self.critics = [ensemble(2, OBSERVATIONS + ACTIONS) for _ in range(2)]
        self.cost_critics = [ensemble(2, OBSERVATIONS + ACTIONS) for _ in range(2)]
        self.actor_old = frozen_copy(self.actor)
        self.critics_old = [frozen_copy(head) for head in self.critics]
        self.cost_critics_old = [frozen_copy(head) for head in self.cost_critics]
        self.actor_opt, self.vae_opt = adam(self.actor, 1e-3), adam(self.vae, 1e-3)
        self.critic_opt = torch.optim.Adam([p for h in self.critics for p in h.parameters()], lr=1e-3)
        self.cost_critic_opt = torch.optim.Adam([p for h in self.cost_critics for p in h.parameters()], lr=1e-3)
        self.error_old, self.integral = 0.0, 0.0

    def modules(self):
        return [self.actor, self.vae, self.actor_old, *self.critics, *self.cost_critics, *self.critics_old,
                *self.cost_critics_old]

    def critic_step(self, heads, heads_old, optimiser, obs, nxt, act, signal, done):
        x = torch.cat([obs, act], -1)
        q_lists = [values(head, x) for head in heads]
        with torch.no_grad():
            repeated = torch.repeat_interleave(nxt, SAMPLED, 0)
            x2 = torch.cat([repeated, self.actor_old(repeated, self.vae.decode(repeated))], -1)
            q1, q2 = (minimum(head, x2) for head in heads_old)
            soft = 0.75 * torch.min(q1, q2) + 0.25 * torch.max(q1, q2)
            backup = signal + GAMMA * (1 - done) * soft.reshape(BATCH, -1).max(1)[0]
        loss = sum(((q - backup) ** 2).mean() for q_list in q_lists for q in q_list)
        optimiser.zero_grad()
        loss.backward()
        optimiser.step()

    def control(self, qc):
        error = torch.mean(qc - COST_THRESHOLD)
        difference = F.relu(error - self.error_old)
        self.integral = torch.mean(F.relu(self.integral + error))
        self.error_old = error
        return F.relu(0.1 * F.relu(error) + 0.003 * self.integral + 0.001 * difference)

    def update(self, batch):
        obs, nxt, act, rew, cost, done, _ = batch
        self.vae.step(self.vae_opt, obs, act)
        self.critic_step(self.critics, self.critics_old, self.critic_opt, obs, nxt, act, rew, done)
        self.critic_step(self.cost_critics, self.cost_critics_old, self.cost_critic_opt, obs, nxt, act, cost, done)

        frozen = [*self.critics, *self.cost_critics, self.vae]
        set_requires_grad(frozen, False)
        xa = torch.cat([obs, self.actor(obs, self.vae.decode(obs))], -1)
        q = torch.min(*(minimum(head, xa) for head in self.critics))
        qc = torch.min(*(minimum(head, xa) for head in self.cost_critics))
        with torch.no_grad():
            multiplier = self.control(qc)
        loss = -q.mean() + ((qc - COST_THRESHOLD) * multiplier).mean()
        self.actor_opt.zero_grad()
        loss.backward()
        self.actor_opt.step()
        set_requires_grad(frozen, True)

        for old, new in zip(self.critics_old + self.cost_critics_old, self.critics + self.cost_critics):
            soft_update(old, new)
        soft_update(self.actor_old, self.actor)


def soft_chi(x):
    return torch.where(x < 1, x * (torch.log(x + 1e-10) - 1) + 1, 0.5 * (x - 1) ** 2)


def soft_chi_prime_inverse(y):
    return torch.where(y < 0, torch.exp(y.clamp(max=0.0)), y + 1)


class COptiDice:
    """OSRL's COptiDICE.update: chi and tau, nu, lambda, then the actor's weighted likelihood."""

    def __init__(self, dtype):
        self.actor = SquashedGaussian()
        self.nu, self.chi = ensemble(2, OBSERVATIONS), ensemble(2, OBSERVATIONS)
        self.tau = torch.ones(1, dtype=dtype, requires_grad=True)
        self.lmbda = torch.ones(1, dtype=dtype, requires_grad=True)
        self.actor_opt, self.nu_opt, self.chi_opt = adam(self.actor, 1e-4), adam(self.nu, 1e-4), adam(self.chi, 1e-4)
        self.lmbda_opt, self.tau_opt = torch.optim.Adam([self.lmbda], lr=1e-4), torch.optim.Adam([self.tau], lr=1e-4)
        self.alpha, self.epsilon, self.initial_share = 0.5, 0.01, 1.0 / 200
        self.observations_std = torch.ones(OBSERVATIONS, dtype=dtype)
        self.actions_std = torch.full((ACTIONS,), 0.5, dtype=dtype)

    def modules(self):
        return [self.actor, self.nu, self.chi]

    def optimal_w(self, obs, nxt, rew, cost, done, lmbda):
        nu_s, nu_next = minimum(self.nu, obs), minimum(self.nu, nxt)
        e = rew - lmbda * cost + GAMMA * (1 - done) * nu_next - nu_s
        return nu_s, e, F.relu(soft_chi_prime_inverse(e / self.alpha))

    def update(self, batch):
        obs, nxt, act, rew, cost, done, initial = batch
        lmbda = F.softplus(self.lmbda)
        nu_s, e, w = self.optimal_w(obs, nxt, rew, cost, done, lmbda.detach())
        w_fixed = w.detach()
        tau = F.softplus(self.tau)
        chi_s, chi_next = minimum(self.chi, obs), minimum(self.chi, nxt)
        ell = (1 - GAMMA) * chi_s * initial / self.initial_share + w_fixed * (cost + GAMMA * (1 - done) * chi_next -
                                                                              chi_s)
        logits = ell / tau.detach()
        weights = torch.softmax(logits, 0) * BATCH
        log_weights = torch.log_softmax(logits, 0) + math.log(BATCH)
        kl = (weights * log_weights - weights + 1).mean()
        weighted_cost = (weights * w_fixed * cost).mean()
        chi_loss = (weights * ell).mean()
        self.chi_opt.zero_grad()
        chi_loss.backward(retain_graph=True)
        self.chi_opt.step()
        tau_loss = tau * (self.epsilon - kl.detach())
        self.tau_opt.zero_grad()
        tau_loss.backward()
        self.tau_opt.step()

        nu_loss = (1 - GAMMA) * (nu_s * initial / self.initial_share).mean() + (w * e - self.alpha * soft_chi(w)).mean()
        self.nu_opt.zero_grad()
        nu_loss.backward(retain_graph=True)
        self.nu_opt.step()
        lmbda_loss = lmbda * (COST_THRESHOLD - weighted_cost.detach())
        self.lmbda_opt.zero_grad()
        lmbda_loss.backward()
        self.lmbda_opt.step()

        obs_eps = torch.randn_like(obs) * self.observations_std * 0.1
        act_eps = torch.randn_like(act) * self.actions_std * 0.1
        mu, std = self.actor.distribution(obs + obs_eps)
        with torch.no_grad():
            _, _, w = self.optimal_w(obs, nxt, rew, cost, done, lmbda.detach())
        log_prob = torch.distributions.Normal(mu, std).log_prob(act + act_eps).sum(-1)
        actor_loss = -(w * log_prob).mean()
        self.actor_opt.zero_grad()
        actor_loss.backward()
        self.actor_opt.step()


DTYPES = {"float32": torch.float32, "float64": torch.float64}
LEARNERS = {"cpq": lambda dtype: Cpq(), "bcq-lag": lambda dtype: BcqLag(), "coptidice": COptiDice}


def make_learner(name, dtype_name):
    dtype = DTYPES[dtype_name]
    learner = LEARNERS[name](dtype)
    for module in learner.modules():
        module.to(dtype)
    if isinstance(learner, Cpq):
        learner.log_alpha = learner.log_alpha.to(dtype)

    def uniform(*shape):
        return torch.rand(*shape, dtype=dtype) * 2 - 1

    initial = (torch.arange(BATCH) % 200 == 0).to(dtype)
    batch = (uniform(BATCH, OBSERVATIONS), uniform(BATCH, OBSERVATIONS), uniform(BATCH, ACTIONS), uniform(BATCH),
             uniform(BATCH).abs(), torch.zeros(BATCH, dtype=dtype), initial)
    for _ in range(5):  # warm-up
        learner.update(batch)
    return learner, batch


def median(values):
    ordered = sorted(values)
    n = len(ordered)
    return ordered[n // 2] if n % 2 else 0.5 * (ordered[n // 2 - 1] + ordered[n // 2])


def time_steps(learner, batch, seconds):
    """(median wall us, median process CPU us, steps) over the steps of at least `seconds` (3 steps at least)."""
    walls, cpus = [], []
    start = time.perf_counter()
    while time.perf_counter() - start < seconds or len(walls) < 3:
        wall, cpu = time.perf_counter(), time.process_time()
        learner.update(batch)
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
    return 1e6 * median(walls), 1e6 * median(cpus), len(walls)


def serve():
    learners = {}
    for line in sys.stdin:
        fields = line.split()
        if not fields:
            continue
        try:
            seconds = float(fields[2]) if len(fields) == 3 else -1.0
        except ValueError:
            seconds = -1.0
        if len(fields) != 3 or fields[0] not in LEARNERS or fields[1] not in DTYPES or not seconds > 0:
            print(f"error: bad request {line.strip()!r}, expected LEARNER DTYPE SECONDS", flush=True)
            continue
        key = (fields[0], fields[1])
        if key not in learners:
            learners[key] = make_learner(*key)
        wall, cpu, steps = time_steps(*learners[key], seconds)
        print(f"{wall:.3f} {cpu:.3f} {steps}", flush=True)


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
    for name in LEARNERS:
        for dtype_name in DTYPES:
            wall, cpu, steps = time_steps(*make_learner(name, dtype_name), 3.0)
            print(f"  torch {name:<9} {dtype_name}  {wall:9.0f} us wall  {cpu:9.0f} us cpu  (median of {steps} steps)",
                  flush=True)


if __name__ == "__main__":
    main()
