#!/usr/bin/python3
"""Learning curves of a run or of a sweep, in the style of the report's Figure 2.

    scripts/plot_curves.py RUN_DIR [--out DIR] [--smooth N]
    scripts/plot_curves.py RUN_DIR RUN_DIR... --out DIR [--smooth N]
    scripts/plot_curves.py SWEEP_DIR [--out DIR] [--smooth N] [--all-configs]
    scripts/plot_curves.py SWEEP_DIR --ci [--out DIR]

A run directory (it holds progress.csv, as `bsg train` leaves it): one PNG,
RUN_DIR/learning_curve.png, with the run's mean episode return and mean
episode cost per epoch (training episodes), the raw values faint and a Hann
window of --smooth epochs (default 9) drawn over them, and the cost limit d;
then one summary line: return and cost at the start and at the end of training
(means over the first and last tenth of the epochs), and the final
deterministic policy's J and H from evaluation.json.

Several run directories (seeds of one run file, say): one PNG,
OUT/learning_curves.png, with each run's curves in its own colour, labelled
by its directory's name, and one summary line per run.

A sweep directory: for each environment, one PNG with two panels, the mean
episode return and the mean episode cost per epoch (training episodes, as
logged in progress.csv), one line per algorithm: the configuration `bsg table`
selected (read from SWEEP_DIR/table1.csv, so run `bsg table SWEEP_DIR` first),
the mean over its seeds with a band of +-1 standard deviation. The cost limit d
is a black dashed line. An algorithm whose final deterministic policy violates
the limit (mean evaluation cost H > d) is drawn dotted, as in Figure 2.
--smooth N applies a Hann window of N epochs to each seed's curve before
averaging (the original plot.py always used 13); the sweep default 1 draws the
raw values. --all-configs draws every configuration instead of the selected
ones (one PNG per environment and algorithm), as the report's Appendix figures
do. Writes SWEEP_DIR/plots/<env_id>.png by default.

--ci draws the interval estimates `bsg table SWEEP_DIR --ci` computed (it
writes curves.csv, profiles.csv, aggregates.csv and frontier.csv beside
table1.csv; this script computes no statistic of its own), each PNG with the
rows it drew as a CSV file of the same name beside it: per environment,
<env_id>_ci.png, the selected configurations' mean episode return, episode
cost, cost rate and cumulative cost per epoch with the bootstrap band of the
mean across seeds; profiles.png, the performance profiles of J / J_TRPO and
of the feasibility margin (d - H) / d with their bands; aggregates.png, the
IQM across environments of J / J_TRPO and of H / d and P(H <= d) per column
with intervals; and, for a sweep over cost limits, frontier_<env_id>.png: per
constraint, the final return J against the final cost H (one point per limit,
interval bars both ways) and H against d with the diagonal H = d.

Runs with Debian's Python 3 and Matplotlib (/usr/bin/python3 with
python3-matplotlib; see scripts/install_deps.sh).
"""

import argparse
import csv
import glob
import json
import math
import os
import re
import sys
import warnings

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# progress.csv column names of bsg (algos/training/epoch_log.cpp), then the original's.
EPOCH_COLUMNS = ("epoch", "Epoch")
RETURN_COLUMNS = ("episode_return_mean", "EpRet/Mean")
COST_COLUMNS = ("episode_cost_mean", "EpCosts/Mean")

# The table of algorithms is common/algorithms.h's kAlgorithms, the one source of the program's
# labels too: each row {Algorithm::x, "name", "label", "pid_label", family, flags..., "colour"},
# read here by its four string literals in order.
ALGORITHM_TABLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common", "algorithms.h")
ALGORITHM_ROW = re.compile(r'\{Algorithm::\w+,\s*"([^"]*)",\s*"([^"]*)",\s*"([^"]*)",[^"{}]*"([^"]*)"\}')


def read_algorithm_table(path=ALGORITHM_TABLE):
    """(labels, order, colours) of the algorithms, from the rows of kAlgorithms in `path`."""
    with open(path) as file:
        rows = ALGORITHM_ROW.findall(file.read())
    if not rows:
        raise SystemExit(f"plot_curves: no rows of kAlgorithms found in {path}")
    labels = {name: label for name, label, _pid_label, _colour in rows}
    colours = {name: colour for name, _label, _pid_label, colour in rows}
    return labels, [name for name, *_ in rows], colours


