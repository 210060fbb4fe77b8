#!/usr/bin/python3
"""ParaView output (issue 18): the tube run with settings.vtk_output writes VTU files and a PVD
time series that a real reader, VTK's own (python3-vtk9), reads back: every step's time in
order, the points at the model part's initial coordinates, and each variable equal to the
results file's values, exactly. `cocopp export-vtk` of the results file writes the same files;
a restarted run continues the collection without repeating a step. settings.vtk_iterations
writes every coupling iteration of chosen steps, with the residual r = x~ - x as a field whose
norm is the results file's residual norm of that iteration, and the converged iteration's
input equal to the step's result.

    /usr/bin/python3 tests/integration/test_vtk_output.py BIN_DIR
"""
import filecmp
import pathlib
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

import h5py
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent


def check(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)


def collection(pvd):
    """(time, part name, file) of every data set, in file order."""
    root = ElementTree.parse(pvd).getroot()
    return [(float(d.get("timestep")), d.get("name"), pvd.parent / d.get("file"))
            for d in root.iter("DataSet")]


def read_vtu(file):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(file))
    reader.Update()
    grid = reader.GetOutput()
    check(grid.GetNumberOfPoints() > 0, f"{file}: VTK read no points")
    arrays = {grid.GetPointData().GetArrayName(i): vtk_to_numpy(grid.GetPointData().GetArray(i))
              for i in range(grid.GetPointData().GetNumberOfArrays())}
    return vtk_to_numpy(grid.GetPoints().GetData()), grid.GetNumberOfCells(), arrays


def compare_with_results(pvd, h5):
    entries = collection(pvd)
    with h5py.File(h5, "r") as f:
        steps, times = f["steps/step"][:], f["steps/time"][:]
        check(len(entries) == len(steps), f"{len(entries)} data sets for {len(steps)} steps")
        check([t for t, _, _ in entries] == list(times), "times differ from the results file")
        check(all(np.diff(times) > 0), "times not in order")
        for row, (time, part, file) in enumerate(entries):
            points, cells, arrays = read_vtu(file)
            check(np.array_equal(points, f[f"x/{part}/coordinates"][:]), f"{file}: points")
            check(cells == len(points), f"{file}: one vertex per point")
            check(np.array_equal(arrays["id"], f[f"x/{part}/ids"][:]), f"{file}: ids")
            for interface in ("x", "y"):
                for variable in f[f"{interface}/{part}"]:
                    if variable in ("ids", "coordinates"):
                        continue
                    expected = f[f"{interface}/{part}/{variable}"][row]
                    got = arrays[variable].reshape(expected.shape)
                    check(np.array_equal(got, expected), f"{file}: {variable} of step {steps[row]}")
    return len(entries)


def main():
    bin_dir = pathlib.Path(sys.argv[1])
    cocopp = str(bin_dir / "cocopp")
    with tempfile.TemporaryDirectory(prefix="cocopp_vtk_") as tmp:
        case_dir = pathlib.Path(tmp) / "tube"
        shutil.copytree(ROOT / "examples/tube/flow_structure", case_dir,
                        ignore=shutil.ignore_patterns("results"))
        case = case_dir / "case.yaml"
        original = case.read_text()
        case.write_text(original.replace(
            "number_of_timesteps: 100",
            "number_of_timesteps: 10\n  vtk_output: true\n  vtk_iterations: [1, 7]"))
        subprocess.run([cocopp, "run", "-q", str(case)], check=True, stdout=subprocess.DEVNULL)
        results = case_dir / "results"
        count = compare_with_results(results / "case.pvd", results / "case.h5")
        check(count == 10, f"{count} data sets")
        variables = read_vtu(collection(results / "case.pvd")[0][2])[2].keys()
        check({"displacement", "pressure", "traction"} <= set(variables), f"arrays {variables}")

        # Every iteration of steps 1 and 7, with the residual as a field.
        with h5py.File(results / "case.h5", "r") as f:
            for step in (1, 7):
                row = step - 1
                offset, count = f["residuals/offset"][row], f["residuals/count"][row]
                norms = f["residuals/norms"][offset:offset + count]
                entries = collection(results / f"case_step{step:06d}_iterations.pvd")
                check([t for t, _, _ in entries] == list(range(1, count + 1)),
                      f"step {step}: one data set per iteration, {count}, timed 1, 2, ...")
                for (iteration, _, file), norm in zip(entries, norms):
                    residual = read_vtu(file)[2]["residual_displacement"]
                    check(np.isclose(np.linalg.norm(residual), norm, rtol=1e-12, atol=0),
                          f"step {step}, iteration {iteration:g}: |r| {np.linalg.norm(residual)}"
                          f" against {norm}")
                last = read_vtu(entries[-1][2])[2]
                check(np.array_equal(last["displacement"].reshape(-1, 3),
                                     f["x/wall/displacement"][row]),
                      f"step {step}: the last iteration's input is the step's displacement")
                check(np.array_equal(last["pressure"].reshape(-1), f["y/wall/pressure"][row, :, 0]),
                      f"step {step}: the last iteration's pressure is the step's")

        # The tube solvers' own ParaView files carry their time (legacy VTK, field data TIME).
        for solver in ("flow", "structure"):
            for step in (0, 10):
                reader = vtk.vtkPolyDataReader()
                reader.SetFileName(str(case_dir / solver / "output" /
                                       f"tube_{solver}_{step:06d}.vtk"))
                reader.Update()
                time = reader.GetOutput().GetFieldData().GetArray("TIME")
                check(time is not None and time.GetValue(0) == step * 1e-4,
                      f"tube_{solver}_{step:06d}.vtk: TIME {time and time.GetValue(0)}")

        # export-vtk writes the same files from the results file.
        exported = pathlib.Path(tmp) / "exported"
        subprocess.run([cocopp, "export-vtk", str(results / "case.h5"), "-o", str(exported)],
                       check=True, stdout=subprocess.DEVNULL)
        check(filecmp.cmp(exported / "case.pvd", results / "case.pvd", shallow=False),
              "export-vtk's collection differs")
        comparison = filecmp.dircmp(exported / "case_vtk", results / "case_vtk")
        check(not comparison.diff_files and not comparison.left_only and not comparison.right_only,
              f"export-vtk's files differ: {comparison.diff_files}")

        # A restarted run continues the collection.
        case.write_text(original.replace("number_of_timesteps: 100",
                                          "number_of_timesteps: 15\n  vtk_output: true"))
        subprocess.run([cocopp, "run", "-q", "--restart", str(case)], check=True,
                       stdout=subprocess.DEVNULL)
        count = compare_with_results(results / "case.pvd", results / "case.h5")
        check(count == 15, f"{count} data sets after the restart")
    print("ok: ParaView output read back by VTK", vtk.vtkVersion.GetVTKVersion())


if __name__ == "__main__":
    main()
