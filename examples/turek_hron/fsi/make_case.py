#!/usr/bin/env python3
"""Write a Turek-Hron FSI test as a cocopp case (docs/validation-turek-hron.md).

    make_case.py fsi1|fsi2|fsi3|cfd3 OUTPUT [--level 1] [--dt 0.001] [--end-time 15] [--q 10]
                 [--tolerance 1e-7] [--alpha -0.1] [--pressure-rel-tol 0] [--cores 1]
                 [--fluid-substeps 1]

OUTPUT/fluid: the channel as an OpenFOAM case for cocoppPimpleFoam (make_mesh.py's blockMeshDict,
its Allmesh runs blockMesh); OUTPUT/flag/flag.inp: the flag in CalculiX (the CSM tests' flag,
cocopp.turek_hron, as ../csm/make_flag.py writes it);
OUTPUT/case.yaml: the coupled case (IQN-ILS with reuse). The benchmark of S. Turek and J. Hron,
"Proposal for numerical benchmarking of fluid-structure interaction between an elastic object
and laminar incompressible flow", in: Fluid-Structure Interaction, LNCSE 53, Springer 2006,
371-385: fluid rho 1000 kg/m3, nu 1e-3 m2/s; parabolic inflow of mean speed U (fsi1 0.2,
fsi2 1, fsi3 2 m/s) ramped up by (1 - cos(pi t / 2)) / 2 over the first 2 s.

cfd3 is the benchmark's CFD3 test, the fluid alone with the flag rigid at FSI3's inflow:
OUTPUT/fluid only, a static mesh, for OpenFOAM's own pimpleFoam (its Allrun), to tell the
fluid's share of an FSI3 error from the coupled one.
"""
import argparse
import json
import math
import pathlib
import sys

import make_mesh
from cocopp import case, openfoam, turek_hron
from cocopp.openfoam import header

RHO_FLUID, NU_FLUID = 1000.0, 1.0e-3
MEAN_INFLOW = {"fsi1": 0.2, "fsi2": 1.0, "fsi3": 2.0, "cfd3": 2.0}
RAMP_TIME = 2.0
# Time step and end time of each test unless given: fsi1 runs to its steady state, fsi2 and
# fsi3 until their oscillation has settled; cfd3's rigid flag sheds its wake from the symmetric
# start slowly (it settles by about 15 s on level 1).
DEFAULT_DT = {"fsi1": 0.01, "fsi2": 0.002, "fsi3": 0.001, "cfd3": 0.001}
DEFAULT_END = {"fsi1": 10.0, "fsi2": 15.0, "fsi3": 10.0, "cfd3": 20.0}


ENDTIME_MARGIN = 1000.0  # s beyond the run's end (controlDict's endTime)


def inflow(y, mean, ramp):
    return 1.5 * mean * y * (make_mesh.HEIGHT - y) / (0.5 * make_mesh.HEIGHT) ** 2 * ramp


def inlet_boundary_data(mean, depth, samples=51, ramp_samples=401):
    """constant/boundaryData/inlet: the parabolic profile at `samples` heights (on both planes of
    the one-cell-thick mesh), at `ramp_samples` times of the ramp; timeVaryingMappedFixedValue
    interpolates linearly between them (profile error 4e-4 of the mean speed, ramp 4e-6) and
    keeps the last after it."""
    heights = [make_mesh.HEIGHT * k / (samples - 1) for k in range(samples)]
    points = [(0.0, y, z) for z in (0.0, depth) for y in heights]
    files = {"constant/boundaryData/inlet/points":
             f"{len(points)}\n(\n" + "".join(f"({x} {y:.15g} {z})\n" for x, y, z in points) + ")\n"}
    for k in range(ramp_samples):
        t = RAMP_TIME * k / (ramp_samples - 1)
        ramp = 0.5 * (1.0 - math.cos(math.pi * t / RAMP_TIME))
        values = "".join(f"({inflow(y, mean, ramp):.15g} 0 0)\n" for _, y, _ in points)
        files[f"constant/boundaryData/inlet/{t:.6g}/U"] = f"{len(points)}\n(\n{values})\n"
    return files