ALGORITHM_LABELS, ALGORITHM_ORDER, ALGORITHM_COLORS = read_algorithm_table()


class PlotError(Exception):
    """An input problem; the message names the file at fault."""


def pick_column(header, candidates, path):
    for name in candidates:
        if name in header:
            return header.index(name)
    raise PlotError(f"{path}: none of the columns {', '.join(candidates)} in its header")


def to_number(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


def read_progress(path):
    """(epochs, returns, costs) as arrays, one entry per logged epoch."""
    with open(path, newline="") as file:
        rows = list(csv.reader(file))
    if not rows:
        raise PlotError(f"{path}: empty file")
    header = rows[0]
    columns = [pick_column(header, names, path) for names in (EPOCH_COLUMNS, RETURN_COLUMNS, COST_COLUMNS)]
    data = [[to_number(row[c]) if c < len(row) else math.nan for c in columns] for row in rows[1:] if row]
    if not data:
        return np.zeros(0), np.zeros(0), np.zeros(0)
    epochs, returns, costs = (np.array(column) for column in zip(*data))
    return epochs, returns, costs


def smooth(values, window):
    """Hann-window moving average that keeps the length and the ends unbiased."""
    if window <= 1 or len(values) < 3:
        return values
    window = min(window, len(values) if len(values) % 2 else len(values) - 1)
    weights = np.hanning(window + 2)[1:-1]  # no zero weights at the ends
    filled = np.where(np.isnan(values), 0.0, values)
    present = (~np.isnan(values)).astype(float)
    numerator = np.convolve(filled, weights, mode="same")
    denominator = np.convolve(present, weights, mode="same")
    with np.errstate(invalid="ignore", divide="ignore"):
        return numerator / denominator


def seed_curves(config_dir, window):
    """Curves of the seeds below config_dir, cut to the epochs all of them logged."""
    curves = []
    for progress in sorted(glob.glob(os.path.join(config_dir, "*", "progress.csv"))):
        epochs, returns, costs = read_progress(progress)
        if len(epochs):
            curves.append((epochs, smooth(returns, window), smooth(costs, window)))
    if not curves:
        return None
    length = min(len(c[0]) for c in curves)
    epochs = curves[0][0][:length]
    returns = np.array([c[1][:length] for c in curves])
    costs = np.array([c[2][:length] for c in curves])
    return epochs, returns, costs, len(curves)


def read_table(sweep_dir):
    path = os.path.join(sweep_dir, "table1.csv")
    if not os.path.exists(path):
        raise PlotError(f"{path} not found: run 'bsg table {sweep_dir}' first (it selects the configurations)")
    with open(path, newline="") as file:
        return list(csv.DictReader(file))


def read_configurations(sweep_dir):
    path = os.path.join(sweep_dir, "configurations.csv")
    if not os.path.exists(path):
        raise PlotError(f"{path} not found: run 'bsg table {sweep_dir}' first")
    with open(path, newline="") as file:
        return list(csv.DictReader(file))


def draw_line(axes_pair, epochs, returns, costs, label, color, dotted):
    style = ":" if dotted else "-"
    width = 1.5 if dotted else 2.0
    for axes, values in zip(axes_pair, (returns, costs)):
        with warnings.catch_warnings():  # "mean of empty slice" where every seed has NaN
            warnings.simplefilter("ignore", category=RuntimeWarning)
            mean = np.nanmean(values, axis=0)
            std = np.nanstd(values, axis=0)
        axes.plot(epochs, mean, linestyle=style, linewidth=width, color=color, label=label)
        axes.fill_between(epochs, mean - std, mean + std, color=color, alpha=0.2, linewidth=0)


def new_figure(title, cost_limit):
    figure, (ax_return, ax_cost) = plt.subplots(1, 2, figsize=(10, 3.8))
    figure.suptitle(title)
    ax_return.set_title("Return")
    ax_cost.set_title("Cost")
    for axes in (ax_return, ax_cost):
        axes.set_xlabel("Epoch")
        axes.grid(alpha=0.3)
    if cost_limit is not None and math.isfinite(cost_limit):
        ax_cost.axhline(cost_limit, color="black", linestyle="--", linewidth=1.2, label=f"d = {cost_limit:g}")
    return figure, (ax_return, ax_cost)


def finish_figure(figure, axes_pair, path):
    handles, labels = axes_pair[0].get_legend_handles_labels()
    cost_handles, cost_labels = axes_pair[1].get_legend_handles_labels()
    for handle, label in zip(cost_handles, cost_labels):
        if label.startswith("d = "):
            handles.append(handle)
            labels.append(label)
    if handles:
        figure.legend(handles, labels, loc="lower center", ncol=min(len(labels), 6), frameon=False)
    figure.tight_layout(rect=(0, 0.1, 1, 0.95))
    figure.savefig(path, dpi=100)
    plt.close(figure)


def env_label(env_id):
    label = env_id[len("Safety"):] if env_id.startswith("Safety") else env_id
    return label.split("-v")[0]


def float_or_none(text):
    return float(text) if text not in ("", None) else None


def plot_selected(sweep_dir, out_dir, window):
    rows = read_table(sweep_dir)
    envs = []
    for row in rows:
        if row["env_id"] not in envs:
            envs.append(row["env_id"])
    written = []
    for env_id in envs:
        env_rows = sorted((r for r in rows if r["env_id"] == env_id),
                          key=lambda r: ALGORITHM_ORDER.index(r["alg"]) if r["alg"] in ALGORITHM_ORDER else 99)
        cost_limit = next((float_or_none(r["cost_limit"]) for r in env_rows if r["cost_limit"]), None)
        figure, axes_pair = new_figure(f"{env_label(env_id)} (best configuration per algorithm)", cost_limit)
        drawn = 0
        for row in env_rows:
            label = ALGORITHM_LABELS.get(row["alg"], row["alg"])
            if row["status"] == "missing":
                print(f"plot_curves: {env_id} {label}: missing (no finished run)", file=sys.stderr)
                continue
            curves = seed_curves(os.path.join(sweep_dir, row["config_dir"]), window)
            if curves is None:
                print(f"plot_curves: {env_id} {label}: no progress.csv below {row['config_dir']}", file=sys.stderr)
                continue
            epochs, returns, costs, seeds = curves
            dotted = row["feasible"] != "true"  # the final policy violates the limit
            draw_line(axes_pair, epochs, returns, costs, f"{label} ({seeds} seeds)",
                      ALGORITHM_COLORS.get(row["alg"]), dotted)
            drawn += 1
        path = os.path.join(out_dir, f"{env_id}.png")
        finish_figure(figure, axes_pair, path)
        written.append((path, drawn))
    return written


def plot_all_configurations(sweep_dir, out_dir, window):
    configurations = read_configurations(sweep_dir)
    groups = {}
    for row in configurations:
        groups.setdefault((row["env_id"], row["alg"]), []).append(row)
    written = []
    colors = plt.get_cmap("tab10")
    for (env_id, alg), rows in groups.items():
        cost_limit = next((float_or_none(r["cost_limit"]) for r in rows if r["cost_limit"]), None)
        label = ALGORITHM_LABELS.get(alg, alg)
        figure, axes_pair = new_figure(f"{env_label(env_id)}, {label}: all configurations", cost_limit)
        drawn = 0
        for index, row in enumerate(rows):
            curves = seed_curves(os.path.join(sweep_dir, env_id, alg, row["config"]), window)
            if curves is None:
                continue
            epochs, returns, costs, seeds = curves
            dotted = row["feasible"] != "true"
            name = row["config"] + (" (selected)" if row["selected"] == "true" else "")
            draw_line(axes_pair, epochs, returns, costs, name, colors(index % 10), dotted)
            drawn += 1
        path = os.path.join(out_dir, f"{env_id}_{alg}.png")
        finish_figure(figure, axes_pair, path)
        written.append((path, drawn))
    return written


def read_rows(path, what):
    """The rows of a CSV file `bsg table --ci` wrote, as dicts."""
    if not os.path.exists(path):
        raise PlotError(f"{path} not found: run 'bsg table {os.path.dirname(path) or '.'} --ci' first ({what})")
    with open(path, newline="") as file:
        return list(csv.DictReader(file))


def write_rows(path, rows, fieldnames):
    """The data of a figure, beside its PNG."""
    with open(path, "w", newline="") as file:
        writer = csv.DictWriter(file, fieldnames=fieldnames, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)


def column_color(column, columns):
    """A colour per Table 1 column: the algorithm's own where the column is the algorithm's."""
    for alg, label in ALGORITHM_LABELS.items():
        if label == column:
            return ALGORITHM_COLORS[alg]
    # Columns of their own (CPPO-PID, TRPO-PID, "... corrected"): colours no algorithm uses.
    others = [c for c in columns if c not in ALGORITHM_LABELS.values()]
    extra = [c for c in ("black", "gold", "lime", "maroon", "sienna", "deeppink", "slategray", "olivedrab")
             if c not in ALGORITHM_COLORS.values()]
    return extra[others.index(column) % len(extra)]


def ordered_columns(rows):
    columns = []
    for row in rows:
        if row["column"] not in columns:
            columns.append(row["column"])
    return columns


def confidence_of(rows):
    return f"{100 * float(rows[0]['confidence']):g} %" if rows else ""


CURVE_PANELS = (("return", "Episode return"), ("cost", "Episode cost"), ("cost_rate", "Cost rate (training)"),
                ("cumulative_cost", "Cumulative cost (training)"))


def plot_ci_curves(sweep_dir, out_dir):
    rows = read_rows(os.path.join(sweep_dir, "curves.csv"), "learning curves with bands")
    limits = {}
    table_path = os.path.join(sweep_dir, "table1.csv")
    if os.path.exists(table_path):
        for row in read_table(sweep_dir):
            if row["cost_limit"] and row["env_id"] not in limits:
                limits[row["env_id"]] = float(row["cost_limit"])
    written = []
    envs = []
    for row in rows:
        if row["env_id"] not in envs:
            envs.append(row["env_id"])
    for env_id in envs:
        env_rows = [r for r in rows if r["env_id"] == env_id]
        columns = ordered_columns(env_rows)
        figure, axes = plt.subplots(1, 4, figsize=(17, 3.9))
        figure.suptitle(f"{env_label(env_id)}: mean over seeds with its {confidence_of(env_rows)} bootstrap band "
                        "(selected configuration per algorithm)")
        for panel, (metric, title) in zip(axes, CURVE_PANELS):
            panel.set_title(title)
            panel.set_xlabel("Epoch")
            panel.grid(alpha=0.3)
            for column in columns:
                data = [r for r in env_rows if r["column"] == column and r["metric"] == metric]
                if not data:
                    continue
                epochs = np.array([int(r["epoch"]) for r in data])
                mean, low, high = (np.array([float(r[k]) for r in data]) for k in ("mean", "low", "high"))
                color = column_color(column, columns)
                panel.plot(epochs, mean, color=color, linewidth=1.8, label=f"{column} ({data[0]['seeds']} seeds)")
                panel.fill_between(epochs, low, high, color=color, alpha=0.25, linewidth=0)
        if env_id in limits and math.isfinite(limits[env_id]):
            axes[1].axhline(limits[env_id], color="black", linestyle="--", linewidth=1.2, label=f"d = {limits[env_id]:g}")
        handles, labels = axes[0].get_legend_handles_labels()
        for handle, label in zip(*axes[1].get_legend_handles_labels()):
            if label.startswith("d = "):
                handles.append(handle)
                labels.append(label)
        figure.legend(handles, labels, loc="lower center", ncol=min(len(labels), 7), frameon=False)
        figure.tight_layout(rect=(0, 0.1, 1, 0.94))
        path = os.path.join(out_dir, f"{env_id}_ci.png")
        figure.savefig(path, dpi=100)
        plt.close(figure)
        write_rows(path[:-4] + ".csv", env_rows, list(env_rows[0].keys()))
        written.append((path, len(columns)))
    return written


PROFILE_TITLES = {"J_over_trpo": ("Normalised return J / J_TRPO", "tau"),
                  "feasibility_margin": ("Feasibility margin (d - H) / d", "tau")}


def plot_ci_profiles(sweep_dir, out_dir):
    rows = read_rows(os.path.join(sweep_dir, "profiles.csv"), "performance profiles")
    if not rows:
        return []
    metrics = [m for m in PROFILE_TITLES if any(r["metric"] == m for r in rows)]
    columns = ordered_columns(rows)
    figure, axes = plt.subplots(1, len(metrics), figsize=(max(8.0, 6.5 * len(metrics)), 4.4), squeeze=False)
    figure.suptitle(f"Performance profiles ({confidence_of(rows)} stratified bootstrap bands)")
    for panel, metric in zip(axes[0], metrics):
        title, xlabel = PROFILE_TITLES[metric]
        panel.set_title(title)
        panel.set_xlabel(xlabel)
        panel.set_ylabel("Fraction of runs with score > tau")
        panel.set_ylim(-0.02, 1.02)
        panel.grid(alpha=0.3)
        if metric == "feasibility_margin":
            panel.axvline(0.0, color="black", linestyle="--", linewidth=1.0, label="H = d")
        for column in columns:
            data = [r for r in rows if r["column"] == column and r["metric"] == metric]
            if not data:
                continue
            tau, value, low, high = (np.array([float(r[k]) for r in data])
                                     for k in ("tau", "fraction_above", "low", "high"))
            color = column_color(column, columns)
            panel.plot(tau, value, color=color, linewidth=1.8, drawstyle="steps-post",
                       label=f"{column} ({data[0]['seeds']} runs, {data[0]['environments']} env)")
            panel.fill_between(tau, low, high, color=color, alpha=0.2, step="post", linewidth=0)
        panel.legend(fontsize=8, frameon=False)
    figure.tight_layout(rect=(0, 0, 1, 0.93))
    path = os.path.join(out_dir, "profiles.png")
    figure.savefig(path, dpi=100)
    plt.close(figure)
    write_rows(path[:-4] + ".csv", rows, list(rows[0].keys()))
    return [(path, len(columns))]


AGGREGATE_PANELS = (("J_over_trpo", "iqm", "IQM of J / J_TRPO"), ("H_over_d", "iqm", "IQM of H / d"),
                    ("feasible", "proportion", "P(H <= d)"))


def plot_ci_aggregates(sweep_dir, out_dir):
    rows = read_rows(os.path.join(sweep_dir, "aggregates.csv"), "aggregates across environments")
    panels = [p for p in AGGREGATE_PANELS if any(r["metric"] == p[0] and r["statistic"] == p[1] for r in rows)]
    if not panels:
        return []
    columns = ordered_columns(rows)
    figure, axes = plt.subplots(1, len(panels), figsize=(4.6 * len(panels), 0.5 * len(columns) + 1.8),
                                squeeze=False)
    figure.suptitle(f"Across environments, selected configurations ({confidence_of(rows)} intervals)")
    drawn = []
    for panel, (metric, statistic, title) in zip(axes[0], panels):
        panel.set_title(title)
        panel.grid(alpha=0.3, axis="x")
        ends = []
        for index, column in enumerate(columns):
            data = [r for r in rows if r["column"] == column and r["metric"] == metric and r["statistic"] == statistic]
            if not data:
                continue
            row = data[0]
            drawn.append(row)
            point, low, high = float(row["point"]), float(row["low"]), float(row["high"])
            ends += [low, high]
            color = column_color(column, columns)
            panel.barh(index, high - low, left=low, height=0.6, color=color, alpha=0.5)
            panel.plot([point, point], [index - 0.3, index + 0.3], color="black", linewidth=1.5)
        panel.set_yticks(range(len(columns)))
        panel.set_yticklabels(columns if panel is axes[0][0] else [""] * len(columns))
        panel.invert_yaxis()
        if metric == "H_over_d":
            panel.axvline(1.0, color="black", linestyle="--", linewidth=1.0)
        if metric == "feasible":
            panel.set_xlim(-0.02, 1.02)
        elif ends:  # bars hold the axis at their ends: pad it so that an interval of width zero stays in view
            pad = 0.05 * (max(ends) - min(ends)) or 0.5
            panel.set_xlim(min(ends) - pad, max(ends) + pad)
    figure.tight_layout(rect=(0, 0, 1, 0.9))
    path = os.path.join(out_dir, "aggregates.png")
    figure.savefig(path, dpi=100)
    plt.close(figure)
    write_rows(path[:-4] + ".csv", drawn, list(rows[0].keys()))
    return [(path, len(columns))]


def plot_ci_frontier(sweep_dir, out_dir):
    path = os.path.join(sweep_dir, "frontier.csv")
    if not os.path.exists(path):
        return []  # not a sweep over cost limits
    rows = read_rows(path, "cost-limit frontier")
    written = []
    envs = []
    for row in rows:
        if row["env_id"] not in envs:
            envs.append(row["env_id"])
    for env_id in envs:
        env_rows = [r for r in rows if r["env_id"] == env_id]
        constraints = sorted({int(r["constraint"]) for r in env_rows})
        lines = []
        for row in env_rows:
            key = (row["column"], row["family"])
            if key not in lines:
                lines.append(key)
        columns = ordered_columns(env_rows)
        figure, axes = plt.subplots(len(constraints), 2, figsize=(12, 4.6 * len(constraints)), squeeze=False)
        figure.suptitle(f"{env_label(env_id)}: cost-limit frontier, mean over seeds with "
                        f"{confidence_of(env_rows)} bootstrap intervals")
        for row_axes, constraint in zip(axes, constraints):
            ax_return, ax_cost = row_axes
            suffix = f" {constraint}" if len(constraints) > 1 else ""
            ax_return.set_title(f"Final return against final cost{suffix}")
            ax_return.set_xlabel(f"H{suffix} (final policy)")
            ax_return.set_ylabel("J (final policy)")
            ax_cost.set_title(f"Final cost against the limit{suffix}")
            ax_cost.set_xlabel(f"d{suffix}")
            ax_cost.set_ylabel(f"H{suffix}")
            limits = sorted({float(r["cost_limit"]) for r in env_rows if int(r["constraint"]) == constraint})
            top = max([float(r["cost_high"]) for r in env_rows if int(r["constraint"]) == constraint] + limits)
            ax_cost.plot([0, max(limits) * 1.05], [0, max(limits) * 1.05], color="black", linestyle="--",
                         linewidth=1.0, label="H = d")
            for limit in limits:
                ax_return.axvline(limit, color="gray", linestyle=":", linewidth=0.8)
            for column, family in lines:
                data = [r for r in env_rows if r["column"] == column and r["family"] == family and
                        int(r["constraint"]) == constraint]
                if not data:
                    continue
                d, j, j_low, j_high, h, h_low, h_high = (
                    np.array([float(r[k]) for r in data])
                    for k in ("cost_limit", "mean_return", "return_low", "return_high", "mean_cost", "cost_low",
                              "cost_high"))
                color = column_color(column, columns)
                single_family = sum(1 for c, _ in lines if c == column) == 1
                label = column if single_family else f"{column} {family}"
                label += f" ({data[0]['seeds']} seeds)"
                ax_return.errorbar(h, j, xerr=[h - h_low, h_high - h], yerr=[j - j_low, j_high - j], color=color,
                                   marker="o", capsize=3, linewidth=1.5, label=label)
                for x, y, limit in zip(h, j, d):
                    ax_return.annotate(f"d={limit:g}", (x, y), textcoords="offset points", xytext=(4, 4),
                                       fontsize=7, color=color)
                ax_cost.errorbar(d, h, yerr=[h - h_low, h_high - h], color=color, marker="o", capsize=3,
                                 linewidth=1.5, label=label)
            ax_cost.set_xlim(0, max(limits) * 1.05)
            ax_cost.set_ylim(0, top * 1.05)
            for axes_ in row_axes:
                axes_.grid(alpha=0.3)
            ax_cost.legend(fontsize=8, frameon=False)
        figure.tight_layout(rect=(0, 0, 1, 0.95))
        path = os.path.join(out_dir, f"frontier_{env_id}.png")
        figure.savefig(path, dpi=100)
        plt.close(figure)
        write_rows(path[:-4] + ".csv", env_rows, list(env_rows[0].keys()))
        written.append((path, len(lines)))
    return written


def plot_intervals(sweep_dir, out_dir, _window=None):
    written = plot_ci_curves(sweep_dir, out_dir)
    written += plot_ci_profiles(sweep_dir, out_dir)
    written += plot_ci_aggregates(sweep_dir, out_dir)
    written += plot_ci_frontier(sweep_dir, out_dir)
    return written


def read_run_config_value(run_dir, key):
    """A scalar `key: value` of RUN_DIR/config.yaml (as bsg writes it), or None."""
    path = os.path.join(run_dir, "config.yaml")
    if not os.path.exists(path):
        return None
    with open(path) as file:
        for line in file:
            name, _, rest = line.partition(":")
            if name.strip() == key and not line.startswith((" ", "#")):
                return rest.split("#", 1)[0].strip().strip("'\"")
    return None


def last_logged_value(path, column):
    """The last row's value of `column` in a CSV file, or None."""
    with open(path, newline="") as file:
        rows = list(csv.DictReader(file))
    value = rows[-1].get(column) if rows else None
    return to_number(value) if value not in (None, "") else None


def start_and_end_means(values):
    """Means of the first and the last tenth of `values` (at least one value each)."""
    count = max(1, len(values) // 10)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", category=RuntimeWarning)
        return float(np.nanmean(values[:count])), float(np.nanmean(values[-count:])), count


def run_name(run_dir):
    return os.path.basename(os.path.normpath(run_dir))


def plot_runs(run_dirs, out_dir, window):
    """The learning curves of RUN_DIRs as one PNG; returns (path, summary lines)."""
    runs = []
    for run_dir in run_dirs:
        progress = os.path.join(run_dir, "progress.csv")
        epochs, returns, costs = read_progress(progress)
        if not len(epochs):
            raise PlotError(f"{progress}: no epoch logged yet")
        runs.append((run_dir, epochs, returns, costs))
    env_ids = {read_run_config_value(run_dir, "env_id") or "run" for run_dir in run_dirs}
    algs = {read_run_config_value(run_dir, "alg") or "" for run_dir in run_dirs}
    limits = {read_run_config_value(run_dir, "cost_limit") for run_dir in run_dirs}
    cost_limit = float(next(iter(limits))) if len(limits) == 1 and next(iter(limits)) else None
    what = ", ".join(sorted(env_label(env_id) for env_id in env_ids))
    label = ", ".join(sorted(ALGORITHM_LABELS.get(alg, alg) for alg in algs))
    single = len(runs) == 1
    title = f"{what}, {label}: {run_name(run_dirs[0])}" if single else f"{what}, {label}: {len(runs)} runs"
    figure, axes_pair = new_figure(title, cost_limit)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    smoothing = f" (Hann window of {window} epochs)" if window > 1 else ""
    for index, (run_dir, epochs, returns, costs) in enumerate(runs):
        alg = read_run_config_value(run_dir, "alg") or ""
        color = ALGORITHM_COLORS.get(alg, "tab:blue") if single else colors[index % len(colors)]
        for axes, values in zip(axes_pair, (returns, costs)):
            axes.plot(epochs, values, color=color, alpha=0.3, linewidth=1.0)
        line_label = (label if single else run_name(run_dir)) + smoothing
        draw_line(axes_pair, epochs, np.array([smooth(returns, window)]), np.array([smooth(costs, window)]),
                  line_label, color, False)
    path = os.path.join(out_dir, "learning_curve.png" if single else "learning_curves.png")
    finish_figure(figure, axes_pair, path)
    return path, [run_summary(run_dir, epochs, returns, costs) for run_dir, epochs, returns, costs in runs]


def run_summary(run_dir, epochs, returns, costs):
    """One line: the run's return and cost at the start and at the end, its time and evaluation."""
    progress = os.path.join(run_dir, "progress.csv")
    env_id = read_run_config_value(run_dir, "env_id") or "run"
    alg = read_run_config_value(run_dir, "alg") or ""
    label = ALGORITHM_LABELS.get(alg, alg)
    cost_limit_text = read_run_config_value(run_dir, "cost_limit")
    cost_limit = float(cost_limit_text) if cost_limit_text else None
    return_start, return_end, count = start_and_end_means(returns)
    cost_start, cost_end, _ = start_and_end_means(costs)
    limit = f" (limit {cost_limit:g})" if cost_limit is not None else ""
    seconds = last_logged_value(progress, "time_s")
    took = f" in {seconds:.0f} s" if seconds is not None and math.isfinite(seconds) else ""
    summary = (f"{env_id} {label}, {len(epochs)} epochs{took}: return {return_start:.1f} -> {return_end:.1f}, "
               f"cost {cost_start:.1f} -> {cost_end:.1f}{limit} (means of the first and last {count} epochs)")
    evaluation_path = os.path.join(run_dir, "evaluation.json")
    if os.path.exists(evaluation_path):
        with open(evaluation_path) as file:
            evaluation = json.load(file)
        summary += (f"; final policy J {evaluation['mean_return']:.1f}, H {evaluation['mean_cost']:.1f} "
                    f"over {evaluation['episodes']} episodes")
    return summary


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directories", nargs="+", metavar="directory",
                        help="a run directory (bsg train), several run directories, or a sweep directory "
                             "(bsg sweep, then bsg table)")
    parser.add_argument("--out", help="directory for the PNG files (default: RUN_DIR, or SWEEP_DIR/plots)")
    parser.add_argument("--smooth", type=int, help="Hann window in epochs (default: 9 for a run, 1 for a sweep)")
    parser.add_argument("--all-configs", action="store_true",
                        help="sweep: one PNG per environment and algorithm with every configuration")
    parser.add_argument("--ci", action="store_true",
                        help="sweep: the interval estimates of 'bsg table SWEEP_DIR --ci' (curves with bootstrap "
                             "bands, performance profiles, aggregates, the cost-limit frontier), a CSV beside "
                             "each PNG")
    args = parser.parse_args(argv)
    if args.smooth is not None and args.smooth < 1:
        parser.error("--smooth must be at least 1")
    if len(args.directories) > 1:
        for directory in args.directories:
            if not os.path.exists(os.path.join(directory, "progress.csv")):
                parser.error(f"{directory} is not a run directory (no progress.csv): several directories must "
                             "all be runs")
        if not args.out:
            parser.error("several run directories need --out DIR for their one PNG")
        if args.all_configs or args.ci:
            parser.error("--all-configs and --ci apply to a sweep directory, not to run directories")
    args.directory = args.directories[0]
    is_run = os.path.exists(os.path.join(args.directory, "progress.csv"))
    if is_run and args.all_configs:
        parser.error("--all-configs applies to a sweep directory, not to a run directory")
    if is_run and args.ci:
        parser.error("--ci applies to a sweep directory, not to a run directory")
    if args.ci and (args.all_configs or args.smooth is not None):
        parser.error("--ci draws the bands bsg table computed: no --all-configs or --smooth with it")
    window = args.smooth if args.smooth is not None else (9 if is_run else 1)
    out_dir = args.out or (args.directory if is_run else os.path.join(args.directory, "plots"))
    try:
        if not os.path.isdir(args.directory):
            raise PlotError(f"directory {args.directory} does not exist")
        os.makedirs(out_dir, exist_ok=True)
        if is_run:
            path, summaries = plot_runs(args.directories, out_dir, window)
            for summary in summaries:
                print(f"summary: {summary}; curves: {path}")
            return 0
        plot = plot_intervals if args.ci else plot_all_configurations if args.all_configs else plot_selected
        written = plot(args.directory, out_dir, window)
    except (PlotError, OSError, KeyError, ValueError) as error:
        print(f"plot_curves: error: {error}", file=sys.stderr)
        return 1
    for path, drawn in written:
        print(f"{path} ({drawn} curves)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
