#!/usr/bin/python3
"""Write the wire drawing case (docs/wire-drawing.md) from parameters.yaml.

    make_case.py [--parameters parameters.yaml] [--output DIR] [--refine] [--set KEY=VALUE ...]

Writes DIR/fluid, the lubricant film as an OpenFOAM case (an axisymmetric wedge between the
wire's surface and the die: an entry cone and a bearing; blockMesh makes its mesh), and
DIR/structure/wire.inp, the wire as an axisymmetric CalculiX deck (CAX8, elastoplastic with
Swift hardening, NLGEOM, quasi-static: pulled at the drawing speed at its exit end, the back
force on its entry end). --refine doubles the cells and elements in each direction; --set
changes one parameter, e.g. --set die.reduction=0 (the die held for the whole run) or
--set lubricant.viscosity=122.5. With --set coupling.type=iqnism it also writes DIR/surrogate,
the same film and wire on the coarser meshes of the `surrogate` parameters (IQN-ILSM);
--set coupling.type=ibqn couples by IBQN, with a model of each solver's Jacobian.
"""
import argparse
import copy
import math
import pathlib
import sys

import yaml

import surface_compliance
from cocopp import calculix, case, openfoam
from cocopp.executable import patched_ccx
from cocopp.openfoam import header

HERE = pathlib.Path(__file__).resolve().parent
TEXT_PARAMETERS = {"wire_element", "wire_model", "model", "type", "drive", "film_motion",
                   "solver", "film_stiffness"}  # others: numbers


def load_parameters(path, changes):
    parameters = yaml.safe_load(pathlib.Path(path).read_text())
    for section, values in parameters.items():
        for name, value in values.items():
            # YAML 1.1 reads 1.5e9 (no sign in the exponent) as text: say so, not crash later.
            if not isinstance(value, (int, float)) and name not in TEXT_PARAMETERS:
                sys.exit(f"make_case.py: {path}: {section}.{name}: '{value}' is not a number "
                         f"(write exponents with a sign: 1.5e+9)")
    for change in changes:
        key, _, value = change.partition("=")
        section, _, name = key.partition(".")
        if section not in parameters or name not in parameters[section]:
            sys.exit(f"make_case.py: --set {change}: no parameter '{key}' in {path}")
        default = parameters[section][name]
        new = yaml.safe_load(value)
        # A whole-number parameter (a count) must not take 0.05 silently as 0.
        if isinstance(default, int) and not (isinstance(new, int) or float(new).is_integer()):
            sys.exit(f"make_case.py: --set {change}: {key} is a whole number")
        parameters[section][name] = type(default)(new)
    return parameters


class Film:
    """The film's geometry: z along the axis (drawing direction), r from the axis."""

    def __init__(self, p, refine):
        wire, die, mesh = p["wire"], p["die"], p["mesh"]
        self.radius = wire["radius"]
        self.entry = die["entry_length"]
        self.bearing = die["bearing_length"]
        self.gap = die["film_thickness"]
        self.slope = math.tan(math.radians(die["half_angle_degrees"]))
        self.transition = die.get("transition_length", 0.0)  # cases made before it: sharp
        self.half_wedge = math.radians(mesh["wedge_degrees"] / 2)
        factor = 2 if refine else 1
        axial = factor * mesh["film_axial_cells"]
        self.entry_cells = round(axial * self.entry / (self.entry + self.bearing))
        self.bearing_cells = axial - self.entry_cells
        self.radial_cells = factor * mesh["film_radial_cells"]

    def die_radius(self, z):
        """The die's radius at axial position z (0: film inlet), before it moves. With a
        transition length L the cone meets the bearing through a parabola over the bearing's
        first L, tangent to both (the cone raised by slope L / 2 to meet it)."""
        bearing = self.radius + self.gap
        if z <= self.entry:
            return bearing + self.slope * (self.entry - z + self.transition / 2)
        into = z - self.entry
        if into < self.transition:
            return bearing + self.slope * (self.transition - into) ** 2 / (2 * self.transition)
        return bearing

    @property
    def length(self):
        return self.entry + self.bearing


def wedge_point(r, z, side, film):
    s, c = math.sin(film.half_wedge), math.cos(film.half_wedge)
    return f"({side * r * s:.17g} {r * c:.17g} {z:.17g})"


