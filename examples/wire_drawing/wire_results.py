"""A wire drawing run's results, for plot.py, checks.py and the probes of the wire: the film side
from the coupler's results file (results/case.h5, a cocopp.results.ResultsFile) and the wire
from CalculiX's .frd files (cocopp.calculix.Frd; the calculix wrapper keeps one per time step in
structure/results/step_NNNNN.frd).

ccx writes an axisymmetric model's results on the 2D nodes: x is the radius, y the axis and z
the hoop direction; stresses are extrapolated from the integration points to the nodes.
"""
import pathlib
import shutil
import subprocess

import numpy as np
import yaml

import make_case
from cocopp.calculix import ccx_environment, dat_block, deck_elements


def integration_point_check(dat_path, wire):
    """Equivalent stress over hardened yield stress at the integration points of the *EL PRINT
    of S and PEEQ (make_case.py prints the outer column of elements, SKIN): the largest ratio
    and the largest plastic strain, or None if the .dat file has no such print."""
    stresses = dat_block(dat_path, "stresses")
    strains = dat_block(dat_path, "equivalent plastic strain")
    if not stresses or not strains:
        return None
    stress = np.array([row[2:8] for row in stresses])
    peeq = np.array([row[2] for row in strains])
    ratio = von_mises(stress) / swift_yield_stress(wire, peeq)
    return float(np.max(ratio)), float(np.max(peeq))


def von_mises(stress):
    """Equivalent stress of rows (sxx, syy, szz, sxy, syz, szx)."""
    sxx, syy, szz, sxy, syz, szx = stress.T
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
                   + 3.0 * (sxy ** 2 + syz ** 2 + szx ** 2))


def swift_yield_stress(wire, plastic_strain):
    """The hardened yield stress of make_case.hardening_table's law."""
    sigma0, n, e0 = wire["yield_stress"], wire["hardening"], wire["hardening_reference_strain"]
    return sigma0 * (1.0 + np.asarray(plastic_strain) / e0) ** n


def surface(frd, wire, time):
    """Along the wire's surface (reference radius = wire radius), sorted by the axial position
    at `time` in the die's frame (the wire's frame moves with its exit end at the drawing
    speed): z, radial displacement, equivalent stress, yield stress and plastic strain."""
    radius = wire["radius"]
    on_surface = np.abs(frd.coordinates[:, 0] - radius) < 1e-9 * max(radius, 1.0)
    u = frd.values("DISP")[on_surface]
    z = frd.coordinates[on_surface, 1] + u[:, 1] + wire["drawing_speed"] * time
    stress = von_mises(frd.values("STRESS")[on_surface])
    peeq = frd.values("PE")[on_surface, 0]
    order = np.argsort(z)
    return {"z": z[order], "u_r": u[order, 0], "von_mises": stress[order],
            "yield_stress": swift_yield_stress(wire, peeq)[order], "peeq": peeq[order]}


def sector_angle(frd):
    """The opening of a sector model of the wire in radians (its nodes turn from the x-y plane
    towards -z, make_case.sector_wire_deck), 0 for the axisymmetric model."""
    return float(np.max(np.arctan2(-frd.coordinates[:, 2], frd.coordinates[:, 0])))


def exit_force(frd, wire):
    """The axial reaction force at the exit end, the drawing force (ccx gives an axisymmetric
    model's reaction forces for the whole circumference; a sector's are scaled to it)."""
    end = wire["start"] + wire["length"]
    at_exit = np.abs(frd.coordinates[:, 1] - end) < 1e-9
    angle = sector_angle(frd)
    ring = 2 * np.pi / angle if angle > 1e-9 else 1.0
    return ring * float(np.sum(frd.values("FORC")[at_exit, 1]))


def step_files(case):
    """The .frd files of a run, by time step."""
    folder = pathlib.Path(case) / "structure" / "results"
    return {int(p.stem.split("_")[1]): p for p in sorted(folder.glob("step_*.frd"))}


def die_displacement(schedule, t):
    times, values = zip(*schedule)
    return float(np.interp(t, times, values))


