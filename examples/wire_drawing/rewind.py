#!/usr/bin/python3
"""A copy of a wire drawing run that restarts after an earlier step: to measure a coupling
variant on the same steps from the same state (docs/wire-drawing.md, "Fewer coupling
iterations").

    /usr/bin/python3 examples/wire_drawing/rewind.py examples/wire_drawing/results/final 65 \\
        examples/wire_drawing/results/from65 --steps 72
    build/bin/cocopp run examples/wire_drawing/results/from65/case.yaml --restart

--wire KEY=VALUE sets a key of the calculix wrapper's settings (repeatable), --omega sets the
coupled solver's first relaxation, --predictor its predictor (linear, quadratic, cubic), and --compliance writes the wire's surface compliance
(surface_compliance.py) and uses it (surface_compliance: surface_compliance.txt): the drive
variants of docs/wire-drawing.md, "Fewer coupling iterations".

The copy holds the case file (number_of_timesteps set to --steps), the film's case with its
time directories up to the step, the wire's deck and its restart files up to the step (saved
every state_interval steps: the step must be one of them), the results file, and a state file
for the step (cocopp.state.rewind_state: the predictor's history from the results file). The
run must not carry secant columns between steps (the case's IQN-ILS has none)."""
import argparse
import re
import shutil
import sys
from pathlib import Path

from cocopp.executable import patched_ccx
from cocopp.state import rewind_state
from surface_compliance import write_checked


# The converged steps each predictor extrapolates from.
HISTORY = {"constant": 1, "linear": 2, "legacy": 2, "quadratic": 3, "cubic": 4}


def copy_film(source, target, last_time):
    """The film's case without the time directories after `last_time`."""
    def later(directory, names):
        return [n for n in names if directory == str(source) and is_later(n, last_time)]
    shutil.copytree(source, target, ignore=later)


def is_later(name, last_time):
    try:
        return float(name) > last_time * (1 + 1e-9)
    except ValueError:
        return False


def copy_wire(source, target, step):
    """The wire's directory without its results and with restart files up to `step`."""
    def skipped(directory, names):
        if directory == str(source):
            return [n for n in names if n == "results" or n.startswith("cocopp_iteration")]
        if directory == str(source / "restart"):
            return [n for n in names
                    if (m := re.search(r"_(\d+)\.r", n)) and int(m.group(1)) > step]
        return []
    shutil.copytree(source, target, ignore=skipped)
    restart = target / "restart"
    if not any(restart.glob(f"*_{step:06d}.restart")):
        sys.exit(f"rewind.py: {source / 'restart'} has no restart file for step {step} "
                 "(saved every state_interval steps)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", type=Path, help="a run's case directory (results/<name>)")
    parser.add_argument("step", type=int, help="the step to restart after")
    parser.add_argument("target", type=Path, help="the new case directory")
    parser.add_argument("--steps", type=int, help="the copy's number_of_timesteps")
    parser.add_argument("--wire", action="append", default=[], metavar="KEY=VALUE",
                        help="a key of the calculix wrapper's settings (repeatable)")
    parser.add_argument("--omega", type=float, help="the coupled solver's omega")
    parser.add_argument("--predictor", choices=sorted(HISTORY), help="the predictor")
    parser.add_argument("--compliance", action="store_true",
                        help="compute the wire's surface compliance and drive with it")
    args = parser.parse_args()
    if args.target.exists():
        sys.exit(f"rewind.py: {args.target} exists")
    case = (args.run / "case.yaml").read_text()
    delta_t = float(re.search(r"delta_t:\s*(\S+)", case).group(1))
    args.target.mkdir(parents=True)
    if args.steps:
        case = re.sub(r"(number_of_timesteps:\s*)\d+", rf"\g<1>{args.steps}", case)
    if args.predictor:
        case = re.sub(r"(\n  predictor:\n    type:\s*)\w+", rf"\g<1>{args.predictor}", case, count=1)
    if args.omega is not None:
        case = re.sub(r"(\n  omega:\s*)[0-9.e+-]+", rf"\g<1>{args.omega}", case, count=1)
    keys = list(args.wire) + (["surface_compliance=surface_compliance.txt"] if args.compliance
                              else [])
    for key in keys:
        name, _, value = key.partition("=")
        if not value:
            sys.exit(f"rewind.py: --wire {key}: give KEY=VALUE")
        # A key the wrapper has gets the new value (its comment dropped); a new one goes after
        # the wrapper's surface_stiffness, at its indentation.
        case, found = re.subn(rf"(\n( *){re.escape(name)}:)[^\n]*", rf"\1 {value}", case, count=1)
        if not found:
            case, found = re.subn(r"(\n( *)surface_stiffness:[^\n]*)", rf"\1\n\2{name}: {value}",
                                  case, count=1)
        if not found:
            sys.exit("rewind.py: the case has no surface_stiffness (is its wire driven?)")
    (args.target / "case.yaml").write_text(case)
    shutil.copy(args.run / "made_with.yaml", args.target)
    copy_film(args.run / "fluid", args.target / "fluid", args.step * delta_t)
    copy_wire(args.run / "structure", args.target / "structure", args.step)
    if args.compliance:
        write_checked(args.target / "structure", patched_ccx())
    results = args.target / "results"
    results.mkdir()
    shutil.copy(args.run / "results" / "case.h5", results)
    rewind_state(results / "case.h5", args.run / "results" / "case.state.h5", args.step,
                 results / "case.state.h5", HISTORY.get(args.predictor))
    print(f"{args.target}: restarts after step {args.step}: "
          f"cocopp run {args.target / 'case.yaml'} --restart")


if __name__ == "__main__":
    main()
