#!/usr/bin/python3
"""The checks an expert makes on a wire drawing run (docs/wire-drawing.md), as numbers.

    checks.py [CASE_DIR] [--step N]

CASE_DIR is the case directory run.sh wrote (default results/case). The checks are made at the
last time step (or --step N) from the coupler's results file and the wire's .frd file of that
step; they are printed and written to CASE_DIR/checks.json:
- coupling iterations per step against the paper's 5.33;
- film thickness where the die's approach ends (the entry cone and its rounded transition into
  the bearing) against Wilson and Walowit's inlet-zone
  estimate h0 = 3 eta U / ((Y - sigma_b) tan alpha);
- reduction of the cross section just behind the bearing (the wire the die drew in its last
  step);
- drawing stress (exit force over the drawn cross section) against the ideal-work estimate
  Y ln(A0/A1) + sigma_b and Sachs' estimate with the friction the film computed; and the
  drawing force against its terms: back force + ideal work of the local reduction + the film's
  viscous shear;
- steady drawing: how far the drawing force and the film at the end of the cone moved over
  the last 10 steps;
- axial force balance of the wire: exit force = back force - axial film force, with the film
  force integrated on the film's faces (shear, and the pressure on the wall's slope), and, at
  the last step, as ccx applied it on the wire's moved surface (structure/cocopp_loads.inp);
- the film's load against what reached the wire (last step): total shear and pressure;
- the largest ratio of equivalent (von Mises) stress to hardened yield stress at the surface.
"""
import argparse
import json
import math
import pathlib

import numpy as np

import make_case
from cocopp.calculix import Frd
from cocopp.results import ResultsFile, read_summary, results_path
from wire_results import (exit_force, film_exact_forces, film_forces, film_profile,
                          integration_point_check, made_with, sector_wire_forces, step_files,
                          surface, wire_forces)

HERE = pathlib.Path(__file__).resolve().parent
PAPER_ITERATIONS = 5.33
# The reduction is measured on the wire the die drew in its last steps.
BEHIND_BEARING_STEPS = 1
# Steady drawing: the drawing force and the inlet film within 1 % over this many steps.
STEADY_WINDOW = 10


def sachs_drawing_stress(yield_stress, back_stress, area_ratio, friction, half_angle):
    """Sachs' drawing stress for a conical die with Coulomb friction mu: B = mu cot(alpha)."""
    b = friction / math.tan(half_angle)
    if b < 1e-9:
        return yield_stress * math.log(1 / area_ratio) + back_stress
    return (yield_stress * (1 + b) / b * (1 - area_ratio ** b)
            + back_stress * area_ratio ** b)


def step_balances(case, run, film, wire):
    """Per time step with a .frd file: the wire's axial balance against the film's own force,
    (exit force - (back force - film's axial force)) / exit force. The film's force is what
    it summed on its faces in the step's last iteration; the wire took it as nodal forces
    (a conservative mapping), so the balance holds to ccx's equilibrium tolerance every step."""
    errors = {}
    for step, path in step_files(case).items():
        if step not in run.steps:
            continue
        pull = exit_force(Frd(path), wire)
        film_axial = film_exact_forces(run, film, run.row(step))["axial"]
        errors[step] = (pull - (wire["back_force"] - film_axial)) / pull
    return errors


def steadiness(case, run, film, schedule, wire, last_step, window=STEADY_WINDOW):
    """The drawing force (from each step's .frd) and the film where the die's approach ends,
    per step up to `last_step`, and how far each moved over the last `window` steps:
    (largest - smallest) / mean. None before `window` steps."""
    approach_end = film.entry + film.transition
    force, inlet = {}, {}
    for step, path in step_files(case).items():
        if step in run.steps and step <= last_step:
            force[step] = exit_force(Frd(path), wire)
            z, thickness, _ = film_profile(run, film, schedule, run.row(step))
            inlet[step] = float(np.interp(approach_end, z, thickness))
    last = sorted(force)[-window:]
    if len(last) < window or last[-1] - last[0] != window - 1:
        return None

    def spread(values):
        values = [values[s] for s in last]
        return (max(values) - min(values)) / abs(float(np.mean(values)))
    return {"steady_window": [last[0], last[-1]], "drawing_force_spread": spread(force),
            "film_at_cone_end_spread": spread(inlet),
            "drawing_force_history": {str(k): v for k, v in force.items()},
            "film_at_cone_end_history": {str(k): v for k, v in inlet.items()}}


