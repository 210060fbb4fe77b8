"""cocopp.results against a real run: the tube example (examples/tube/flow_structure, 20 steps,
a watchpoint) run by cocopp, its results file read through the package and checked against
what the same run printed and wrote to its summary JSON. The cocopp run is $COCOPP_BIN_DIR's
(ctest sets it), else the one cocopp.executable finds."""
import json
import pathlib
import re
import shutil
import subprocess
import tempfile
import unittest

import numpy as np

from cocopp import results
from cocopp.executable import find_cocopp

SOURCE = pathlib.Path(__file__).resolve().parents[2]
STEPS = 20
PROGRESS = re.compile(r"^step +(\d+) / \d+ .* iterations +(\d+) +residual ([0-9.e+-]+)", re.M)


class TubeRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.scratch = tempfile.TemporaryDirectory(prefix="cocopp-python-results-")
        cls.case = pathlib.Path(cls.scratch.name) / "tube" / "case.yaml"
        shutil.copytree(SOURCE / "examples/tube/flow_structure", cls.case.parent,
                        ignore=shutil.ignore_patterns("results", "output", "*.log"))
        text = cls.case.read_text().replace(
            "number_of_timesteps: 100", f"number_of_timesteps: {STEPS}\n  watchpoints: "
            "[{name: mid, coordinates: [0, 0.005, 0.00025]}]")
        cls.case.write_text(text)
        run = subprocess.run([str(find_cocopp()), "run", str(cls.case)], capture_output=True,
                             text=True, check=True)
        cls.printed = [(int(s), int(i), float(r)) for s, i, r in PROGRESS.findall(run.stdout)]
        cls.summary = json.loads((cls.case.parent / "results/case.summary.json").read_text())
        cls.file = results.ResultsFile(results.results_path(cls.case))

    @classmethod
    def tearDownClass(cls):
        cls.file.close()
        cls.scratch.cleanup()

    def test_where_the_run_wrote(self):
        self.assertEqual(results.results_path(self.case), self.case.parent / "results/case.h5")
        self.assertEqual(results.read_summary(results.results_path(self.case)), self.summary)

    def test_steps_times_and_status(self):
        self.assertEqual(len(self.printed), STEPS)
        self.assertEqual(list(self.file.steps), [s for s, _, _ in self.printed])
        np.testing.assert_allclose(self.file.times, self.file.steps * 1.0e-4, rtol=1e-12)
        self.assertEqual(self.file.status, self.summary["status"])
        self.assertEqual(self.file.status, "completed")
        self.assertEqual(self.file.solver_names, self.summary["solvers"])

    def test_iterations_as_printed_and_summarized(self):
        printed = [i for _, i, _ in self.printed]
        self.assertEqual(list(self.file.iterations), printed)
        self.assertEqual(list(self.file.iterations), self.summary["iterations_per_step"])
        self.assertTrue(self.file.converged.all())

    def test_residual_histories(self):
        histories = self.file.residual_histories()
        self.assertEqual([len(norms) for _, norms, _ in histories], list(self.file.iterations))
        for (step, norms, converged), history in zip(histories,
                                                     self.summary["residual_history"]):
            np.testing.assert_array_equal(norms, history)
            self.assertTrue(converged)
        for (_, norms, _), (_, _, printed) in zip(histories, self.printed):
            self.assertAlmostEqual(norms[-1] / printed, 1.0, delta=1e-3)  # printed with %.3e
        self.assertIsNone(self.file.unfinished_step())
        self.assertEqual(self.file.tolerance(), ("relative", "2", 1.0e-6))  # the case's

    def test_interface_and_watchpoint(self):
        self.assertEqual(self.file.model_parts("x"), ["wall"])
        coordinates = self.file.coordinates("x", "wall")
        displacement = self.file.values("x", "wall", "displacement")
        self.assertEqual(displacement.shape, (STEPS, len(coordinates), 3))
        self.assertEqual(self.file.find_variable("pressure"), ("y", "wall"))
        series, point = self.file.watchpoint_series("mid")
        np.testing.assert_allclose(point, [0, 0.005, 0.00025])
        nearest, at = self.file.nearest_point_series(point)
        np.testing.assert_allclose(at, point, atol=1e-12)  # a cell centre of the tube
        np.testing.assert_allclose(series["pressure"][1], nearest["pressure"][1], rtol=1e-12)
        self.assertEqual(series["pressure"][2], "Pa")

    def test_a_missing_step_and_an_unreadable_file_are_named(self):
        with self.assertRaisesRegex(SystemExit, "step 999 not in"):
            self.file.row(999)
        with self.assertRaisesRegex(results.ResultsFileError, "cannot open"):
            results.ResultsFile(self.case)  # a YAML file, not HDF5


class FileNames(unittest.TestCase):
    def test_the_case_settings_name_the_results(self):
        with tempfile.TemporaryDirectory() as directory:
            case = pathlib.Path(directory) / "tube.yaml"
            case.write_text("settings: {delta_t: 1.0}\n")
            self.assertEqual(results.results_path(case), case.parent / "results/tube.h5")
            case.write_text("settings: {results_directory: out, results_name: run1}\n")
            self.assertEqual(results.results_path(case), case.parent / "out/run1.h5")
            self.assertEqual(results.summary_path(case.parent / "out/run1.h5"),
                             case.parent / "out/run1.summary.json")
            self.assertEqual(results.read_summary(case.parent / "out/run1.h5", missing_ok=True),
                             {})

    def test_a_bench_run_directory(self):
        self.assertEqual(results.bench_run_directory("out", {"name": "iqni"}),
                         pathlib.Path("out/iqni"))
        self.assertEqual(results.bench_run_directory("out", {"case": "stiff", "name": "iqni"}),
                         pathlib.Path("out/stiff/iqni"))


if __name__ == "__main__":
    unittest.main()
