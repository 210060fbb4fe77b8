#!/usr/bin/python3
"""Figures of a wire drawing run (docs/wire-drawing.md) from its results file.

    plot.py [CASE_DIR] [-o wire-drawing.png] [--parameters parameters.yaml] [--until STEP]

CASE_DIR is the case directory run.sh wrote (default results/case; it holds results/case.h5
and the wire's structure/results/step_NNNNN.frd). Six panels: the equivalent (von Mises) and
the hardened yield stress along the wire's surface, the film thickness and the wire's radial
displacement along the die, the pressure and the wire's shear along the die (each at the last
step with the die held and at the last step), the drawing force per step, the coupling
residuals of the last 5 time steps per iteration, and the coupling iterations per step against
the paper's average of 5.33.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import make_case  # noqa: E402
from cocopp.calculix import Frd  # noqa: E402
from cocopp.results import ResultsFile, results_path  # noqa: E402
from wire_results import (exit_force, film_profile, loads_profile, made_with,  # noqa: E402
                          step_files, surface)

HERE = pathlib.Path(__file__).resolve().parent
PAPER_ITERATIONS = 5.33


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", nargs="?", default=str(HERE / "results" / "case"))
    parser.add_argument("-o", "--output", default=None,
                        help="the figure (default: <case>/wire-drawing.png)")
    parser.add_argument("--parameters", default=str(HERE / "parameters.yaml"))
    parser.add_argument("--until", type=int, default=None, metavar="STEP",
                        help="plot the run up to this time step (default: all of it)")
    args = parser.parse_args()
    case = pathlib.Path(args.case)
    p, refine = made_with(case, args.parameters)
    film = make_case.Film(p, refine)
    schedule = make_case.die_schedule(p)
    output = pathlib.Path(args.output) if args.output else case / "wire-drawing.png"

    with ResultsFile(results_path(case / "case.yaml")) as results:
        steps = results.steps
        if args.until is not None:
            steps = steps[steps <= args.until]
        iterations = results.iterations[:len(steps)]
        held = min(p["time"]["held_steps"], len(steps)) - 1
        last = len(steps) - 1
        rows = sorted({held, last})
        fig, axes = plt.subplots(3, 2, figsize=(12, 12.5))
        (stress_ax, force_ax), (thick_ax, load_ax), (residual_ax, iteration_ax) = axes
        frds = step_files(case)
        times = results.times
        for row, style in zip(rows, ["-", "--"]):
            if int(steps[row]) not in frds:
                continue
            profile = surface(Frd(frds[int(steps[row])], {"DISP", "STRESS", "PE"}), p["wire"],
                              float(times[row]))
            near = (profile["z"] > -1e-3) & (profile["z"] < film.length + 2e-3)
            z = 1e3 * profile["z"][near]
            stress_ax.plot(z, 1e-6 * profile["von_mises"][near], "C0" + style,
                           label=f"von Mises, step {steps[row]}")
            stress_ax.plot(z, 1e-6 * profile["yield_stress"][near], "C3" + style,
                           label=f"yield stress, step {steps[row]}")
        stress_ax.axvspan(0, 1e3 * film.length, color="0.9", zorder=0)
        stress_ax.set(xlabel="z along the die [mm] (grey: under the film)",
                      ylabel="stress [MPa]",
                      title="equivalent and yield stress at the wire's surface (nodal)")
        stress_ax.legend(fontsize=8)

        force_steps = sorted(set(frds) & {int(v) for v in steps})
        forces = [exit_force(Frd(frds[s], {"FORC"}), p["wire"]) for s in force_steps]
        force_ax.plot(force_steps, forces, "o-", ms=3, label="drawing force (exit end)")
        force_ax.axhline(p["wire"]["back_force"], color="k", ls=":", label="back force")
        force_ax.set(xlabel="time step", ylabel="force [N]", title="drawing force per step")
        force_ax.legend(fontsize=8)

        disp_ax = thick_ax.twinx()
        for row, style in zip(rows, ["-", "--"]):
            z, thickness, radial = film_profile(results, film, schedule, row)
            label = f"step {steps[row]}"
            thick_ax.plot(1e3 * z, 1e6 * thickness, "C0" + style, label=f"film, {label}")
            disp_ax.plot(1e3 * z, 1e6 * radial, "C3" + style, label=f"wire u_r, {label}")
        thick_ax.set(xlabel="z along the die [mm]", ylabel="film thickness [µm]",
                     title="film thickness and the wire's radial displacement")
        disp_ax.set_ylabel("wire radial displacement [µm]", color="C3")
        thick_ax.legend(loc="upper left", fontsize=8)
        disp_ax.legend(loc="upper right", fontsize=8)
        thick_ax.set_ylim(bottom=0, top=min(thick_ax.get_ylim()[1], 40))

        shear_ax = load_ax.twinx()
        for row, style in zip(rows, ["-", "--"]):
            z, pressure, shear = loads_profile(results, row)
            load_ax.plot(1e3 * z, 1e-6 * pressure, "C0" + style, label=f"pressure, step {steps[row]}")
            shear_ax.plot(1e3 * z, 1e-6 * shear, "C2" + style, label=f"wire shear, step {steps[row]}")
        load_ax.set(xlabel="z along the die [mm]", ylabel="pressure [MPa]",
                    title="pressure and wall shear on the wire")
        shear_ax.set_ylabel("axial shear on the wire [MPa]", color="C2")
        load_ax.legend(loc="upper left", fontsize=8)
        shear_ax.legend(loc="lower right", fontsize=8)

        histories = results.residual_histories()[:len(steps)]
        for step, values, _ in histories[-5:]:
            residual_ax.semilogy(range(1, len(values) + 1), values, "o-", label=f"step {step}")
        residual_ax.axhline(1e-8, color="k", lw=0.8, ls=":", label="tolerance 0.01 µm")
        residual_ax.set(xlabel="coupling iteration", ylabel="‖r‖₂ [m]",
                        title="coupling residuals of the last 5 time steps")
        residual_ax.legend(fontsize=8)

        average = float(np.mean(iterations))
        iteration_ax.bar(steps, iterations, color="C0", label="cocopp, IQN-ILS")
        iteration_ax.axhline(average, color="C0", ls="--", label=f"average {average:.2f}")
        iteration_ax.axhline(PAPER_ITERATIONS, color="C3", ls=":",
                             label=f"paper's average {PAPER_ITERATIONS}")
        iteration_ax.set(xlabel="time step", ylabel="coupling iterations",
                         title="coupling iterations per time step")
        iteration_ax.legend(fontsize=8)
    fig.tight_layout()
    output.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(output, dpi=110)
    print(f"plot.py: {output} ({len(steps)} steps, {average:.2f} iterations per step)")


if __name__ == "__main__":
    main()