def run_checks(case, p, refine, step=None):
    wire, die, lubricant = p["wire"], p["die"], p["lubricant"]
    film = make_case.Film(p, refine)
    schedule = make_case.die_schedule(p)
    results = {}
    results_file = results_path(case / "case.yaml")
    with ResultsFile(results_file) as run:
        steps = run.steps
        row = len(steps) - 1 if step is None else run.row(step)
        time = float(run.times[row])
        iterations = run.iterations
        results["steps"] = int(len(steps))
        results["step"] = int(steps[row])
        results["iterations_per_step"] = float(np.mean(iterations))
        results["paper_iterations_per_step"] = PAPER_ITERATIONS

        z, thickness, radial = film_profile(run, film, schedule, row)
        # Where the die's approach ends and the bearing begins (the cone's end, or the end of
        # the rounded transition after it).
        approach_end = film.entry + film.transition
        results["film_thickness_at_cone_end"] = float(np.interp(approach_end, z, thickness))
        results["film_thickness_min"] = float(np.min(thickness))
        back_stress = wire["back_force"] / (math.pi * wire["radius"] ** 2)
        alpha = math.radians(die["half_angle_degrees"])
        results["wilson_walowit_h0"] = (3 * lubricant["viscosity"] * wire["drawing_speed"]
                                        / ((wire["yield_stress"] - back_stress) * math.tan(alpha)))
        forces = film_forces(run, film, schedule, row)
        exact = film_exact_forces(run, film, row)
        balance = step_balances(case, run, film, wire) if exact is not None else None
        steady = steadiness(case, run, film, schedule, wire, results["step"])
    if steady:
        results.update(steady)
    results.update({f"film_{k}": v for k, v in forces.items()})
    if exact is not None:
        results.update({f"film_exact_{k}": v for k, v in exact.items()})
    if balance:
        step, error = max(balance.items(), key=lambda item: abs(item[1]))
        results["force_balance_error_film_largest"] = error
        results["force_balance_error_film_largest_step"] = step
        results["force_balance_steps"] = len(balance)

    frd_path = step_files(case)[results["step"]]
    frd = Frd(frd_path)
    pull = exit_force(frd, wire)
    results["exit_force"] = pull
    # With the film's loads integrated on the film (the pressure's axial part from the slope of
    # the film's wall points, which only approximates the wire's wavy surface under the die).
    # The film's own sum where it gives one, else the estimate from its wall's slope.
    film_axial = (exact["axial"] if exact is not None
                  else forces["shear_axial"] + forces["pressure_axial"])
    results["force_balance_error_film"] = (pull - (wire["back_force"] - film_axial)) / pull
    # A run still going (or killed) has no summary yet: its steps so far are checked all the same.
    summary = read_summary(results_file, missing_ok=True)
    axisymmetric = p["mesh"].get("wire_model", "axisymmetric") == "axisymmetric"
    last_of_run = (results["step"] == results["steps"]
                   and summary.get("status") in ("completed", "stalled"))
    # The loads ccx applied in the last coupling iteration (after a run that stopped, the loads
    # file is of the step that failed).
    if last_of_run and not axisymmetric:
        # A sector takes them as nodal forces, and where it is driven by displacement the film's
        # pressure as the drive's reactions: only the axial and the radial sums compare.
        applied = sector_wire_forces(case, frd)
        results.update({f"wire_{k}": v for k, v in applied.items()})
        results["force_balance_error"] = (pull - (wire["back_force"] - applied["axial"])) / pull
        results["transfer_error_axial"] = applied["axial"] / film_axial - 1
        # (The film's pressure pushes inwards, along -r.)
        results["transfer_error_radial"] = (applied["radial"] / exact["radial"] - 1
                                            if exact is not None else
                                            -applied["radial"] / forces["pressure_radial"] - 1)
    if last_of_run and axisymmetric:
        # On the wire's moved surface.
        applied = wire_forces(case, frd)
        results.update({f"wire_{k}": v for k, v in applied.items()})
        wire_axial = applied["shear_axial"] + applied["pressure_axial"]
        results["force_balance_error"] = (pull - (wire["back_force"] - wire_axial)) / pull
        results["transfer_error_shear"] = applied["shear_axial"] / forces["shear_axial"] - 1
        results["transfer_error_pressure"] = (applied["pressure_total"]
                                              / forces["pressure_total"] - 1)

    profile = surface(frd, wire, time)
    # The wire as the die draws it now: the surface just behind the bearing, over the length
    # it travels in BEHIND_BEARING_STEPS steps (farther downstream is wire the die drew while it
    # was still closing; the mean over all of it is reported as reduction_downstream_mean).
    behind = BEHIND_BEARING_STEPS * wire["drawing_speed"] * p["time"]["delta_t"]
    just_behind = (profile["z"] > film.length) & (profile["z"] <= film.length + behind)
    if not np.any(just_behind):
        just_behind = profile["z"] > film.length
    drawn_radius = wire["radius"] + float(np.mean(profile["u_r"][just_behind]))
    area_ratio = (drawn_radius / wire["radius"]) ** 2
    results["reduction"] = 1 - area_ratio
    results["reduction_measured_over"] = [film.length, film.length + behind]
    downstream = profile["z"] > film.length
    results["reduction_downstream_mean"] = 1 - ((wire["radius"] + float(
        np.mean(profile["u_r"][downstream]))) / wire["radius"]) ** 2
    results["drawing_stress"] = pull / (math.pi * drawn_radius ** 2)
    mean_yield = float(np.mean(profile["yield_stress"][just_behind]))
    results["mean_yield_stress_drawn"] = mean_yield
    results["ideal_work_stress"] = (0.5 * (wire["yield_stress"] + mean_yield)
                                    * math.log(1 / area_ratio) + back_stress)
    results["ideal_work_stress_nominal"] = (wire["yield_stress"] * math.log(1 / (1 - die["reduction"]))
                                            + back_stress)
    friction = forces["shear_total"] / forces["pressure_total"] if forces["pressure_total"] > 0 else 0
    results["friction_coefficient"] = friction
    results["sachs_stress"] = sachs_drawing_stress(0.5 * (wire["yield_stress"] + mean_yield),
                                                   back_stress, area_ratio, friction, alpha)
    # The drawing force term by term: the back force, the ideal work of the reduction the die
    # draws now (homogeneous, frictionless: Y ln(A0/A1) on the drawn section, Y the mean of the
    # initial and the drawn yield stress) and the film's viscous shear, which a film carries
    # instead of Coulomb friction. Redundant work (the die's shearing of the section) is left
    # out: it is what the estimate misses.
    terms = {"back_force": wire["back_force"],
             "ideal_work": (0.5 * (wire["yield_stress"] + mean_yield) * math.log(1 / area_ratio)
                            * math.pi * drawn_radius ** 2),
             "film_shear": -forces["shear_axial"]}
    results["drawing_force_terms"] = terms
    results["drawing_force_estimate"] = sum(terms.values())
    results["drawing_force_error"] = pull / results["drawing_force_estimate"] - 1
    at_points = integration_point_check(frd_path.with_suffix(".dat"), wire)
    if at_points:
        results["max_equivalent_over_yield"], results["max_plastic_strain_surface"] = at_points
        results["equivalent_stress_at"] = "integration points of the outer elements"
    else:  # nodal values are extrapolated from the integration points: they overshoot
        ratio = profile["von_mises"] / profile["yield_stress"]
        results["max_equivalent_over_yield"] = float(np.max(ratio))
        results["max_plastic_strain_surface"] = float(np.max(profile["peeq"]))
        results["equivalent_stress_at"] = "surface nodes (extrapolated)"
    return results