ALLMESH = """\
#!/bin/sh
# Meshes the channel (make_case.py): blockMesh, then checkMesh.
cd "$(dirname "$0")" || exit 1
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
blockMesh > log.blockMesh 2>&1 || { echo "Allmesh: blockMesh failed, see $PWD/log.blockMesh" >&2; exit 1; }
checkMesh > log.checkMesh 2>&1 || { echo "Allmesh: checkMesh failed, see $PWD/log.checkMesh" >&2; exit 1; }
"""

FIXED_WALLS = ("    walls        { type noSlip; }\n    cylinder     { type noSlip; }\n"
               "    frontAndBack { type empty; }\n")


# The coupled tests' mesh motion: the flag's displacement from the coupler.
MESH_MOTION_FILES = {
    "0/pointDisplacement": header("pointVectorField", "pointDisplacement") +
    "// flag: the coupler's displacement; everything else stays.\n"
    "dimensions      [0 1 0 0 0 0 0];\ninternalField   uniform (0 0 0);\nboundaryField\n{\n"
    "    flag         { type fixedValue; value uniform (0 0 0); }\n"
    "    inlet        { type fixedValue; value uniform (0 0 0); }\n"
    "    outlet       { type fixedValue; value uniform (0 0 0); }\n"
    "    walls        { type fixedValue; value uniform (0 0 0); }\n"
    "    cylinder     { type fixedValue; value uniform (0 0 0); }\n"
    "    frontAndBack { type empty; }\n}\n",
    "constant/dynamicMeshDict": header("dictionary", "dynamicMeshDict") +
    "dynamicFvMesh   dynamicMotionSolverFvMesh;\n"
    "motionSolverLibs (\"libfvMotionSolvers.so\");\n"
    "// The flag's motion spread by a Laplacian whose diffusivity falls with the square of the\n"
    "// distance from the flag: the cells next to it move with it, rigidly, and the\n"
    "// distortion goes to the larger cells further out.\n"
    "solver          displacementLaplacian;\n"
    "displacementLaplacianCoeffs\n{\n    diffusivity     quadratic inverseDistance (flag);\n}\n",
}


def end_time_entry(rigid, end_time):
    if rigid:  # pimpleFoam alone: endTime ends the run
        return f"endTime         {end_time:.15g};\n"
    return ("// The coupler ends the run (case.yaml's number_of_timesteps); endTime lies beyond it so\n"
            "// that a restart or a cocopp bench window can go on past the first run's end.\n"
            f"endTime         {end_time + ENDTIME_MARGIN:.15g};\n")


def decompose_par_dict(cores):
    """system/decomposeParDict for `cores` MPI ranks: slices across the channel. OpenFOAM's
    `simple` method gives every slice the same number of cells (it sorts them by x), so the
    fine cells around the cylinder and the flag are shared out evenly; scotch is a stub in
    Debian's package."""
    return (header("dictionary", "decomposeParDict") +
            f"numberOfSubdomains {cores};\nmethod          simple;\n"
            f"simpleCoeffs\n{{\n    n               ({cores} 1 1);\n    delta           0.001;\n}}\n")


