"""cocopp: the Python side of the cocopp coupler's scripts and examples (docs/python.md).

Modules, each importing only what it needs (NumPy always; h5py, matplotlib and yaml where said):
  results     a run's results file (h5py) and summary, and `cocopp bench`'s bench.json
  plot        figures of them (matplotlib)
  case        writing a case file (case.yaml) from a dict, with comments (yaml)
  openfoam    OpenFOAM case files: the FoamFile header, writing a case's files
  calculix    CalculiX decks (*NODE, *ELEMENT, sets, surfaces), reading .dat, .frd and decks
  executable  the cocopp executable to run (a checkout's build, or an installed one)
  turek_hron  the Turek-Hron benchmark's flag, shared by examples/turek_hron/csm and fsi

The solver SDK (cocopp_sdk, solvers/sdk) is a module of its own: a solver imports it
with nothing but NumPy.
"""
