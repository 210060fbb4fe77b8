#!/usr/bin/env python3
"""Plot the result of `cocopp bench`: the error against the reference versus wall time,
coupling iterations and the solvers' time, one panel each.

Reads <output_directory>/bench.json (written by cocopp bench, docs/bench.md); each point is a
run labelled with its variant. Wall time includes the solvers' start-up, which dominates short
runs; the iterations are free of timing noise; the solvers' time is what the iterations cost.
An error of exactly 0 (a run identical to the reference) is drawn on the bottom edge with the
label "(= reference)"; runs without an error are listed under the plot. The figure is made by
the package cocopp (cocopp.plot.bench, docs/python.md).

    /usr/bin/python3 scripts/plot_bench.py results/bench/bench.json -o results/bench/bench.png
"""
import argparse
import os
import sys

# The package cocopp beside this script, as cocopp bench runs it without a PYTHONPATH: a
# checkout's python/, or an install's (and the build tree's) lib/python3/dist-packages.
HERE = os.path.dirname(os.path.realpath(__file__))
sys.path[:0] = [os.path.join(HERE, "..", "python"),
                os.path.join(HERE, "..", "..", "lib", "python3", "dist-packages")]


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("bench_json", help="bench.json written by cocopp bench")
    parser.add_argument("-o", "--output", default="bench.png", help="PNG to write (default: %(default)s)")
    parser.add_argument("--error", choices=["displacement", "pressure"], default="displacement",
                        help="which error to plot (default: %(default)s)")
    parser.add_argument("--include-reference", action="store_true",
                        help="also draw the computed reference run")
    return parser.parse_args(argv)


def main(argv):
    args = parse_arguments(argv)
    import matplotlib

    matplotlib.use("Agg")  # no display needed
    from cocopp.plot import bench
    from cocopp.results import read_bench

    bench.plot_bench(read_bench(args.bench_json), args.output, args.error, args.include_reference)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