def film_profile(results, film, schedule, row):
    """(z, film thickness, wire radial displacement) along the film's wall points at `row`."""
    points = results.coordinates("x", "wire_points")
    u = results.values("x", "wire_points", "displacement", row)
    radius = np.hypot(points[:, 0], points[:, 1])
    radial = (points[:, 0] * u[:, 0] + points[:, 1] * u[:, 1]) / radius
    z = points[:, 2]
    t = results.times[row]
    die = np.array([film.die_radius(zi) for zi in z]) + die_displacement(schedule, t)
    thickness = die - (film.radius + radial)
    order = np.argsort(z)
    # Each axial position has a point on both wedge planes: one is enough.
    keep = order[::2]
    return z[keep], thickness[keep], radial[keep]


def loads_profile(results, row):
    centres = results.coordinates("y", "wire_faces")
    order = np.argsort(centres[:, 2])
    pressure = results.values("y", "wire_faces", "pressure", row)[:, 0]
    shear = results.values("y", "wire_faces", "traction", row)[:, 2]
    return centres[order, 2], pressure[order], shear[order]


def face_lengths(z):
    """Lengths of faces with centres z along the axis that tile a line (equal neighbours)."""
    order = np.argsort(z)
    middles = 0.5 * (z[order][1:] + z[order][:-1])
    bounds = np.concatenate([[2 * z[order][0] - middles[0]], middles,
                             [2 * z[order][-1] - middles[-1]]])
    lengths = np.empty_like(z)
    lengths[order] = np.diff(bounds)
    return lengths


def film_forces(results, film, schedule, row):
    """The film's load on the wire at `row`, over the whole circumference: (axial force of the
    shear, axial force of the pressure on the sloped wire surface, integral of the pressure, its
    radial part (inwards), integral of the shear magnitude). The wire surface's slope comes from its
    radial displacement at the film's wall points."""
    z, pressure, shear = loads_profile(results, row)
    wall_z, _, radial = film_profile(results, film, schedule, row)
    r = film.radius + np.interp(z, wall_z, radial)
    slope = np.interp(z, wall_z, np.gradient(film.radius + radial, wall_z))
    area = 2 * np.pi * r * face_lengths(z)  # projected on the axis
    return {"shear_axial": float(np.sum(shear * area)),
            "pressure_axial": float(np.sum(pressure * slope * area)),
            "pressure_total": float(np.sum(pressure * area * np.sqrt(1 + slope ** 2))),
            "pressure_radial": float(np.sum(pressure * area)),
            "shear_total": float(np.sum(np.abs(shear) * area))}


def film_exact_forces(results, film, row):
    """The film's own force on the wire at `row`, whole ring, as the film sums it on its moved
    faces (pressure and shear on each face's area: its `force` output, what OpenFOAM's `forces`
    function object sums): {"axial", "radial" (outwards)}, or None for a run whose film did not
    output it. The film's coordinates: x across its wedge, y radial, z along the axis."""
    if "force" not in results.variables("y", "wire_faces"):
        return None
    force = results.values("y", "wire_faces", "force", row)
    ring = 2 * np.pi / (2 * film.half_wedge)
    return {"axial": float(ring * np.sum(force[:, 2])),
            "radial": float(ring * np.sum(force[:, 1]))}


def made_with(case, parameters, changes=()):
    """The parameters a case was made from and whether it was refined: make_case.py's
    made_with.yaml in the case, else the parameter file with `changes` (as --set)."""
    record = pathlib.Path(case) / "made_with.yaml"
    if record.exists():
        data = yaml.safe_load(record.read_text())
        return data["parameters"], data["refine"]
    return make_case.load_parameters(parameters, list(changes)), False