def block_mesh_dict(film):
    # Vertices per axial station z (inlet, end of the cone, outlet): wire front, die front,
    # die back, wire back; blocks are hex (wire-front die-front die-back wire-back) x (z0 z1).
    stations = [0.0, film.entry, film.length]
    vertices = []
    for z in stations:
        r_die = film.die_radius(z)
        vertices += [wedge_point(film.radius, z, 1, film), wedge_point(r_die, z, 1, film),
                     wedge_point(r_die, z, -1, film), wedge_point(film.radius, z, -1, film)]

    def hex_block(k, cells):
        a, b = 4 * k, 4 * (k + 1)
        ids = " ".join(str(i) for i in [a, a + 1, a + 2, a + 3, b, b + 1, b + 2, b + 3])
        return f"    hex ({ids}) ({film.radial_cells} 1 {cells}) simpleGrading (1 1 1)"

    def faces(pattern):
        return " ".join("(" + " ".join(str(4 * k + i) for i in pattern(k)) + ")" for k in (0, 1))

    # The rounded transition: the die's two edges of the bearing block follow the parabola.
    edges = ""
    if film.transition > 0:
        samples = [film.entry + film.transition * i / 40 for i in range(1, 40)]
        for side, (a, b) in ((1, (5, 9)), (-1, (6, 10))):
            points = " ".join(wedge_point(film.die_radius(z), z, side, film) for z in samples)
            edges += f"    polyLine {a} {b} ({points})\n"
    wire = faces(lambda k: [0, 4, 7, 3])
    die = faces(lambda k: [1, 2, 6, 5])
    front = faces(lambda k: [0, 1, 5, 4])
    back = faces(lambda k: [3, 7, 6, 2])
    return (header("dictionary", "blockMeshDict") +
            "// The lubricant film (make_case.py): wire surface `wire` at r = R, die `die` with an\n"
            "// entry cone and a bearing, axisymmetric wedge about the z axis.\nscale 1;\n\n"
            "vertices\n(\n" + "\n".join("    " + v for v in vertices) + "\n);\n\n"
            "blocks\n(\n" + hex_block(0, film.entry_cells) + "\n" +
            hex_block(1, film.bearing_cells) + "\n);\n\nedges\n(\n" + edges + ");\n\nboundary\n(\n"
            f"    wire   {{ type wall;  faces ({wire}); }}\n"
            f"    die    {{ type wall;  faces ({die}); }}\n"
            "    inlet  { type patch; faces ((0 1 2 3)); }\n"
            "    outlet { type patch; faces ((8 9 10 11)); }\n"
            f"    front  {{ type wedge; faces ({front}); }}\n"
            f"    back   {{ type wedge; faces ({back}); }}\n);\n")


def static_card(p):
    """*STATIC with the sparse direct solver calculix.solver names (spooles: ccx's default;
    suitesparse: CHOLMOD, cocopp's ccx patch 06, the same answers to round-off)."""
    solver = p["calculix"].get("solver", "spooles")
    if solver not in ("spooles", "suitesparse"):
        sys.exit(f"make_case.py: calculix.solver: '{solver}' is not spooles or suitesparse")
    return "*STATIC" if solver == "spooles" else "*STATIC, SOLVER=SUITESPARSE"


def die_schedule(p):
    """(time, radial displacement) of the die: held, then closing at a constant rate until the
    wire's cross section is reduced by `reduction`: the bearing at the reduced radius plus the
    film it keeps there (`bearing_film`), from the initial gap `film_thickness`; then held
    there for `time.steady_steps` more steps (steady drawing)."""
    radius, time, die = p["wire"]["radius"], p["time"], p["die"]
    closing = (radius * (1.0 - math.sqrt(1.0 - die["reduction"]))
               + die["film_thickness"] - die.get("bearing_film", die["film_thickness"]))
    held = time["held_steps"] * time["delta_t"]
    end = time["steps"] * time["delta_t"]
    if held >= end:
        return [(0.0, 0.0), (end, 0.0)]
    held_points = [(held, 0.0)] if held > 0 else []  # a table's times must increase
    steady = [(end + steady_steps(p) * time["delta_t"], -closing)] if steady_steps(p) else []
    return [(0.0, 0.0)] + held_points + [(end, -closing)] + steady


def steady_steps(p):
    """The steps after the die has closed, with the die held at its final diameter."""
    steps = p["time"].get("steady_steps", 0)
    if not isinstance(steps, int) or steps < 0:
        sys.exit(f"make_case.py: time.steady_steps: '{steps}' is not a whole number >= 0")
    return steps


def total_steps(p):
    """The time steps of the run: the die held, closing, then held closed."""
    return p["time"]["steps"] + steady_steps(p)


# The film's zones for its layered motion: the cells, and the wire and die walls as face zones.
TOPO_SET_DICT = header("dictionary", "topoSetDict") + """\
actions
(
    { name filmCells; type cellSet; action new; source boxToCell; box (-1 -1 -1) (1 1 1); }
    { name film; type cellZoneSet; action new; source setToCellZone; set filmCells; }
    { name wireFaces; type faceSet; action new; source patchToFace; patch wire; }
    { name wireZone; type faceZoneSet; action new; source setToFaceZone; faceSet wireFaces; }
    { name dieFaces; type faceSet; action new; source patchToFace; patch die; }
    { name dieZone; type faceZoneSet; action new; source setToFaceZone; faceSet dieFaces; }
);
"""

# The film's mesh, made in its own directory as an OpenFOAM case is: ./Allmesh.
ALLMESH = """\
#!/bin/sh
# Meshes the film (make_case.py): blockMesh, then the zones of its layered motion (topoSet).
cd "$(dirname "$0")" || exit 1
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
blockMesh > log.blockMesh 2>&1 || { echo "Allmesh: blockMesh failed, see $PWD/log.blockMesh" >&2; exit 1; }
topoSet > log.topoSet 2>&1 || { echo "Allmesh: topoSet failed, see $PWD/log.topoSet" >&2; exit 1; }
"""


