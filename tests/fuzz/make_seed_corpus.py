#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora, tests/fuzz/corpus/<target>/, from the examples (case
files, ccx decks, OpenFOAM dictionaries), from the protocol's byte layout (docs/protocol.md),
and from the inputs behind issue 17's defects; files named found_* are inputs a fuzz run found
(each fixed, each with a test) and cov_* the minimized corpus of a long case-file run: they stay. Rerun it after an example changes:

  /usr/bin/python3 tests/fuzz/make_seed_corpus.py
"""
import pathlib
import struct

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
CORPUS = ROOT / "tests" / "fuzz" / "corpus"


def write(target, name, data):
    directory = CORPUS / target
    directory.mkdir(parents=True, exist_ok=True)
    (directory / name).write_bytes(data if isinstance(data, bytes) else data.encode())


def case_files():
    for file in sorted(ROOT.glob("examples/**/case*.yaml")) + sorted(ROOT.glob("examples/**/case*.json")):
        if "results" in file.parts:
            continue
        name = "_".join(file.relative_to(ROOT / "examples").parts)
        write("case_file", name, file.read_bytes())
    base = (ROOT / "examples/tube/flow_structure/case.yaml").read_text()
    # Issue 17's defects, each as the input that showed it.
    write("case_file", "defect8_duplicate_key.yaml",
          base.replace("  number_of_timesteps: 100", "  number_of_timesteps: 100\n  delta_t: 2.0e-4"))
    write("case_file", "defect8_second_document.yaml", base + "---\nsettings: {}\n")
    write("case_file", "defect9_mapping_as_key.yaml", base.replace("settings:", "? [a, b]\n: 1\nsettings:"))
    write("case_file", "defect9_deep_nesting.yaml", "settings: " + "[" * 600 + "]" * 600 + "\n")
    write("case_file", "defect6_end_time.yaml", base.replace("number_of_timesteps: 100", "end_time: 1.0e+300"))
    write("case_file", "defect6_timestep_start.yaml",
          base.replace("number_of_timesteps: 100", "number_of_timesteps: 100\n  timestep_start: 2147483647"))
    write("case_file", "defect10_name_as_path.yaml", base.replace("name: flow", "name: ../../x"))
    write("case_file", "nan_omega.yaml", base.replace("omega: 0.05", "omega: .nan"))
    # Found by fuzzing: after a NUL byte yaml-cpp's LoadAll collected empty documents for ever.
    write("case_file", "found_nul_byte_hang.yaml", base.replace("1D flexible", "1D f" + "\0" * 56 + "lexible"))


def decks():
    for file in sorted(ROOT.glob("examples/**/*.inp")):
        write("calculix_deck", file.name, file.read_bytes())
    write("calculix_deck", "small_cax.inp", """*NODE
1, 0.0, 0.0
2, 1.0, 0.0
3, 1.0, 1.0
4, 0.0, 1.0
*ELEMENT, TYPE=CAX4, ELSET=EALL
1, 1, 2, 3, 4
*NSET, NSET=WALLMID
2, 3
*SURFACE, NAME=WALL, TYPE=ELEMENT
1, S2
*MATERIAL, NAME=STEEL
*ELASTIC
2.0e11, 0.3
*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL
*STEP, NLGEOM
*STATIC
*NODE PRINT, NSET=WALLMID
U
*END STEP
""")


def dat_files():
    header = " displacements (vx,vy,vz) for set WALLMID and time  0.1000000E+01\n\n"
    rows = "".join(f"{i:10d}  {1e-6 * i:.6E}  {-2e-6 * i:.6E}  0.000000E+00\n" for i in (1, 2, 3))
    write("calculix_dat", "one_block.dat", "\n" + header + rows + "\n")
    write("calculix_dat", "two_blocks.dat", "\n" + header + rows + "\n" + header + rows + "\n")
    write("calculix_dat", "missing_node.dat", "\n" + header + rows.splitlines(True)[0] + "\n")


def dictionaries():
    case = ROOT / "examples/tube/openfoam_wedge/fluid"
    for file in sorted(case.glob("system/*")) + sorted(case.glob("constant/*")):
        write("openfoam_dictionary", file.name, file.read_bytes())
    write("openfoam_dictionary", "boundary", """FoamFile
{
    version     2.0;
    format      ascii;
    class       polyBoundaryMesh;
    object      boundary;
}
3
(
    inlet
    {
        type            patch;
        nFaces          10;
        startFace       400;
    }
    wall
    {
        type            wall;
        nFaces          40;
        startFace       410;
    }
    front
    {
        type            wedge;
        nFaces          40;
        startFace       450;
    }
)
""")


def frame(type_byte, payload=b""):
    return bytes([type_byte]) + payload


def f64_array(values):
    return struct.pack("<Q", len(values)) + b"".join(struct.pack("<d", v) for v in values)


def i64_array(values):
    return struct.pack("<Q", len(values)) + b"".join(struct.pack("<q", v) for v in values)


def string(text):
    data = text.encode()
    return struct.pack("<I", len(data)) + data


def names(words):
    return struct.pack("<I", len(words)) + b"".join(string(w) for w in words)


def frames():
    interface = (struct.pack("<I", 1) + string("wall") + i64_array([1, 2])
                 + f64_array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0])
                 + names(["displacement"]) + names(["pressure", "traction"]) + f64_array([0.0] * 8))
    seeds = {
        "initialize": frame(1, struct.pack("<di", 1e-4, 0)),
        "initialize_step": frame(2, struct.pack("<id", 3, 3e-4)),
        "solve": frame(3, f64_array([1e-6, -2e-6, 0.0])),
        "finalize_step": frame(4),
        "output_step": frame(5),
        "stop": frame(6),
        "save_restart": frame(7, struct.pack("<i", 50)),
        "hello": frame(128, struct.pack("<Iq", 1, 4242)),
        "ok": frame(129),
        "interface": frame(130, interface),
        "data": frame(131, f64_array([1.0, float("nan"), float("inf")])),
        "error": frame(132, string("the step did not converge\x1b[31m")),
        "rejected": frame(133, string("negative cell volume")),
        "length_prefix_1GiB": struct.pack("<I", 1 << 30) + frame(131),
        "truncated_interface": frame(130, interface[:-5]),
        "lying_count": frame(131, struct.pack("<Q", 0xFFFFFFFFFFFFFFFF)),
    }
    for name, data in seeds.items():
        write("protocol", name, data)


def main():
    # found_*: inputs a fuzz run found (a crash or a hang, fixed since); cov_*: the case-file
    # corpus of a long fuzz run, minimized (-merge=1), which the sanitizer build replays. Kept.
    for file in CORPUS.glob("*/*"):
        if not file.name.startswith(("found_", "cov_")):
            file.unlink()
    case_files()
    decks()
    dat_files()
    dictionaries()
    frames()
    for directory in sorted(CORPUS.iterdir()):
        print(f"{directory.relative_to(ROOT)}: {len(list(directory.iterdir()))} inputs")


if __name__ == "__main__":
    main()
