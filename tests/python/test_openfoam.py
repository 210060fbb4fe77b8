"""cocopp.openfoam: the FoamFile header as OpenFOAM's dictionaries start, and a case's files
written with their scripts executable."""
import os
import pathlib
import re
import tempfile
import unittest

from cocopp import openfoam


def foam_file_entries(text):
    """The FoamFile block's entries, read as OpenFOAM reads a dictionary: keyword value;"""
    block = re.match(r"FoamFile\n\{\n(.*?)\n\}\n", text, re.S)
    return dict(re.findall(r"^\s*(\w+)\s+([^;]+);", block.group(1), re.M)) if block else None


class Header(unittest.TestCase):
    def test_entries_and_the_blank_line_after(self):
        header = openfoam.header("volVectorField", "U")
        self.assertEqual(foam_file_entries(header), {"version": "2.0", "format": "ascii",
                                                     "class": "volVectorField", "object": "U"})
        self.assertTrue(header.endswith("}\n\n"))

    def test_as_debian_openfoam_writes_it(self):
        # The entries' layout of OpenFOAM's own tutorials: keyword padded to 12 columns.
        self.assertIn("\n    class       dictionary;\n    object      controlDict;\n",
                      openfoam.header("dictionary", "controlDict"))


class WriteCase(unittest.TestCase):
    def test_files_folders_and_executable_scripts(self):
        files = {"system/controlDict": openfoam.header("dictionary", "controlDict") + "a 1;\n",
                 "Allmesh": "#!/bin/sh\nblockMesh\n"}
        with tempfile.TemporaryDirectory() as directory:
            openfoam.write_case(pathlib.Path(directory) / "fluid", files)
            fluid = pathlib.Path(directory) / "fluid"
            self.assertEqual((fluid / "system/controlDict").read_text(),
                             files["system/controlDict"])
            self.assertTrue(os.access(fluid / "Allmesh", os.X_OK))
            self.assertFalse(os.access(fluid / "system/controlDict", os.X_OK))


if __name__ == "__main__":
    unittest.main()