def fluid_files(test, level, dt, end_time, depth, pressure_rel_tol=0.0, cores=1,
                outer_correctors=1):
    # cfd3: the flag a fixed wall on a static mesh, for OpenFOAM's own pimpleFoam (no coupler).
    rigid = test == "cfd3"
    flag_velocity = ("{ type noSlip; }" if rigid
                     else "{ type movingWallVelocity; value uniform (0 0 0); }")
    write_every = max(1, round(0.1 / dt))
    files = {
        "system/blockMeshDict": make_mesh.block_mesh_dict(level, depth),
        "Allmesh": ALLMESH,
        "0/U": header("volVectorField", "U") +
        "dimensions      [0 1 -1 0 0 0 0];\ninternalField   uniform (0 0 0);\nboundaryField\n{\n"
        "    // The benchmark's parabolic inflow and its start-up ramp (constant/boundaryData).\n"
        "    inlet        { type timeVaryingMappedFixedValue; offset (0 0 0); setAverage off; }\n"
        "    outlet       { type zeroGradient; }\n"
        f"    flag         {flag_velocity}\n" + FIXED_WALLS +
        "}\n",
        "0/p": header("volScalarField", "p") +
        "// Kinematic pressure (p / rho), zero at the outlet.\n"
        "dimensions      [0 2 -2 0 0 0 0];\ninternalField   uniform 0;\nboundaryField\n{\n"
        "    inlet        { type zeroGradient; }\n"
        "    outlet       { type fixedValue; value uniform 0; }\n"
        "    flag         { type zeroGradient; }\n"
        "    walls        { type zeroGradient; }\n    cylinder     { type zeroGradient; }\n"
        "    frontAndBack { type empty; }\n}\n",
        "constant/transportProperties": header("dictionary", "transportProperties") +
        f"transportModel  Newtonian;\nnu              {NU_FLUID};\nrho             {RHO_FLUID};\n",
        "constant/turbulenceProperties": header("dictionary", "turbulenceProperties") +
        "simulationType  laminar;\n",
        "system/controlDict": header("dictionary", "controlDict") +
        f"application     {'pimpleFoam' if rigid else 'cocoppPimpleFoam'};\n"
        "startFrom       startTime;\nstartTime       0;\n"
        "stopAt          endTime;\n" + end_time_entry(rigid, end_time) +
        f"deltaT          {dt:.15g};\n"
        f"writeControl    timeStep;\nwriteInterval   {write_every};\npurgeWrite      0;\n"
        "writeFormat     binary;\nwritePrecision  12;\nwriteCompression off;\n"
        "timeFormat      general;\ntimePrecision   8;\nrunTimeModifiable false;\n\n"
        "functions\n{\n"
        "    // Drag and lift of cylinder and flag together (postProcessing/forces/0/force.dat),\n"
        f"    // per {depth} m of depth: post.py divides by it.\n"
        "    forces\n    {\n        type            forces;\n"
        "        libs            (\"libforces.so\");\n        writeControl    timeStep;\n"
        "        writeInterval   1;\n        patches         (cylinder flag);\n"
        f"        rho             rhoInf;\n        rhoInf          {RHO_FLUID};\n"
        "        CofR            (0 0 0);\n    }\n}\n",
        "system/fvSchemes": header("dictionary", "fvSchemes") +
        "// Second order in time (backward) and space.\n"
        "ddtSchemes      { default backward; }\ngradSchemes     { default Gauss linear; }\n"
        "divSchemes\n{\n    default         none;\n    div(phi,U)      Gauss linearUpwind grad(U);\n"
        "    div((nuEff*dev2(T(grad(U))))) Gauss linear;\n}\n"
        "laplacianSchemes { default Gauss linear corrected; }\n"
        "interpolationSchemes { default linear; }\nsnGradSchemes   { default corrected; }\n",
        "system/fvSolution": header("dictionary", "fvSolution") +
        "solvers\n{\n"
        "    // The last pressure corrector to 1e-10; the ones before it (and their\n"
        "    // non-orthogonal correctors) to relTol of their initial residual (make_case.py\n"
        "    // --pressure-rel-tol).\n"
        "    \"(p|pcorr)\"\n    {\n        solver          PCG;\n"
        "        preconditioner  DIC;\n        tolerance       1e-10;\n"
        f"        relTol          {pressure_rel_tol:g};\n    }}\n"
        "    \"(pFinal|pcorrFinal)\"\n    {\n        solver          PCG;\n"
        "        preconditioner  DIC;\n        tolerance       1e-10;\n        relTol          0;\n"
        "    }\n    \"(U|UFinal)\"\n    {\n        solver          smoothSolver;\n"
        "        smoother        symGaussSeidel;\n        tolerance       1e-10;\n"
        "        relTol          0;\n    }\n    \"(cellDisplacement|cellDisplacementFinal)\"\n    {\n"
        "        solver          PCG;\n        preconditioner  DIC;\n        tolerance       1e-12;\n"
        "        relTol          0;\n    }\n}\n\n"
        "// Within each coupling iteration: outer correctors (1: PISO, whose pressure-velocity\n"
        "// splitting is first order in time; make_case.py --outer-correctors), three pressure\n"
        "// correctors each.\n"
        f"PIMPLE\n{{\n    nOuterCorrectors {outer_correctors};\n    nCorrectors     3;\n"
        "    nNonOrthogonalCorrectors 1;\n    correctPhi      yes;\n}\n",
    }
    files.update(inlet_boundary_data(MEAN_INFLOW[test], depth))
    if cores > 1:
        files["system/decomposeParDict"] = decompose_par_dict(cores)
    files.update({"Allrun": ALLRUN_RIGID} if rigid else MESH_MOTION_FILES)
    return files