def dynamic_mesh_dict(motion):
    """The film's mesh motion. layered: each point keeps its fraction of the gap between wire
    and die, walked along its column of edges in the initial mesh (the film is thin and moves
    only radially); laplacian: displacementLaplacian, whose layers grow uneven at the outlet
    once the die has closed (docs/wire-drawing.md)."""
    text = (header("dictionary", "dynamicMeshDict") + "dynamicFvMesh   dynamicMotionSolverFvMesh;\n"
            "motionSolverLibs (\"libfvMotionSolvers.so\");\n")
    if motion == "laplacian":
        return (text + "solver          displacementLaplacian;\n"
                "displacementLaplacianCoeffs\n{\n    diffusivity     uniform;\n}\n")
    if motion != "layered":
        sys.exit(f"make_case.py: mesh.film_motion: '{motion}' is not layered or laplacian")
    return (text + "// Each film point keeps its fraction of the wire-die gap (system/topoSetDict makes\n"
            "// the zones).\nsolver          displacementLayeredMotion;\n"
            "displacementLayeredMotionCoeffs\n{\n    regions\n    {\n        film\n        {\n"
            "            interpolationScheme linear;\n            boundaryField\n            {\n"
            "                wireZone { type follow; }\n                dieZone  { type follow; }\n"
            "            }\n        }\n    }\n}\n")


def fluid_files(p, film):
    lubricant, time = p["lubricant"], p["time"]
    speed = p["wire"]["drawing_speed"]
    table = " ".join(f"({t:.17g} {d:.17g})" for t, d in die_schedule(p))
    end_time = total_steps(p) * time["delta_t"]
    walls = "    front        { type wedge; }\n    back         { type wedge; }\n"
    return {
        "system/blockMeshDict": block_mesh_dict(film),
        "0/U": header("volVectorField", "U") +
        "dimensions      [0 1 -1 0 0 0 0];\ninternalField   uniform (0 0 0);\nboundaryField\n{\n"
        "    // The wire's surface slides along the fixed film grid at the drawing speed; its\n"
        "    // radial motion (the coupler's displacement) comes from the mesh.\n"
        f"    wire         {{ type cocoppSlidingWallVelocity; wallVelocity constant (0 0 {speed:.17g});"
        " value uniform (0 0 0); }\n"
        "    die          { type movingWallVelocity; value uniform (0 0 0); }\n"
        "    inlet        { type pressureInletOutletVelocity; value uniform (0 0 0); }\n"
        "    outlet       { type pressureInletOutletVelocity; value uniform (0 0 0); }\n" + walls +
        "}\n",
        "0/p": header("volScalarField", "p") +
        "// Kinematic pressure (p / rho); ambient (0) at both ends of the film.\n"
        "dimensions      [0 2 -2 0 0 0 0];\ninternalField   uniform 0;\nboundaryField\n{\n"
        "    wire         { type zeroGradient; }\n    die          { type zeroGradient; }\n"
        "    inlet        { type fixedValue; value uniform 0; }\n"
        "    outlet       { type fixedValue; value uniform 0; }\n" + walls + "}\n",
        "0/pointDisplacement": header("pointVectorField", "pointDisplacement") +
        "// wire: the coupler's (radial) displacement; die: held, then closing radially.\n"
        "dimensions      [0 1 0 0 0 0 0];\ninternalField   uniform (0 0 0);\nboundaryField\n{\n"
        "    wire         { type fixedValue; value uniform (0 0 0); }\n"
        "    die\n    {\n        type               cocoppRadialDisplacement;\n"
        "        origin             (0 0 0);\n        axis               (0 0 1);\n"
        f"        radialDisplacement table ({table});\n"
        "        value              uniform (0 0 0);\n    }\n"
        "    inlet        { type slip; }\n    outlet       { type slip; }\n" + walls + "}\n",
        "constant/dynamicMeshDict": dynamic_mesh_dict(p["mesh"]["film_motion"]),
        "system/topoSetDict": TOPO_SET_DICT,
        "Allmesh": ALLMESH,
        "constant/transportProperties": header("dictionary", "transportProperties") +
        "transportModel  Newtonian;\n"
        f"nu              {lubricant['viscosity'] / lubricant['density']:.17g};\n"
        f"rho             {lubricant['density']:.17g};\n",
        "constant/turbulenceProperties": header("dictionary", "turbulenceProperties") +
        "simulationType  laminar;\n",
        "system/controlDict": header("dictionary", "controlDict") +
        "application     cocoppPimpleFoam;\nstartFrom       startTime;\nstartTime       0;\n"
        f"stopAt          endTime;\nendTime         {end_time:.17g};\n"
        f"deltaT          {time['delta_t']:.17g};\nwriteControl    timeStep;\n"
        "writeInterval   1;\npurgeWrite      0;\nwriteFormat     ascii;\nwritePrecision  12;\n"
        "writeCompression off;\ntimeFormat      general;\ntimePrecision   6;\n"
        "runTimeModifiable false;\n",
        "system/fvSchemes": header("dictionary", "fvSchemes") +
        "// First order in time and central in space, as the paper (its Peclet number is far\n"
        "// below 1).\nddtSchemes      { default Euler; }\ngradSchemes     { default Gauss linear; }\n"
        "divSchemes\n{\n    default         none;\n    div(phi,U)      Gauss linear;\n"
        "    div((nuEff*dev2(T(grad(U))))) Gauss linear;\n}\n"
        "laplacianSchemes { default Gauss linear corrected; }\n"
        "interpolationSchemes { default linear; }\nsnGradSchemes   { default corrected; }\n",
        "system/fvSolution": header("dictionary", "fvSolution") +
        "solvers\n{\n    \"(p|pFinal|pcorr|pcorrFinal)\"\n    {\n        solver          PCG;\n"
        "        preconditioner  DIC;\n        tolerance       1e-12;\n        relTol          0;\n"
        "    }\n    \"(U|UFinal)\"\n    {\n        solver          smoothSolver;\n"
        "        smoother        symGaussSeidel;\n        tolerance       1e-14;\n"
        "        relTol          0;\n    }\n    cellDisplacement\n    {\n"
        "        solver          PCG;\n        preconditioner  DIC;\n        tolerance       1e-16;\n"
        "        relTol          0;\n    }\n}\n\n"
        "// The film is viscous (Re ~ 1e-5) and steady within a time step: the outer loop iterates\n"
        "// pressure and velocity to convergence, which needs the consistent (SIMPLEC) form and a\n"
        "// slightly relaxed momentum equation (plain PISO diverges on this film).\n"
        "PIMPLE\n{\n    nOuterCorrectors 100;\n    nCorrectors     2;\n"
        "    nNonOrthogonalCorrectors 1;\n    consistent      yes;\n    residualControl\n    {\n"
        "        \"(U|p)\" { tolerance 1e-7; relTol 0; }\n    }\n}\n\n"
        "relaxationFactors\n{\n    equations { U 0.9; UFinal 1; }\n}\n",
    }


