"""cocopp bench's result: the error against the reference versus what a run cost, three ways:
wall time (start-up included), coupling iterations (what the algorithm saves, free of timing
noise) and the solvers' time (what the iterations cost in the solvers). The bench file is read
by cocopp.results.read_bench."""
import math
import os

import matplotlib.pyplot as plt
from matplotlib.ticker import FormatStrFormatter, NullFormatter

COSTS = [("wall_time", "wall time [s]"),
         ("iterations", "coupling iterations (all steps)"),
         ("solver_time", "time in the solvers [s]")]


def finite(value):
    return value is not None and math.isfinite(value)


def cost(run, key):
    if key == "iterations":
        return run["solver_calls"] / 2 if run.get("solver_calls") else None
    return run.get(key)


def plain_tick_labels(axis, limits):
    """Within a decade (runs of similar cost) matplotlib labels every minor tick of a log axis
    in scientific notation and the labels run into each other: plain numbers then, on the
    minor ticks too; over decades, the decades only."""
    low, high = limits
    if low > 0 and high / low < 10:
        axis.set_major_formatter(FormatStrFormatter("%g"))
        axis.set_minor_formatter(FormatStrFormatter("%g"))
    else:
        axis.set_minor_formatter(NullFormatter())


def plot_bench(bench, output, error="displacement", include_reference=False):
    """Writes the figure and returns it: one panel per cost, each run a point labelled with its variant. An
    error of exactly 0 (the reference's own settings) is drawn on the bottom edge as
    "(= reference)"; runs without an error are listed under the panels."""
    key = error + "_error"
    runs = [r for r in bench["runs"] if include_reference or r["name"] != "reference"]
    with_error = [r for r in runs if finite(r[key])]
    missing = [r for r in runs if r not in with_error]
    positive = [r[key] for r in with_error if r[key] > 0]
    floor = min(positive) / 10 if positive else 1e-16
    figure, axes = plt.subplots(1, len(COSTS), figsize=(6 * len(COSTS), 5), sharey=True)
    colors = {run["name"]: f"C{i % 10}" for i, run in enumerate(with_error)}  # same in each panel
    for ax, (cost_key, cost_label) in zip(axes, COSTS):
        for run in with_error:
            x = cost(run, cost_key)
            if not finite(x) or x <= 0:
                continue
            y = run[key] if run[key] > 0 else floor
            ax.scatter(x, y, marker="o" if run["completed"] else "x", s=40,
                       color=colors[run["name"]])
            text = run["name"] + ("" if run[key] > 0 else " (= reference)")
            if not run["completed"]:
                text += f" ({run['status']} after {run['steps_completed']} steps)"
            ax.annotate(text, (x, y), textcoords="offset points", xytext=(5, 4), fontsize=8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.margins(x=0.2, y=0.2)
        plain_tick_labels(ax.xaxis, ax.get_xlim())
        ax.set_xlabel(cost_label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel(f"relative {error} error (L2 over space and time)")
    figure.suptitle(f"cocopp bench: {os.path.basename(bench.get('bench_file', ''))}", fontsize=9)
    if missing:
        figure.text(0.01, 0.01, "no error: " + ", ".join(
            f"{r['name']} ({r['status']})" for r in missing), fontsize=8)
    figure.tight_layout(rect=(0, 0.04 if missing else 0, 1, 0.96))
    figure.savefig(output, dpi=120)
    return figure