ALLRUN_RIGID = """\
#!/bin/sh
# The fluid alone, the flag rigid (make_case.py cfd3): the mesh, then OpenFOAM's pimpleFoam.
cd "$(dirname "$0")" || exit 1
./Allmesh || exit 1
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
pimpleFoam > log.pimpleFoam 2>&1 || { echo "Allrun: pimpleFoam failed, see $PWD/log.pimpleFoam" >&2; exit 1; }
"""


def case_file(test, level, dt, steps, q, tolerance, depth, command, cores=1, fluid_substeps=1):
    """The coupled case (case.yaml): IQN-ILS with reuse, the fluid in OpenFOAM and the flag in
    CalculiX behind a mapped wrapper."""
    fluid = {"type": case.commented("openfoam",
                                    "F: the flag's displacement -> the flow's loads on it"),
             "name": "fluid", "working_directory": "fluid", "boundary_names": ["flag"],
             "timeout": 600}
    if cores > 1:
        fluid["cores"] = case.commented(cores, "MPI ranks (system/decomposeParDict)")
    if fluid_substeps > 1:
        fluid["substeps"] = case.commented(
            fluid_substeps, "the fluid's steps per coupling step (controlDict's deltaT)")
    flag = {
        "type": case.commented("mapped", "S: the loads -> the flag's displacement"),
        "name": "flag",
        "solver_wrapper": {
            "type": case.commented("calculix", "persistent (cocopp-ccx) where built"),
            "working_directory": "flag", "input_file": "flag.inp",
            "interface_surface": case.commented("WET", "the three sides in the flow"),
            "interface_node_set": "WETN"},
        "input_mapper": case.commented({"type": "linear", "directions": ["x", "y"]},
                                       "fluid face centres -> the flag's faces, along its outline"),
        "output_mapper": case.commented(
            {"type": "linear", "transformers": [case.flow(
                {"type": "depth_2d_to_3d", "direction_depth": "z", "coordinates": [0, depth]})]},
            "the flag's nodes -> the fluid's flag points: the nodes\n"
            "copied to both planes of the one-cell-thick mesh, then\n"
            "interpolated on that ribbon")}
    coupled_solver = {
        "type": "iqni",
        "omega": case.commented(0.05, "relaxation of the first step's first update"),
        "model": {
            "type": case.commented("ls", "IQN-ILS ..."),
            "q": case.commented(q, "... reusing the secant information of earlier steps"),
            "min_significant": case.commented(1.0e-12, "filter of nearly dependent secant columns: "
                                                       "relative 1e-3,"),
            "min_significant_relative": case.commented(1.0e-3, "else FSI3's reused columns "
                                                               "overshoot (docs)")},
        "predictor": {"type": "linear"},
        **({"time_interpolation": case.commented(
            "quadratic", "the flag's displacement at the fluid's substeps (docs/coupling.md)")}
           if fluid_substeps > 1 else {}),
        "convergence_criterion": {"type": "or", "criteria": [
            {"type": case.commented("absolute_norm",
                                    f"the flag's displacement to {tolerance} m (2-norm)"),
             "tolerance": tolerance},
            {"type": "iteration_limit", "maximum": 30}]}}
    settings = {"delta_t": dt, "number_of_timesteps": steps,
                "state_interval": case.commented(max(1, round(0.5 / dt)),
                                                 "a state to restart from (cocopp run --restart)")}
    header = (f"Turek-Hron {test.upper()} (docs/validation-turek-hron.md), written by "
              "make_case.py:\n"
              f"  {command}\n"
              f"fluid/: the channel in OpenFOAM (level {level}, {make_mesh.cell_count(level)} "
              "cells); flag/: the flag in CalculiX.")
    return case.dump({"settings": settings, "coupled_solver": coupled_solver,
                      "solver_wrappers": [fluid, flag]}, header)