def hardening_table(wire, points=40):
    """(yield stress, plastic strain) pairs of Swift's law sigma_y = sigma_0 (1 + e_p / e_0)^n,
    n the paper's hardening coefficient, up to a plastic strain of 1."""
    sigma0, n, e0 = wire["yield_stress"], wire["hardening"], wire["hardening_reference_strain"]
    strains = [0.0] + [10 ** (-4 + 4 * k / (points - 1)) for k in range(points)]
    return [(sigma0 * (1 + e / e0) ** n, e) for e in strains]


def quad8(node, i, k):
    """A CAX8 element with its lower corner at the doubled grid point (i, k): corners
    counter-clockwise in the (r, z) plane, then the mid-side nodes."""
    ids = [(i, k), (i + 2, k), (i + 2, k + 2), (i, k + 2),
           (i + 1, k), (i + 2, k + 1), (i + 1, k + 2), (i, k + 1)]
    return [node(a, b) for a, b in ids]


# C3D20 local nodes in the doubled grid (radial, hoop, axial offsets 0..2).
HEX20 = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2),
         (1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 1, 2),
         (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1)]
# C3D15 at the axis: the triangle (axis, outer edge at hoop 0, outer edge at hoop 2) at both
# axial ends, its mid-sides, then the axial mid-sides.
WEDGE15 = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (1, 0, 0), (2, 1, 0),
           (1, 2, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 0, 1), (2, 0, 1), (2, 2, 1)]


