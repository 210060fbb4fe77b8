"""cocopp.case: a case file written from a dict loads back as that dict (with yaml, the
reference), with its comments where they were asked for."""
import pathlib
import tempfile
import unittest

import yaml

from cocopp import case

TUBE = {
    "settings": {"delta_t": 1.0e-4, "number_of_timesteps": case.commented(100, "10 ms"),
                 "results_name": "1e-07"},  # text that YAML 1.1 would read as text: kept text
    "coupled_solver": {
        "type": "iqni", "omega": 0.05,
        "model": case.flow({"type": "ls", "q": 10, "min_significant": 1.0e-12}),
        "predictor": case.flow({"type": "linear"}),
        "convergence_criterion": {"type": "or", "criteria": [
            {"type": case.commented("relative_norm", "the first tolerance\nand why"),
             "tolerance": 1.0e-6},
            case.flow({"type": "iteration_limit", "maximum": 15})]}},
    "solver_wrappers": [
        {"type": "tube_flow", "name": "flow", "boundary_names": ["wall"],
         "frame_velocity": [0, 1.5, 0], "synchronize": True},
        case.commented(case.flow({"type": "tube_structure", "name": "structure"}), "S")]}


class Dump(unittest.TestCase):
    def setUp(self):
        self.text = case.dump(TUBE, header="The tube\n  cocopp run case.yaml")

    def test_loads_back_as_the_dict(self):
        loaded = yaml.safe_load(self.text)
        self.assertEqual(loaded["settings"], {"delta_t": 1.0e-4, "number_of_timesteps": 100,
                                              "results_name": "1e-07"})
        self.assertEqual(loaded["coupled_solver"]["convergence_criterion"]["criteria"],
                         [{"type": "relative_norm", "tolerance": 1.0e-6},
                          {"type": "iteration_limit", "maximum": 15}])
        self.assertEqual(loaded["solver_wrappers"][1], {"type": "tube_structure",
                                                        "name": "structure"})
        self.assertEqual(loaded, case.plain(TUBE))

    def test_header_and_comments_where_asked(self):
        lines = self.text.splitlines()
        self.assertEqual(lines[:3], ["# The tube", "#   cocopp run case.yaml", "settings:"])
        counted = next(line for line in lines if "number_of_timesteps" in line)
        self.assertEqual(counted.split("#")[1], " 10 ms")
        first = lines.index(next(line for line in lines if "relative_norm" in line))
        self.assertTrue(lines[first].endswith("# the first tolerance"))
        self.assertEqual(lines[first + 1].strip(), "# and why")
        self.assertTrue(lines[-1].endswith("# S"))

    def test_flow_and_block_style(self):
        self.assertIn("  model: {type: ls, q: 10, min_significant: 1.0e-12}\n", self.text)
        self.assertIn("    boundary_names: [wall]\n", self.text)
        self.assertIn("  - type: tube_flow\n    name: flow\n", self.text)
        self.assertIn("      - {type: iteration_limit, maximum: 15}\n", self.text)

    def test_the_number_of_steps_on_a_line_of_its_own(self):
        # examples/wire_drawing/run.sh --steps edits this line with sed.
        self.assertRegex(self.text, r"\n  number_of_timesteps: 100 +# 10 ms\n")

    def test_two_comments_for_one_line_are_refused(self):
        clash = {"list": [case.commented({"type": case.commented("a", "one")}, "two")]}
        with self.assertRaises(ValueError):
            case.dump(clash)

    def test_write_and_read(self):
        with tempfile.TemporaryDirectory() as directory:
            path = pathlib.Path(directory) / "case.yaml"
            case.write(path, TUBE)
            self.assertEqual(case.read(path), case.plain(TUBE))


if __name__ == "__main__":
    unittest.main()