def write_made(args, dt, end_time):
    """turek_hron.json: what the case was made with, for post.py."""
    (args.output / "turek_hron.json").write_text(json.dumps(
        {"test": args.test, "level": args.level, "dt": dt, "end_time": end_time,
         "depth": args.depth, "q": args.q, "tolerance": args.tolerance,
         "alpha": args.alpha, "pressure_rel_tol": args.pressure_rel_tol,
         "outer_correctors": args.outer_correctors,
         "cores": args.cores, "fluid_substeps": args.fluid_substeps}, indent=1) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("test", choices=sorted(MEAN_INFLOW))
    parser.add_argument("output", type=pathlib.Path)
    parser.add_argument("--level", type=int, default=1, help="fluid mesh level (make_mesh.py)")
    parser.add_argument("--dt", type=float, help="time step, s (default: per test)")
    parser.add_argument("--end-time", type=float, help="simulated time, s (default: per test)")
    parser.add_argument("--q", type=int, default=10, help="earlier steps IQN-ILS reuses")
    parser.add_argument("--tolerance", type=float, default=1.0e-7,
                        help="the coupling's absolute tolerance on the displacement, m")
    parser.add_argument("--depth", type=float, default=0.01, help="the fluid mesh's depth, m")
    parser.add_argument("--alpha", type=float, default=-0.1,
                        help="the flag's HHT alpha (ccx *DYNAMIC, ALPHA=): numerical damping")
    parser.add_argument("--pressure-rel-tol", type=float, default=0.0,
                        help="relative tolerance of the pressure correctors before the last "
                             "(0: every one to 1e-10)")
    parser.add_argument("--outer-correctors", type=int, default=1,
                        help="PIMPLE's nOuterCorrectors (1: PISO; 2 takes out PISO's splitting "
                             "error, docs/validation-turek-hron.md, CFD3)")
    parser.add_argument("--cores", type=int, default=1,
                        help="MPI ranks of the fluid (the coupled tests; decomposeParDict)")
    parser.add_argument("--fluid-substeps", type=int, default=1,
                        help="the fluid's own steps per coupling time step (--dt): the fluid at "
                             "dt / K, the flag at dt (docs/coupling.md, substeps)")
    args = parser.parse_args()
    dt = args.dt or DEFAULT_DT[args.test]
    end_time = args.end_time or DEFAULT_END[args.test]
    steps = round(end_time / dt)
    command = "make_case.py " + " ".join(sys.argv[1:])
    openfoam.write_case(args.output / "fluid",
                        fluid_files(args.test, args.level, dt / args.fluid_substeps, end_time,
                                    args.depth, args.pressure_rel_tol, args.cores,
                                    args.outer_correctors))
    if args.test == "cfd3":
        write_made(args, dt, end_time)
        print(f"make_case.py: {args.output}: cfd3 (the fluid alone, fluid/Allrun), level "
              f"{args.level}, {make_mesh.cell_count(args.level)} cells, dt {dt}, {steps} steps")
        return
    (args.output / "flag").mkdir(parents=True, exist_ok=True)
    (args.output / "flag/flag.inp").write_text(
        turek_hron.flag_deck(args.test, 20 * args.level, 2 * args.level, dt, args.alpha))
    (args.output / "case.yaml").write_text(
        case_file(args.test, args.level, dt, steps, args.q, args.tolerance, args.depth,
                  command, args.cores, args.fluid_substeps))
    write_made(args, dt, end_time)
    print(f"make_case.py: {args.output}: {args.test}, level {args.level}, "
          f"{make_mesh.cell_count(args.level)} cells, dt {dt}, {steps} steps")


if __name__ == "__main__":
    main()