def sector_wire_deck(p, refine):
    """The wire as a thin 3D sector (mesh.sector_degrees) of the same grid as wire_deck's: C3D20R
    bricks, C3D15 wedges in the ring at the axis, all off-axis nodes in a cylindrical *TRANSFORM
    about the y axis (1 radial, 2 hoop, 3 axial) with the hoop displacement held: axisymmetric.
    One side of the sector lies in the x-y plane (x = radius, y = axis, as the CAX deck), the
    sector turns from it towards -z. Its reaction forces are the forces at the nodes, which a
    CAX model's are not (reaction_probe.py): what interface_drive: displacement needs.
    SURFACEN is the surface's nodes on the x-y side (the axisymmetric mapping's), SURFACEALL all
    of them (the driven ones). Bricks as mesh.wire_element: C3D20R for CAX8R, C3D20 for CAX8
    (full integration: driven uniformly around the hoop, C3D20R's surface is held against the
    hoop zigzag its solution has under a load, and comes out stiffer; leaving the mid-plane
    nodes free instead lets their zero-energy mode make ccx cut its increments back)."""
    wire, mesh = p["wire"], p["mesh"]
    factor = 2 if refine else 1
    radial, axial = factor * mesh["wire_radial_elements"], factor * mesh["wire_axial_elements"]
    if radial < 2:
        sys.exit("make_case.py: the sector wire needs mesh.wire_radial_elements >= 2 (its "
                 "surface faces are on bricks, the ring at the axis is of wedges)")
    radius, length, start = wire["radius"], wire["length"], wire["start"]
    angle = math.radians(mesh["sector_degrees"])
    ni, nk = 2 * radial + 1, 2 * axial + 1

    def node(i, j, k):
        return 1 + i + ni * ((0 if i == 0 else j) + 3 * k)  # one node per axis point

    def exists(i, j, k):
        return i % 2 + j % 2 + k % 2 <= 1 and not (i == 0 and j > 0)

    def position(i, j, k):
        r, theta = radius * i / (ni - 1), angle * j / 2
        return (node(i, j, k), r * math.cos(theta), start + length * k / (nk - 1),
                -r * math.sin(theta))

    deck = calculix.Deck(f"** The drawn wire (make_case.py): a {mesh['sector_degrees']:g} degree "
                         "sector of C3D20(R) (C3D15 at the axis), x = radius, y = axis, hoop "
                         "towards -z.")
    deck.nodes(position(i, j, k) for k in range(nk) for j in range(3) for i in range(ni)
               if exists(i, j, k))

    def element(m, q):
        return 1 + m + radial * q

    def connectivity(table, m, q):
        return element(m, q), [node(2 * m + a, b, 2 * q + c) for a, b, c in table]

    deck.elements("C3D15", (connectivity(WEDGE15, 0, q) for q in range(axial)))
    brick = {"CAX8R": "C3D20R", "CAX8": "C3D20"}[mesh["wire_element"]]
    # The outer layer, where the film's loads and the drive act, may be fully integrated: a
    # loaded node next to driven ones (the film's edge) then cannot take C3D20R's zero-energy
    # hoop mode, whose flow under a yielding skin makes ccx's Newton stall and cut back.
    skin = "C3D20" if mesh["full_integration_skin"] else brick
    cards = ([(brick, range(1, radial))] if skin == brick else
             [(brick, range(1, radial - 1)), (skin, [radial - 1])])
    for kind, layers in cards:
        deck.elements(kind, (connectivity(HEX20, m, q) for q in range(axial) for m in layers))
    deck.node_set("SURFACEN", [node(ni - 1, 0, k) for k in range(nk)])
    deck.node_set("SURFACEALL", [node(ni - 1, j, k) for k in range(nk) for j in range(3)
                                 if exists(ni - 1, j, k)])
    deck.node_set("AXIS", [node(0, 0, k) for k in range(nk)])
    deck.node_set("OFFAXIS", [node(i, j, k) for k in range(nk) for j in range(3)
                              for i in range(1, ni) if exists(i, j, k)])
    deck.node_set("EXIT", [node(i, j, nk - 1) for j in range(3) for i in range(1, ni)
                           if exists(i, j, nk - 1)])
    deck.node_set("EXITAXIS", [node(0, 0, nk - 1)])
    deck.surface("SURFACE", [(element(radial - 1, q), "S4") for q in range(axial)])  # r = R: xi = 1
    deck.element_set("SKIN", [element(radial - 1, q) for q in range(axial)])
    deck.element_set("ENTRY", [element(m, 0) for m in range(radial)])  # y min: face S1 of all
    deck.add("*TRANSFORM, NSET=OFFAXIS, TYPE=C", "0., 0., 0., 0., 1., 0.")
    deck.add(*material_and_step(p, [
        "** Axisymmetric: no hoop displacement; the axis stays on the axis.",
        "*BOUNDARY", "OFFAXIS, 2, 2", "AXIS, 1, 1", "AXIS, 3, 3",
        "** The exit end held axially (local 3 off the axis, global y on it).",
        "EXIT, 3, 3", "EXITAXIS, 2, 2"]))
    return deck.text()


def material_and_step(p, boundary):
    """The wire's material, `boundary` and its step (both wire decks)."""
    wire, time = p["wire"], p["time"]
    tension = wire["back_force"] / (math.pi * wire["radius"] ** 2)
    lines = ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{wire['young']:.13g}, {wire['poisson']:.13g}",
             "*DENSITY", f"{wire['density']:.13g}", "*PLASTIC"]
    lines.extend(f"{stress:.13g}, {strain:.13g}" for stress, strain in hardening_table(wire))
    lines += ["*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
              "** The wire is described in a frame that moves with its exit end at the drawing",
              "** speed (case.yaml: frame_velocity), so the exit end is held here."]
    lines += boundary
    lines += ["** Quasi-static: inertia is below 1e-2 of the stresses (docs/wire-drawing.md).",
              "** A step that needs more increments than INC gives up: the coupler steps back.",
              f"*STEP, NLGEOM, INC={p['calculix']['max_increments']}", static_card(p),
              f"{time['delta_t']:.13g}, {time['delta_t']:.13g}, {time['delta_t'] * 1e-6:.13g}, "
              f"{time['delta_t']:.13g}",
              "** The back force: a uniform tension on the entry end (a negative pressure).",
              "*DLOAD", f"ENTRY, P1, {-tension:.13g}",
              "** Newton's tolerances: largest residual force / mean force, largest correction /",
              "** the increment's largest displacement (ccx's defaults: 0.005, 0.01).",
              "*CONTROLS, PARAMETERS=FIELD",
              f"{p['calculix']['residual_tolerance']:g}, {p['calculix']['correction_tolerance']:g}",
              "** ccx's increment control at its defaults but for the cut-back of a diverging",
              "** increment (D_f, ccx's 0.25) and of one converging too slowly (D_C, 0.5).",
              "*CONTROLS, PARAMETERS=TIME INCREMENTATION", "4, 8, 9, 16, 10, 4, 12, 5",
              f"{p['calculix']['cutback']:g}, 0.5",
              "*NODE FILE", "U, RF", "*EL FILE", "S, PEEQ",
              "** Stresses at the integration points, for the check against the yield stress",
              "*EL PRINT, ELSET=SKIN", "S, PEEQ", "*END STEP"]
    return lines


