"""OpenFOAM case files: the FoamFile header every dictionary starts with, and writing a case's
files. The dictionaries' bodies stay text in the scripts that make them, with their comments.

    from cocopp import openfoam

    files = {"constant/transportProperties": openfoam.header("dictionary", "transportProperties")
             + "transportModel  Newtonian;\\nnu              1e-06;\\n"}
    openfoam.write_case("fluid", files)
"""
import pathlib


def header(cls, name):
    """The FoamFile header of a dictionary of class `cls` (dictionary, volVectorField, ...) named
    `name`, with a blank line after it."""
    return (f"FoamFile\n{{\n    version     2.0;\n    format      ascii;\n    class       {cls};"
            f"\n    object      {name};\n}}\n\n")


def write_case(directory, files):
    """Writes {path relative to `directory`: text} (folders made as needed); a file whose text
    starts with #! (Allmesh, Allrun) is made executable."""
    directory = pathlib.Path(directory)
    for name, text in files.items():
        path = directory / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        if text.startswith("#!"):
            path.chmod(0o755)
