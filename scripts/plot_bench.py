#!/usr/bin/env python3
"""Plot the result of `cocopp bench`: error against the reference versus wall time.

Reads <output_directory>/bench.json (written by cocopp bench, docs/bench.md) and draws a
log-log scatter of the relative displacement error against the wall time of every run, each
point labelled with its variant. An error of exactly 0 (a run identical to the reference)
cannot be shown on a log axis: such runs are drawn on the bottom edge with the label
"(= reference)". Runs without an error (diverged before the first step, other delta_t) are
listed under the plot instead.

    /usr/bin/python3 scripts/plot_bench.py bench_results/bench.json -o bench_results/bench.png
"""
import argparse
import json
import math
import sys


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("bench_json", help="bench.json written by cocopp bench")
    parser.add_argument("-o", "--output", default="bench.png", help="PNG to write (default: %(default)s)")
    parser.add_argument("--error", choices=["displacement", "pressure"], default="displacement",
                        help="which error to plot (default: %(default)s)")
    parser.add_argument("--include-reference", action="store_true",
                        help="also draw the computed reference run")
    return parser.parse_args(argv)


def finite(value):
    return value is not None and math.isfinite(value)


def main(argv):
    args = parse_arguments(argv)
    import matplotlib

    matplotlib.use("Agg")  # no display needed
    import matplotlib.pyplot as plt

    with open(args.bench_json) as f:
        bench = json.load(f)
    key = args.error + "_error"
    runs = [r for r in bench["runs"] if args.include_reference or r["name"] != "reference"]
    shown = [r for r in runs if finite(r[key]) and finite(r["wall_time"]) and r["wall_time"] > 0]
    missing = [r for r in runs if r not in shown]
    positive = [r[key] for r in shown if r[key] > 0]
    floor = min(positive) / 10 if positive else 1e-16

    figure, axes = plt.subplots(figsize=(7, 5))
    for run in shown:
        error = run[key] if run[key] > 0 else floor
        marker = "o" if run["completed"] else "x"
        axes.scatter(run["wall_time"], error, marker=marker, s=40)
        label = run["name"] + ("" if run[key] > 0 else " (= reference)")
        if not run["completed"]:
            label += f" ({run['status']} after {run['steps_completed']} steps)"
        axes.annotate(label, (run["wall_time"], error), textcoords="offset points", xytext=(5, 4),
                      fontsize=8)
    axes.set_xscale("log")
    axes.margins(x=0.2, y=0.2)  # room for the labels
    axes.set_yscale("log")
    axes.set_xlabel("wall time [s]")
    axes.set_ylabel(f"relative {args.error} error (L2 over space and time)")
    axes.set_title(f"cocopp bench: {bench.get('bench_file', '')}", fontsize=9)
    axes.grid(True, which="both", alpha=0.3)
    if missing:
        text = "no error: " + ", ".join(f"{r['name']} ({r['status']})" for r in missing)
        figure.text(0.01, 0.01, text, fontsize=8)
    figure.tight_layout(rect=(0, 0.04 if missing else 0, 1, 1))
    figure.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