def wire_deck(p, refine):
    """The wire as CAX8 or CAX8R elements (x = radius, y = axis): radial x axial elements of
    equal size, its whole outer surface the interface (the wire slides: any part of it may be
    under the film), in a frame that moves with its exit end (y max) at the drawing speed, so
    that end is held; the back force as a uniform tension on the entry end (y min)."""
    wire = p["wire"]
    factor = 2 if refine else 1
    radial = factor * p["mesh"]["wire_radial_elements"]
    axial = factor * p["mesh"]["wire_axial_elements"]
    radius, length, start = wire["radius"], wire["length"], wire["start"]
    ni, nk = 2 * radial + 1, 2 * axial + 1

    def node(i, k):
        return 1 + i + ni * k

    def element(m, q):
        return 1 + m + radial * q

    element_type = p["mesh"]["wire_element"]
    if element_type not in ("CAX8", "CAX8R"):
        sys.exit(f"make_case.py: mesh.wire_element is {element_type}: use CAX8 or CAX8R")
    deck = calculix.Deck(f"** The drawn wire (make_case.py): axisymmetric {element_type}, "
                         "x = radius, y = axis (z).")
    deck.nodes((node(i, k), radius * i / (ni - 1), start + length * k / (nk - 1), "0.")
               for k in range(nk) for i in range(ni) if i % 2 + k % 2 <= 1)
    deck.elements(element_type, ((element(m, q), quad8(node, 2 * m, 2 * q))
                                 for q in range(axial) for m in range(radial)))
    deck.node_set("SURFACEN", [node(ni - 1, k) for k in range(nk)])
    deck.node_set("AXIS", [node(0, k) for k in range(nk)])
    deck.node_set("EXIT", [node(i, nk - 1) for i in range(ni)])
    deck.surface("SURFACE", [(element(radial - 1, q), "S2")  # r = R: edge S2 (nodes 2-3)
                             for q in range(axial)])
    # The outer column: stresses at its integration points.
    deck.element_set("SKIN", [element(radial - 1, q) for q in range(axial)])
    deck.element_set("ENTRY", [element(m, 0) for m in range(radial)])  # y min: edge S1 (nodes 1-2)
    deck.add(*material_and_step(p, ["*BOUNDARY", "AXIS, 1, 1", "EXIT, 2, 2"]))
    return deck.text()


def case_file(p):
    """The coupled case: the film (openfoam) and the wire (calculix behind a mapped wrapper)."""
    time, coupling = p["time"], p["coupling"]
    if coupling["type"] not in ("iqni", "iqnism", "ibqn"):
        sys.exit(f"make_case.py: coupling.type: '{coupling['type']}' is not iqni, iqnism or ibqn")
    if coupling["type"] != "iqni" and (coupling["mixing"] != 1.0 or coupling["model"] != "ls"):
        sys.exit(f"make_case.py: coupling.type {coupling['type']} takes model ls and mixing 1")
    coupled_solver = {
        "type": case.commented(coupling["type"], "interface quasi-Newton, as the paper"),
        "omega": case.commented(coupling["omega"], "relaxation of a step's first update")}
    if coupling["type"] == "ibqn":  # a model of the film's Jacobian and one of the wire's
        coupled_solver.update(model_f=secant_model(coupling), model_s=secant_model(coupling))
    else:
        if coupling["type"] == "iqni":
            coupled_solver["mixing"] = case.commented(
                coupling["mixing"], "1: IQN-ILS; < 1: the unexplained residual relaxed (ls only)")
        coupled_solver["model"] = secant_model(coupling)
    if coupling["type"] == "iqnism":
        coupled_solver["surrogate"] = surrogate(p)
    coupled_solver["predictor"] = {"type": "linear"}
    coupled_solver["convergence_criterion"] = {"type": "or", "criteria": [
        {"type": case.commented("absolute_norm", "the paper's 0.01 um on the 2-norm of the "
                                                 "displacement residual"),
         "tolerance": coupling["tolerance"]},
        {"type": "iteration_limit", "maximum": coupling["max_iterations"]}]}
    settings = {"delta_t": time["delta_t"], "number_of_timesteps": total_steps(p),
                "state_interval": case.commented(time["state_interval"], "a state to restart "
                                                 "from (cocopp run --restart)")}
    return case.dump({"settings": settings, "coupled_solver": coupled_solver,
                      "solver_wrappers": solver_wrappers(p, "")},
                     header="The dry wire drawing case (docs/wire-drawing.md), written by "
                            "make_case.py.\n  cocopp run case.yaml")


def secant_model(coupling):
    return {"type": case.commented(coupling["model"], "ls: IQN-ILS (the paper's); mvmf: IQN-MVJ"),
            "q": case.commented(coupling["reuse_steps"],
                                "earlier steps whose secant information is reused"),
            "min_significant": case.commented(coupling["min_significant"],
                                              "filter of nearly dependent secant columns:"),
            "min_significant_relative": case.commented(coupling["min_significant_relative"],
                                                       "  absolute and relative thresholds")}


def surrogate(p):
    """iqnism's surrogate: the case on the coarser meshes in surrogate/, its own iqni."""
    s = p["surrogate"]
    coupled_solver = {
        "type": "iqni", "omega": p["coupling"]["omega"], "model": case.flow({"type": s["model"]}),
        "predictor": case.flow({"type": "linear"}),
        "convergence_criterion": {"type": "or", "criteria": [
            case.flow({"type": "absolute_norm", "tolerance": s["tolerance"]}),
            case.flow({"type": "iteration_limit", "maximum": s["max_iterations"]})]}}
    return case.commented({
        "synchronize": case.commented(True, "every step; its Jacobian guides this coupling"),
        "coupled_solver": coupled_solver,
        "mapper": case.commented({"type": "linear", "directions": ["x", "z"]},
                                 "the film's wall points (wedge) on both meshes, along the axis"),
        "solver_wrappers": solver_wrappers(p, "surrogate/")},
        "the case on coarser meshes (surrogate/), solved first")


