#!/usr/bin/python3
"""Check a cocopp results file with h5py against the layout documented in docs/results.md.

Usage: read_results.py RESULTS.h5 [--expect EXPECTED.json]

Without --expect only the layout is checked (keys, types, shapes, consistency of the ragged
residuals and of the block description). With --expect the values are compared as well; the
JSON is written by tests/unit/coupler/results/test_results_python.cpp. Prints every problem found and
exits with 1 if there was any.
"""
import argparse
import json
import sys

import h5py
import numpy as np

ROOT_ATTRIBUTES = {
    "cocopp_version": str, "case_file": str, "coupled_solver": str, "created": str,
    "status": str, "message": str, "delta_t": float, "timestep_start": int,
    "number_of_timesteps": int,
}
STEP_DATASETS = ["step", "time", "iterations", "converged", "wall_time", "coupler_time",
                 "solver_times"]
BLOCK_ATTRIBUTES = ["block_model_part", "block_variable", "block_offset", "block_size",
                    "block_points", "block_components"]

problems = []


def expect(condition, message):
    if not condition:
        problems.append(message)
    return condition


def check_root(f):
    for name, kind in ROOT_ATTRIBUTES.items():
        if expect(name in f.attrs, f"root attribute '{name}' missing"):
            value = f.attrs[name]
            ok = isinstance(value, str) if kind is str else np.isscalar(value)
            expect(ok, f"root attribute '{name}' is {type(value).__name__}, expected {kind.__name__}")
    expect("solver_names" in f.attrs, "root attribute 'solver_names' missing")
    for group in ["steps", "residuals", "x", "y"]:
        expect(isinstance(f.get(group), h5py.Group), f"group '{group}' missing")


def check_steps(f):
    n = f["steps/step"].shape[0]
    for name in STEP_DATASETS:
        dataset = f["steps"].get(name)
        if expect(dataset is not None, f"steps/{name} missing"):
            expect(dataset.shape[0] == n, f"steps/{name} has {dataset.shape[0]} rows, not {n}")
    expect(f["steps/converged"].dtype == np.bool_, "steps/converged is not read as bool")
    solvers = len(f.attrs["solver_names"])
    expect(f["steps/solver_times"].shape == (n, solvers),
           f"steps/solver_times has shape {f['steps/solver_times'].shape}, not {(n, solvers)}")
    offset, count = f["residuals/offset"][:], f["residuals/count"][:]
    norms = f["residuals/norms"]
    expect(offset.shape == (n,) and count.shape == (n,), "residuals/offset or count not (steps,)")
    expect(np.array_equal(offset, np.concatenate(([0], np.cumsum(count)[:-1]))[:n]),
           "residuals/offset is not the running sum of residuals/count")
    expect(norms.shape == (int(count.sum()),), "residuals/norms length differs from sum(count)")
    return n


def check_interface(f, name, n):
    group = f[name]
    for attribute in ["model_parts", "size", "role"] + BLOCK_ATTRIBUTES:
        expect(attribute in group.attrs, f"{name}: attribute '{attribute}' missing")
    expect(set(group.keys()) == set(group.attrs["model_parts"]),
           f"{name}: groups {list(group.keys())} differ from model_parts")
    end = 0
    for part, variable, offset, size, points, components in zip(
            *(group.attrs[a] for a in BLOCK_ATTRIBUTES)):
        data = group[part][variable]
        expect(data.shape == (n, points, components),
               f"{name}/{part}/{variable} has shape {data.shape}, not {(n, points, components)}")
        expect(offset == end and size == points * components,
               f"{name}: block {part}/{variable} offset {offset} size {size} not contiguous")
        expect("unit" in data.attrs, f"{name}/{part}/{variable} has no unit")
        expect(group[part]["ids"].shape == (points,), f"{name}/{part}/ids shape")
        expect(group[part]["coordinates"].shape == (points, 3), f"{name}/{part}/coordinates shape")
        end = offset + size
    expect(end == group.attrs["size"], f"{name}: blocks cover {end} values, size is "
                                       f"{group.attrs['size']}")


def flat_vector(f, name, row):
    """The vector the coupled solver works on, rebuilt from the block description."""
    group = f[name]
    values = np.empty(group.attrs["size"])
    for part, variable, offset, size in zip(
            *(group.attrs[a] for a in BLOCK_ATTRIBUTES[:4])):
        values[offset:offset + size] = group[part][variable][row].ravel()
    return values


def residuals_of(f, row):
    start, count = f["residuals/offset"][row], f["residuals/count"][row]
    return f["residuals/norms"][start:start + count]


def close(a, b):
    return np.shape(a) == np.shape(b) and np.allclose(a, b, rtol=1e-14, atol=0)


def check_expected(f, e):
    for name in ["case_file", "coupled_solver", "status", "message", "cocopp_version"]:
        expect(f.attrs[name] == e[name], f"attribute {name}: {f.attrs[name]!r} != {e[name]!r}")
    expect(list(f.attrs["solver_names"]) == e["solver_names"], "solver_names differ")
    expect(f.attrs["delta_t"] == e["delta_t"], "delta_t differs")
    for name in ["step", "time", "iterations", "converged", "wall_time", "coupler_time",
                 "solver_times"]:
        expect(close(f["steps"][name][:], np.array(e[name], dtype=float)), f"steps/{name} differs")
    for row, history in enumerate(e["residuals"]):
        expect(close(residuals_of(f, row), np.array(history)), f"residuals of row {row} differ")
    for name in ["x", "y"]:
        expect(list(f[name].attrs["model_parts"]) == e[name]["model_parts"],
               f"{name}: model_parts differ")
        for part, ids in e[name]["ids"].items():
            expect(np.array_equal(f[name][part]["ids"][:], ids), f"{name}/{part}/ids differ")
        for row, flat in enumerate(e[name]["data"]):
            expect(close(flat_vector(f, name, row), np.array(flat)), f"{name} row {row} differs")


def check_docs_example(f, e):
    """The example of docs/results.md: displacement of step 10 and its residual history."""
    steps = f["steps/step"][:]
    if 10 not in steps:
        return
    row = int(np.flatnonzero(steps == 10)[0])
    displacement = f["x/wall/displacement"][row]  # (n_points, 3), m
    expected = np.array(e["x"]["data"][row])[:displacement.size].reshape(displacement.shape)
    expect(close(displacement, expected), "docs example: displacement of step 10 differs")
    start, count = f["residuals/offset"][row], f["residuals/count"][row]
    expect(close(f["residuals/norms"][start:start + count], np.array(e["residuals"][row])),
           "docs example: residuals of step 10 differ")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("results", help="results file (.h5)")
    parser.add_argument("--expect", help="JSON file with the expected values")
    args = parser.parse_args()
    with h5py.File(args.results, "r") as f:
        check_root(f)
        if not problems:
            n = check_steps(f)
            check_interface(f, "x", n)
            check_interface(f, "y", n)
        if args.expect and not problems:
            with open(args.expect) as stream:
                e = json.load(stream)
            check_expected(f, e)
            check_docs_example(f, e)
    for problem in problems:
        print("problem:", problem)
    print(f"{args.results}: {'OK' if not problems else f'{len(problems)} problem(s)'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