def restart_ccx(structure, work, ccx):
    """Run ccx on work/cocopp_iteration.inp (written by the caller) restarted from the run's last
    converged step, as the calculix wrapper does (structure/cocopp_converged.rout, with the
    model deck it includes); the log goes to work/ccx.log. Returns ccx's exit status."""
    if (structure / "cocopp_model.inp").exists():
        shutil.copy(structure / "cocopp_model.inp", work / "cocopp_model.inp")
    shutil.copy(structure / "cocopp_converged.rout", work / "cocopp_iteration.rin")
    with open(work / "ccx.log", "w") as log:
        return subprocess.run([ccx, "-i", "cocopp_iteration"], cwd=work, stdout=log,
                              stderr=subprocess.STDOUT, env=ccx_environment(2)).returncode


def applied_loads(loads_file):
    """The interface loads of a coupling iteration as the calculix wrapper wrote them:
    {element: pressure} of the *DLOAD P2 lines and the summed *CLOAD per direction (a
    sector's in its nodes' cylindrical axes: 1 radial, 2 hoop, 3 axial)."""
    pressures, forces, mode = {}, {1: 0.0, 2: 0.0, 3: 0.0}, None
    with open(loads_file) as f:
        for line in f:
            if line.startswith("*"):
                mode = line[1:6].upper()
                continue
            fields = [v.strip() for v in line.split(",")]
            if mode == "DLOAD" and len(fields) == 3:
                pressures[int(fields[0])] = float(fields[2])
            elif mode == "CLOAD" and len(fields) == 3:
                forces[int(fields[1])] += float(fields[2])
    return pressures, forces


def sector_wire_forces(case, frd):
    """The film's load as ccx took it on a sector wire in the last coupling iteration: the
    axial sum of the *CLOAD (shear and the pressure's axial part; a wire driven by displacement
    takes no force in its driven direction) and the radial sum of the *CLOAD and of the reaction
    forces at the driven nodes (the film's pressure carried by the drive), whole ring."""
    structure = pathlib.Path(case) / "structure"
    _, forces = applied_loads(structure / "cocopp_loads.inp")
    ring = 2 * np.pi / sector_angle(frd)
    driven = driven_nodes(structure / "cocopp_loads.inp")
    rows = np.isin(frd.ids, list(driven))
    xyz = frd.coordinates[rows]
    radial_axis = xyz[:, [0, 2]] / np.linalg.norm(xyz[:, [0, 2]], axis=1)[:, None]
    reaction = np.sum(frd.values("FORC")[rows][:, [0, 2]] * radial_axis)
    return {"axial": ring * forces[3], "radial": ring * (forces[1] + reaction)}


def driven_nodes(loads_file):
    """The nodes a wire driven by displacement had prescribed (the loads file's *BOUNDARY,
    OP=NEW block before the deck's own boundaries)."""
    nodes, inside = set(), False
    with open(loads_file) as f:
        for line in f:
            if line.startswith("*"):
                inside = line.upper().startswith("*BOUNDARY, OP=NEW")
                continue
            if inside:
                nodes.add(int(line.split(",")[0]))
    return nodes


def wire_forces(case, frd):
    """The film's load as ccx applied it in the last coupling iteration of a run (the loads file
    holds that one; `frd` must be the same step): the axial force of the pressure on the wire's
    deformed surface, pi p (r_b^2 - r_a^2) per S2 edge from corner a to corner b (exact for a
    uniform pressure on a quadratic edge of revolution), the axial and radial sums of the
    *CLOAD (the shear, whole ring), and the integral of the pressure over the moved faces."""
    structure = pathlib.Path(case) / "structure"
    pressures, forces = applied_loads(structure / "cocopp_loads.inp")
    elements = deck_elements((structure / "wire.inp").read_text())
    moved = dict(zip(frd.ids, frd.coordinates[:, :2] + frd.values("DISP")[:, :2]))  # (r, z)
    axial, total = 0.0, 0.0
    for element, p in pressures.items():
        a, b = moved[elements[element][1]], moved[elements[element][2]]  # edge S2: corners 2, 3
        axial += p * np.pi * (b[0] ** 2 - a[0] ** 2)
        total += p * np.pi * (a[0] + b[0]) * np.hypot(*(b - a))  # ring of the moved edge
    return {"pressure_axial": axial, "shear_axial": forces[2], "shear_radial": forces[1],
            "pressure_total": total}