def solver_wrappers(p, prefix):
    """The film and the wire, in the directories under `prefix`."""
    name = "surrogate_" if prefix else ""
    film = {"type": case.commented("openfoam", "F: the film's wire wall displacement -> its loads"),
            "name": f"{name}film", "working_directory": f"{prefix}fluid",
            "boundary_names": ["wire"]}
    if displacement_driven(p):
        film["gap_patch"] = case.commented("die", "the film's gap and wall position, for the wire")
    if probed_film(p):
        film["sensitivity_probe"] = case.commented(
            {"file": "sensitivity.txt", "move": 1.0e-8, "start": "warm",
             "hat": p["coupling"]["probe_hat"]},
            "each step, the film solved again per hoop line of its wall\n"
            "moved by 0.01 um (every probe_hat-th line, a hat over the\n"
            "lines beside it): its own Jacobian, for the wire's drive")
    film["timeout"] = 600
    wire = {"type": case.commented("mapped", "S: the loads -> the wire's surface displacement"),
            "name": f"{name}wire",
            "coordinates": case.commented("current", "a sliding interface: map on the current "
                                                     "positions ..."),
            "rebuild": case.commented("time_step", "... every time step"),
            "frame_velocity": case.commented([0, p["wire"]["drawing_speed"], 0],
                                             "the wire's frame moves with its exit end"),
            "solver_wrapper": calculix_wrapper(p, prefix),
            "input_mapper": input_mapper(p)}
    if displacement_driven(p):
        wire["exact_round_trip"] = case.commented(
            ["wall_displacement"], "the wall's position onto the nodes so that the\n"
            "output mapper gives it back exactly: the balance is then the\n"
            "coupling's fixed point (docs/mappers.md)")
    wire["output_mapper"] = case.commented(output_mapper(p), "wire surface nodes (r, axis) -> "
                                                             "film wall points (wedge)")
    return [film, wire]


def calculix_wrapper(p, prefix):
    wrapper = {"type": "calculix", "working_directory": f"{prefix}structure",
               "input_file": "wire.inp", "interface_surface": "SURFACE",
               "interface_node_set": "SURFACEN",
               "threads": case.commented(p["calculix"]["threads"],
                                         "the film waits while the wire is solved"),
               "initial_increment": case.commented(
                   "previous_iteration", "where ccx cut a step back, the step's next\n"
                   "iterations start at the increment that converged")}
    if p["calculix"].get("warm_start", False):
        wrapper["warm_start"] = case.commented(
            True, "the step's next iterations start ccx's Newton iterations\n"
            "from the last one's solution")
    if displacement_driven(p):
        wrapper["input_variables"] = case.commented(
            ["force"], "the film's force on each face (a total): the wire\n"
            "takes exactly the film's load (pressure and shear)")
        wrapper["interface_drive"] = case.commented(
            "displacement", "the surface under the film driven by its wall position")
        wrapper["driven_node_set"] = case.commented(
            "SURFACEALL", "all of the sector's surface (SURFACEN: its x-y side)")
        wrapper["surface_stiffness"] = case.commented(
            float(f"{surface_stiffness(p):.6g}"), "Pa/m, the Newton step's wire stiffness")
        if elastic_compliance(p):
            wrapper["surface_compliance"] = case.commented(
                "surface_compliance.txt", "the wire's elastic compliance between its\n"
                "surface lines (surface_compliance.py), in that Newton step")
        if probed_film(p):
            wrapper["film_stiffness"] = case.commented(
                "probed", "the film's stiffness in that Newton step: its own\n"
                "sensitivity, which the film measures each step")
            wrapper["film_probe"] = "../fluid/sensitivity.txt"
    wrapper["timeout"] = 600
    return wrapper


def output_mapper(p):
    return {"type": "linear",
            "components": case.commented(["x", "y"], "only the radial displacement moves the "
                                                     "film: it slides"),
            "directions": case.commented(
                ["x", "z"], "across the wedge and along the axis, not radially: the film's\n"
                "points lag the wire's radius by an iteration, and a 3D search\n"
                "then picks skewed triangles (a jagged wall, 10x rougher)"),
            "transformers": [
                case.flow({"type": "axisymmetric_2d_to_3d", "direction_axial": "y",
                           "direction_radial": "x", "angle": p["mesh"]["wedge_degrees"]}),
                case.commented(case.flow({"type": "permutation", "permutation": [2, 0, 1]}),
                               "(r, axis, third) -> film (third, r, axis)")]}


def displacement_driven(p):
    """coupling.drive: displacement (the wire under the film driven by its wall position)."""
    drive = p["coupling"]["drive"]
    if drive not in ("load", "displacement"):
        sys.exit(f"make_case.py: coupling.drive: '{drive}' is not load or displacement")
    if drive == "displacement" and p["mesh"]["wire_model"] != "sector":
        sys.exit("make_case.py: coupling.drive: displacement needs mesh.wire_model: sector "
                 "(ccx's reactions on an axisymmetric model are not the nodal forces)")
    return drive == "displacement"


