"""cocopp.state.rewind_state against real runs of the tube example (examples/tube/flow_structure,
20 steps, a state saved every 5): the state it writes for the last step from the results file
is the one the run saved; a copy of the run restarted from the state it writes for step 10
repeats steps 11-20 bit for bit (IQN-ILS without reuse carries nothing else between steps);
a run whose coupled solver reuses secant columns is refused, since its results file does not
hold them. The cocopp run is $COCOPP_BIN_DIR's (ctest sets it), else the one
cocopp.executable finds."""
import pathlib
import shutil
import subprocess
import tempfile
import unittest

import h5py
import numpy as np

from cocopp.executable import find_cocopp
from cocopp.results import ResultsFile
from cocopp.state import StateError, rewind_state

SOURCE = pathlib.Path(__file__).resolve().parents[2]


def tube_case(directory, reuse):
    """The tube example in `directory`: 20 steps, a state every 5, `reuse` steps of secant
    columns."""
    shutil.copytree(SOURCE / "examples/tube/flow_structure", directory,
                    ignore=shutil.ignore_patterns("results", "output", "*.log"))
    case = directory / "case.yaml"
    text = case.read_text().replace("number_of_timesteps: 100",
                                    "number_of_timesteps: 20\n  state_interval: 5")
    case.write_text(text.replace("q: 10 ", f"q: {reuse} "))
    return case


def run(case, *options):
    subprocess.run([str(find_cocopp()), "run", "--quiet", str(case), *options], check=True,
                   capture_output=True, text=True)


def steps(case):
    """Iterations and the interface's x of every step of a run."""
    with ResultsFile(case.parent / "results" / "case.h5") as results:
        part = results.model_parts("x")[0]
        return (dict(zip(results.steps, results.iterations)),
                dict(zip(results.steps, results.values("x", part, "displacement"))))


class RewindState(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.scratch = tempfile.TemporaryDirectory(prefix="cocopp-python-state-")
        cls.case = tube_case(pathlib.Path(cls.scratch.name) / "run", reuse=0)
        run(cls.case)
        cls.results = cls.case.parent / "results" / "case.h5"
        cls.state = cls.case.parent / "results" / "case.state.h5"

    @classmethod
    def tearDownClass(cls):
        cls.scratch.cleanup()

    def test_the_last_step_is_the_saved_state(self):
        rewound = pathlib.Path(self.scratch.name) / "rewound.h5"
        rewind_state(self.results, self.state, 20, rewound)
        with h5py.File(self.state) as saved, h5py.File(rewound) as written:
            self.assertEqual(written.attrs["step"], saved.attrs["step"])
            self.assertEqual(written.attrs["time"], saved.attrs["time"])
            np.testing.assert_array_equal(written["predictor/history"][...],
                                          saved["predictor/history"][...])
            self.assertEqual(written["largest_first_residual"][()],
                             saved["largest_first_residual"][()])

    def test_a_restart_from_an_earlier_step_repeats_the_run(self):
        copy = pathlib.Path(self.scratch.name) / "from10"
        shutil.copytree(self.case.parent, copy)
        rewind_state(copy / "results/case.h5", self.state, 10, copy / "results/case.state.h5")
        run(copy / "case.yaml", "--restart")
        iterations, x = steps(self.case)
        again_iterations, again_x = steps(copy / "case.yaml")
        for step in range(11, 21):
            self.assertEqual(again_iterations[step], iterations[step], f"step {step}")
            np.testing.assert_array_equal(again_x[step], x[step], f"step {step}")

    def test_a_step_the_file_lacks_is_refused(self):
        with self.assertRaisesRegex(StateError, "no step 21"):
            rewind_state(self.results, self.state, 21, pathlib.Path(self.scratch.name) / "x.h5")

    def test_secant_columns_carried_between_steps_are_refused(self):
        case = tube_case(pathlib.Path(self.scratch.name) / "reuse", reuse=10)
        run(case)
        with self.assertRaisesRegex(StateError, "model/v"):
            rewind_state(case.parent / "results/case.h5", case.parent / "results/case.state.h5",
                         10, pathlib.Path(self.scratch.name) / "y.h5")


if __name__ == "__main__":
    unittest.main()
