#!/usr/bin/env python3
"""CFD3's frequency against the time step and PIMPLE's outer correctors (docs/validation-turek-hron.md,
"Where CFD3's frequency bias comes from").

Runs CFD3 on a level (default 1) from rest to --settle seconds (Δt 2 ms, the case as it ships:
one outer corrector, i.e. PISO), then continues that developed flow for --span seconds with
each variant below, and prints post.py's drag and lift of each (its last 4 periods) against
the reference:

  dt2_outer1    Δt 2 ms, nOuterCorrectors 1 (PISO; the settling run's own continuation)
  dt1_outer1    Δt 1 ms
  dt05_outer1   Δt 0.5 ms
  dt2_outer2    Δt 2 ms, nOuterCorrectors 2
  dt2_outer3    Δt 2 ms, nOuterCorrectors 3
  dt1_outer3    Δt 1 ms, nOuterCorrectors 3

With --level2-span S, the last variant's flow (dt2_outer3) is then mapped onto the level-2
mesh (mapFields) and run S seconds more there, Δt 2 ms, three outer correctors: level2_dt2_outer3.

    /usr/bin/python3 examples/turek_hron/fsi/cfd3_time_study.py [--level 1] [--settle 16] [--span 4]
        [--level2-span 5]

Writes results/cfd3_time/<variant>/ (each a CFD3 case directory) and results/cfd3_time/study.json.
"""
import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
VARIANTS = {"dt2_outer1": (0.002, 1), "dt1_outer1": (0.001, 1), "dt05_outer1": (0.0005, 1),
            "dt2_outer2": (0.002, 2), "dt2_outer3": (0.002, 3), "dt1_outer3": (0.001, 3)}
ENV = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"))


def make(directory, level, dt, end_time, outer):
    subprocess.run([sys.executable, str(HERE / "make_case.py"), "cfd3", str(directory),
                    "--level", str(level), "--dt", str(dt), "--end-time", str(end_time),
                    "--outer-correctors", str(outer)], check=True, stdout=subprocess.DEVNULL)


def pimple(fluid):
    """pimpleFoam in `fluid`; its log there. Returns the wall time."""
    started = time.perf_counter()
    with open(fluid / "log.pimpleFoam", "w") as log:
        done = subprocess.run(["pimpleFoam"], cwd=fluid, env=ENV, stdout=log,
                              stderr=subprocess.STDOUT)
    if done.returncode != 0:
        sys.exit(f"cfd3_time_study.py: pimpleFoam failed, see {fluid / 'log.pimpleFoam'}")
    return time.perf_counter() - started


def start_at(fluid, start):
    """controlDict's startTime set to `start` (its time directory is the caller's)."""
    control = fluid / "system/controlDict"
    control.write_text(re.sub(r"(?m)^startTime .*$", f"startTime       {start:g};",
                              control.read_text()))


def continue_from(settled, directory, level, dt, outer, start, end):
    """A variant's case: made as CFD3, with the settled run's fields at `start`."""
    make(directory, level, dt, end, outer)
    fluid = directory / "fluid"
    subprocess.run([str(fluid / "Allmesh")], check=True)
    shutil.copytree(settled / "fluid" / f"{start:g}", fluid / f"{start:g}")
    start_at(fluid, start)
    return pimple(fluid)


def on_level_2(source, directory, start, span):
    """`source`'s last fields mapped onto a level-2 CFD3 case, run `span` s from `start`."""
    make(directory, 2, 0.002, start + span, 3)
    fluid = directory / "fluid"
    subprocess.run([str(fluid / "Allmesh")], check=True)
    shutil.copytree(fluid / "0", fluid / f"{start:g}")
    start_at(fluid, start)
    with open(fluid / "log.mapFields", "w") as log:
        subprocess.run(["mapFields", str(source / "fluid"), "-consistent", "-sourceTime",
                        "latestTime"], cwd=fluid, env=ENV, stdout=log, stderr=subprocess.STDOUT,
                       check=True)
    return pimple(fluid)


def post(directory):
    """post.py's drag and lift rows over the last 4 periods."""
    subprocess.run([sys.executable, str(HERE / "post.py"), str(directory), "--periods", "4"],
                   check=True, stdout=subprocess.DEVNULL)
    return json.loads((directory / "post.json").read_text())


def report(name, dt, outer, seconds, span, table):
    """One variant's row of study.json, printed."""
    lift, drag = table["lift"], table["drag"]
    print(f"{name:18s} lift {lift['frequency']:.3f} Hz ({100 * lift['frequency_error']:+.1f} %), "
          f"amplitude {100 * lift['amplitude_error']:+.1f} %; drag amplitude "
          f"{100 * drag['amplitude_error']:+.1f} %; {seconds / span:.1f} s per simulated s",
          flush=True)
    return {"name": name, "dt": dt, "outer_correctors": outer,
            "wall_time_per_simulated_s": seconds / span, "post": table}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--level", type=int, default=1)
    parser.add_argument("--settle", type=float, default=16.0, help="s from rest before the variants")
    parser.add_argument("--span", type=float, default=4.0, help="s each variant runs")
    parser.add_argument("--level2-span", type=float, default=0.0,
                        help="s the last variant then runs on level 2 (0: not)")
    args = parser.parse_args()
    out = HERE / "results" / "cfd3_time"
    shutil.rmtree(out, ignore_errors=True)
    settled = out / "settle"
    print(f"settling: level {args.level}, {args.settle:g} s from rest ...", flush=True)
    make(settled, args.level, 0.002, args.settle, 1)
    subprocess.run([str(settled / "fluid/Allmesh")], check=True)
    pimple(settled / "fluid")
    rows = []
    for name, (dt, outer) in VARIANTS.items():
        directory = out / name
        seconds = continue_from(settled, directory, args.level, dt, outer, args.settle,
                                args.settle + args.span)
        rows.append(report(name, dt, outer, seconds, args.span, post(directory)))
    if args.level2_span > 0:
        directory = out / "level2_dt2_outer3"
        seconds = on_level_2(out / "dt2_outer3", directory, args.settle + args.span,
                             args.level2_span)
        rows.append(report("level2_dt2_outer3", 0.002, 3, seconds, args.level2_span,
                           post(directory)))
    (out / "study.json").write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    main()