def report(results):
    r = results
    lines = [
        f"step {r['step']} of {r['steps']}",
        f"coupling iterations per step   {r['iterations_per_step']:.2f} (paper {r['paper_iterations_per_step']})",
        f"film at the end of the cone    {1e6 * r['film_thickness_at_cone_end']:.2f} um "
        f"(Wilson-Walowit h0 {1e6 * r['wilson_walowit_h0']:.2f} um); thinnest {1e6 * r['film_thickness_min']:.2f} um",
        f"reduction of the cross section {100 * r['reduction']:.2f} % just behind the bearing "
        f"({1e3 * r['reduction_measured_over'][0]:.2f}-{1e3 * r['reduction_measured_over'][1]:.2f} mm; "
        f"{100 * r['reduction_downstream_mean']:.2f} % over all the wire past the die)",
        f"drawing force                  {r['exit_force']:.1f} N",
        f"drawing stress                 {1e-6 * r['drawing_stress']:.1f} MPa (ideal work "
        f"{1e-6 * r['ideal_work_stress']:.1f} MPa for this reduction, {1e-6 * r['ideal_work_stress_nominal']:.1f} "
        f"MPa nominal; Sachs {1e-6 * r['sachs_stress']:.1f} MPa with mu {r['friction_coefficient']:.4f})",
        f"drawing force, its terms       {r['drawing_force_estimate']:.1f} N = back force "
        f"{r['drawing_force_terms']['back_force']:.1f} N + ideal work "
        f"{r['drawing_force_terms']['ideal_work']:.1f} N + film shear "
        f"{r['drawing_force_terms']['film_shear']:.1f} N; the computed force "
        f"{100 * r['drawing_force_error']:+.1f} % from it",
        f"axial force balance, film      {100 * r['force_balance_error_film']:+.3f} % (film: shear "
        f"{r['film_shear_axial']:.1f} N, pressure {r['film_pressure_axial']:.1f} N, estimated "
        f"from the wall's slope)",
        f"equivalent / yield at surface  {r['max_equivalent_over_yield']:.4f} at most "
        f"(largest plastic strain {r['max_plastic_strain_surface']:.4f}; {r['equivalent_stress_at']})",
    ]
    if "film_exact_axial" in r:
        lines += [f"film force on the wire, summed  axial {r['film_exact_axial']:.2f} N, radial "
                  f"{r['film_exact_radial']:.2f} N (the film's own sum over its faces)"]
    if "force_balance_error_film_largest" in r:
        lines += [f"axial force balance, each step {100 * r['force_balance_error_film_largest']:+.4f} % "
                  f"at most (step {r['force_balance_error_film_largest_step']}, of "
                  f"{r['force_balance_steps']} steps)"]
    if "steady_window" in r:
        lines += [f"steady drawing, steps {r['steady_window'][0]}-{r['steady_window'][1]}     "
                  f"drawing force within {100 * r['drawing_force_spread']:.2f} %, film at the end "
                  f"of the cone within {100 * r['film_at_cone_end_spread']:.2f} % (steady: 1 %)"]
    if "transfer_error_axial" in r:
        lines += [
            f"axial force balance, wire      {100 * r['force_balance_error']:+.4f} % (as applied: "
            f"{r['wire_axial']:.2f} N axial)",
            f"film load reaching the wire    axial {r['transfer_error_axial']:+.2e}, radial "
            f"{r['transfer_error_radial']:+.2e} (relative difference)"]
    elif "force_balance_error" in r:
        lines += [
            f"axial force balance, wire      {100 * r['force_balance_error']:+.4f} % (as applied: "
            f"shear {r['wire_shear_axial']:.2f} N, pressure {r['wire_pressure_axial']:.2f} N)",
            f"film load reaching the wire    shear {r['transfer_error_shear']:+.2e}, pressure "
            f"{r['transfer_error_pressure']:+.2e} (relative difference)"]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", nargs="?", default=str(HERE / "results" / "case"))
    parser.add_argument("--step", type=int, default=None, help="the time step (default: the last)")
    parser.add_argument("--parameters", default=str(HERE / "parameters.yaml"),
                        help="for a case without made_with.yaml")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="for a case without made_with.yaml: as make_case.py --set")
    args = parser.parse_args()
    case = pathlib.Path(args.case)
    p, refine = made_with(case, args.parameters, args.set)
    results = run_checks(case, p, refine, args.step)
    print(report(results))
    (case / "checks.json").write_text(json.dumps(results, indent=2) + "\n")


if __name__ == "__main__":
    main()
