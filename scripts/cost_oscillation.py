#!/usr/bin/python3
"""How steady each configuration's epoch cost is, from the progress.csv files of
one or more sweeps (or run directories): per run, over the last part of training
(by default the second half of its logged epochs), the mean and the standard
deviation of the epoch cost (episode_cost_mean) and the mean return
(episode_return_mean); per configuration (the folder holding seed=* runs), their
means over runs, the mean cost against the cost limit d of config.yaml, and each
seed's standard deviation. This is the comparison docs/algorithms.md reports for
the PID Lagrangian against TRPO-L's SGD rule.

    scripts/cost_oscillation.py SWEEP_OR_RUN_DIR... [--from 0.5] [--csv OUT.csv]
"""

import argparse
import csv
import pathlib
import statistics
import sys


def fail(message):
    print(f"cost_oscillation.py: {message}", file=sys.stderr)
    sys.exit(1)


def cost_limit_of(run_dir):
    """d from the run's config.yaml (`cost_limit: 25.0  # comment`), or None."""
    config = run_dir / "config.yaml"
    if not config.is_file():
        return None
    for line in config.read_text().splitlines():
        if line.startswith("cost_limit:"):
            return float(line.split(":", 1)[1].split("#", 1)[0])
    return None


def run_statistics(progress, start_fraction):
    with progress.open(newline="") as handle:
        rows = list(csv.DictReader(handle))
    for column in ("episode_cost_mean", "episode_return_mean"):
        if rows and column not in rows[0]:
            fail(f"{progress}: no column {column}")
    if len(rows) < 2:
        fail(f"{progress}: {len(rows)} epoch(s) logged; at least 2 are needed")
    first = min(int(len(rows) * start_fraction), len(rows) - 2)
    window = rows[first:]
    try:
        costs = [float(row["episode_cost_mean"]) for row in window]
        returns = [float(row["episode_return_mean"]) for row in window]
    except ValueError as error:
        fail(f"{progress}: {error}")
    return {"epochs": len(rows), "first_epoch": first, "cost_mean": statistics.fmean(costs),
            "cost_std": statistics.pstdev(costs), "return_mean": statistics.fmean(returns)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dirs", nargs="+", type=pathlib.Path, help="sweep or run directories")
    parser.add_argument("--from", dest="start", type=float, default=0.5,
                        help="fraction of the logged epochs skipped before the window (default 0.5)")
    parser.add_argument("--csv", type=pathlib.Path, help="also write one row per run to this CSV file")
    args = parser.parse_args()
    if not 0 <= args.start < 1:
        fail(f"--from must be in [0, 1), got {args.start}")

    configurations = {}  # configuration folder -> [(seed folder name, statistics, d)]
    for directory in args.dirs:
        if not directory.is_dir():
            fail(f"{directory} is not a directory")
        progress_files = sorted(directory.rglob("progress.csv"))
        if not progress_files:
            fail(f"no progress.csv below {directory}")
        for progress in progress_files:
            run_dir = progress.parent
            stats = run_statistics(progress, args.start)
            configurations.setdefault(run_dir.parent, []).append((run_dir.name, stats, cost_limit_of(run_dir)))

    rows = []
    for configuration, runs in configurations.items():
        cost_mean = statistics.fmean(s["cost_mean"] for _, s, _ in runs)
        limits = {d for _, _, d in runs if d is not None}
        versus_d = ""
        if len(limits) == 1:
            d = limits.pop()
            if d > 0:
                versus_d = f" ({100 * (cost_mean - d) / d:+.1f} % of d = {d:g})"
        per_seed = ", ".join(f"{name} {s['cost_std']:.2f}" for name, s, _ in sorted(runs, key=lambda r: r[0]))
        epochs = sorted({s["epochs"] for _, s, _ in runs})
        print(f"{configuration}: {len(runs)} run(s), epochs {'/'.join(map(str, epochs))}, window from epoch "
              f"{min(s['first_epoch'] for _, s, _ in runs)}")
        print(f"  cost std {statistics.fmean(s['cost_std'] for _, s, _ in runs):.2f}  cost mean {cost_mean:.2f}"
              f"{versus_d}  return {statistics.fmean(s['return_mean'] for _, s, _ in runs):.2f}")
        print(f"  cost std per run: {per_seed}")
        for name, s, d in runs:
            rows.append({"configuration": str(configuration), "run": name, "epochs": s["epochs"],
                         "first_epoch": s["first_epoch"], "cost_mean": s["cost_mean"], "cost_std": s["cost_std"],
                         "return_mean": s["return_mean"], "cost_limit": "" if d is None else d})
    if args.csv:
        with args.csv.open("w", newline="") as handle:
            writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