def elastic_compliance(p):
    """coupling.surface_compliance: the displacement drive's Newton step with the wire's elastic
    compliance between its surface lines (surface_compliance.py, computed with the case)."""
    return displacement_driven(p) and p["coupling"]["surface_compliance"]


def probed_film(p):
    """coupling.film_stiffness: probed (the film's own sensitivity drives the wire) or local
    (a stiffness per face from its pressure and gap); a model of the displacement drive's, of
    no use to a wire that takes the film's loads (drive: load)."""
    model = p["coupling"]["film_stiffness"]
    if model not in ("probed", "local"):
        sys.exit(f"make_case.py: coupling.film_stiffness: '{model}' is not probed or local")
    if not displacement_driven(p):
        return False
    if model == "probed" and not elastic_compliance(p):
        sys.exit("make_case.py: coupling.film_stiffness: probed needs coupling.surface_compliance:"
                 " true (the probed film alone with a stiffness per line diverges, "
                 "docs/wire-drawing.md)")
    return model == "probed"


def surface_stiffness(p):
    """The wire's stiffness per area against a push of its surface (coupling.surface_stiffness,
    0: that of an elastic half-space under the shortest wave its surface mesh carries, a node
    in, a node out: pi E / ((1 - nu^2) l), l the length of a face along the axis)."""
    given = p["coupling"]["surface_stiffness"]
    if given > 0:
        return given
    wire, face = p["wire"], p["wire"]["length"] / p["mesh"]["wire_axial_elements"]
    return math.pi * wire["young"] / ((1 - wire["poisson"] ** 2) * face)


def input_mapper(p):
    """Film faces -> wire faces; driven by displacement, first film points -> wire nodes."""
    to_wire_axes = case.commented(case.flow({"type": "permutation", "permutation": [1, 2, 0]}),
                                  "film (x, y, z) -> (y, z, x)")
    faces = {"type": case.commented("overlap", "each wire face: the length-weighted mean of the "
                                               "film faces it\noverlaps along the axis (a value "
                                               "per area times length is\nconserved); zero "
                                               "(ambient) for the part of a wire face\noutside "
                                               "the film"),
             "directions": ["y"], "transformers": [to_wire_axes]}
    if not displacement_driven(p):
        return case.commented(faces, "film faces (axis z, radial y) -> wire faces (r, axis)")
    mesh = p["mesh"]
    faces["conservative"] = case.commented(
        ["force"], "each wire face: the film's force on the part of each\n"
        "film face it overlaps (the transpose of a mean: totals kept)")
    faces["conservative_scale"] = case.commented(
        mesh["sector_degrees"] / mesh["wedge_degrees"],
        "the wire's sector over the film's wedge")
    points = {"type": case.commented("linear", "film wall points -> the wire's drivable nodes: "
                                               "the wall's\nposition there, along the axis and "
                                               "across the wedge (an\ninterpolation, which "
                                               "exact_round_trip below corrects);\nzero beyond "
                                               "the film (not driven there)"),
              "directions": ["y", "z"], "max_distance": 1.0e-4, "unmatched": "zero",
              "transformers": [to_wire_axes]}
    return case.commented([points, faces], "a mapper per model part pair:")


def surrogate_parameters(p):
    """The parameters of the surrogate: the case's, on the surrogate's meshes."""
    coarse = copy.deepcopy(p)
    for key in ("film_axial_cells", "film_radial_cells", "wire_radial_elements",
                "wire_axial_elements"):
        coarse["mesh"][key] = p["surrogate"][key]
    return coarse


def write_solvers(p, refine, output):
    """fluid/ and structure/ under output; returns the film."""
    film = Film(p, refine)
    openfoam.write_case(output / "fluid", fluid_files(p, film))
    (output / "structure").mkdir(parents=True, exist_ok=True)
    model = p["mesh"]["wire_model"]
    if model not in ("axisymmetric", "sector"):
        sys.exit(f"make_case.py: mesh.wire_model: '{model}' is not axisymmetric or sector")
    deck = sector_wire_deck(p, refine) if model == "sector" else wire_deck(p, refine)
    (output / "structure" / "wire.inp").write_text(deck)
    if elastic_compliance(p):
        surface_compliance.write_checked(output / "structure", patched_ccx())
    return film


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--parameters", default=str(HERE / "parameters.yaml"))
    parser.add_argument("--output", default=str(HERE / "results" / "case"),
                        help="directory to write the case into (default: results/case)")
    parser.add_argument("--refine", action="store_true", help="double the cells in each direction")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="change one parameter, e.g. --set die.reduction=0")
    args = parser.parse_args()
    p = load_parameters(args.parameters, args.set)
    output = pathlib.Path(args.output)
    film = write_solvers(p, args.refine, output)
    if p["coupling"]["type"] == "iqnism":
        write_solvers(surrogate_parameters(p), False, output / "surrogate")
    (output / "case.yaml").write_text(case_file(p))
    # What the case was made from, for plot.py and checks.py.
    (output / "made_with.yaml").write_text(yaml.safe_dump({"parameters": p,
                                                            "refine": args.refine}))
    print(f"make_case.py: film of {film.radial_cells} x {film.entry_cells + film.bearing_cells} "
          f"cells in {output / 'fluid'}, wire deck {output / 'structure' / 'wire.inp'}")


if __name__ == "__main__":
    main()
