#!/usr/bin/env python3
"""Gauss-Seidel-unstable wall modes of the flexible tube next to the results of a stability sweep.

Linearised about rest, a Dirichlet-Neumann (Gauss-Seidel) iteration on the tube with inertia
multiplies the error in wall mode j, sin(j pi z / l), by

    lambda_j = -[2 rho_f / (rho_s h r0 k_j^2)] / (1 + omega_r^2 dt^2),
    k_j = j pi / l,  omega_r^2 = E / (rho_s r0^2)

(docs/coupling.md, "Why Gauss-Seidel diverges on the tube"). A mode with |lambda_j| > 1 grows:
Gauss-Seidel must diverge when at least one of the modes j = 1..cells is unstable.

Reads <results>/bench.json of `cocopp bench` (docs/bench.md), takes every run's parameters from
its own copied input files (case.yaml for delta_t, the tube_structure and tube_flow input files
of the case's solvers, after solver_inputs were merged), and prints a Markdown table: one row per
case with rho_s/rho_f, E, dt, l, |lambda_1|, the number of unstable modes, and for every variant
its average coupling iterations per step or how it ended. With -o it draws the average iterations
per step against the number of unstable modes, one line per variant.

    /usr/bin/python3 scripts/tube_modes.py examples/tube/stability/results/stability -o stability.png
"""
import argparse
import math
import os
import sys

from cocopp.case import read as load_yaml
from cocopp.results import bench_run_directory, read_bench


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", help="output directory of cocopp bench (holds bench.json)")
    parser.add_argument("-o", "--output", help="PNG to draw (iterations against unstable modes)")
    return parser.parse_args(argv)


def gauss_seidel_factors(rho_f, rho_s, e, h, diameter, length, cells, delta_t):
    """|lambda_j| for the wall modes j = 1..cells (the grid resolves no more)."""
    r0 = diameter / 2
    omega_r2 = e / (rho_s * r0 * r0)
    factors = []
    for j in range(1, cells + 1):
        k = j * math.pi / length
        factors.append(2 * rho_f / (rho_s * h * r0 * k * k) / (1 + omega_r2 * delta_t**2))
    return factors


def solver_input(run_directory, case, solver_type, default_file):
    for wrapper in case["solver_wrappers"]:
        if wrapper.get("type") == solver_type:
            return load_yaml(os.path.join(run_directory, wrapper["working_directory"],
                                          wrapper.get("input_file", default_file)))
    raise ValueError(f"{run_directory}: the case has no {solver_type} solver")


def tube_parameters(run_directory):
    """The physics of one run, from the files that run read."""
    case = load_yaml(os.path.join(run_directory, "case.yaml"))
    structure = solver_input(run_directory, case, "tube_structure", "tube_structure.yaml")
    flow = solver_input(run_directory, case, "tube_flow", "tube_flow.yaml")
    return {
        "rho_f": float(flow["rho_f"]),
        "rho_s": float(structure["rho_s"]),
        "e": float(structure["e"]),
        "h": float(structure["h"]),
        "diameter": float(structure["diameter"]),
        "length": float(structure["length"]),
        "cells": int(structure["cells"]),
        "delta_t": float(case["settings"]["delta_t"]),
    }


def cell(run):
    """Average iterations per step, or how the run ended."""
    average = run["average_iterations"]
    if run["outcome"] == "converged":
        return f"{average:.2f}"
    if run["outcome"] == "stalled":
        return f"{average:.2f} (stalled {run['unconverged_steps']})"
    if run["outcome"] == "diverged":
        return f"**div.** step {run['steps_completed'] + 1}"
    return f"{run['outcome']} after {run['steps_completed']}"


def collect(results):
    bench = read_bench(results)
    cases, variants = {}, []
    for run in bench["runs"]:
        name = run.get("case", "")
        if run["name"] not in variants:
            variants.append(run["name"])
        parameters = tube_parameters(bench_run_directory(results, run))
        case = cases.setdefault(name, {"parameters": parameters, "runs": {}})
        if parameters != case["parameters"]:
            raise ValueError(f"case {name}: variant {run['name']} has other tube parameters")
        case["runs"][run["name"]] = run
    for case in cases.values():
        factors = gauss_seidel_factors(**case["parameters"])
        case["lambda_1"] = factors[0]
        case["unstable"] = sum(1 for f in factors if f > 1)
    return cases, variants


def print_table(cases, variants):
    header = ["case", "ρs/ρf", "E [Pa]", "Δt [s]", "l [m]", "\\|λ₁\\|", "unstable modes"] + variants
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for name, case in cases.items():
        p = case["parameters"]
        row = [name, f"{p['rho_s'] / p['rho_f']:g}", f"{p['e']:g}", f"{p['delta_t']:g}",
               f"{p['length']:g}", f"{case['lambda_1']:.3g}", str(case["unstable"])]
        row += [cell(case["runs"][v]) if v in case["runs"] else "" for v in variants]
        print("| " + " | ".join(row) + " |")


def plot(cases, variants, output):
    import matplotlib

    matplotlib.use("Agg")  # no display needed
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(8, 5))
    for index, variant in enumerate(variants):
        # Several cases share a mode count: spread the variants a little sideways.
        shift = 1 + 0.04 * (index - (len(variants) - 1) / 2)
        points = sorted(((case["unstable"] * shift, case["runs"][variant])
                         for case in cases.values() if variant in case["runs"]),
                        key=lambda point: point[0])
        color = f"C{index}"
        converged = [(m, r["average_iterations"]) for m, r in points if r["outcome"] == "converged"]
        stalled = [(m, r["average_iterations"]) for m, r in points if r["outcome"] == "stalled"]
        diverged = [m for m, r in points if r["outcome"] not in ("converged", "stalled")]
        if converged:
            axes.plot(*zip(*converged), "o", color=color, label=variant, markersize=5)
        if stalled:
            axes.plot(*zip(*stalled), "s", color=color, markerfacecolor="none", markersize=8)
        if diverged:
            axes.plot(diverged, [0.8] * len(diverged), "x", color=color, markersize=8)
    axes.plot([], [], "ks", markerfacecolor="none", label="stalled (some steps at the limit)")
    axes.plot([], [], "kx", label="diverged (drawn at the bottom)")
    axes.set_xscale("symlog", linthresh=1)
    axes.set_yscale("log")
    axes.set_ylim(bottom=0.7)
    axes.set_xlabel("Gauss-Seidel-unstable wall modes (|λ_j| > 1, linear analysis)")
    axes.set_ylabel("average coupling iterations per time step")
    axes.set_title("Tube stability suite: every case x coupled solver", fontsize=10)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(output, dpi=110)
    print(f"\nwrote {output}")


def main(argv):
    args = parse_arguments(argv)
    cases, variants = collect(args.results)
    print_table(cases, variants)
    if args.output:
        plot(cases, variants, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
