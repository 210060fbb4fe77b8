"""cocopp.calculix: a deck written card by card, and ccx's answer to it read back.

data/cube.inp is the deck below as the package writes it; data/cube.dat and data/cube.frd are
what Debian's ccx 2.20 wrote for it: a unit cube of E = 1000 Pa, nu = 0, pulled along x by
4 x 2.5 N, so u_x = F L / (E A) = 0.01 m on its right face and s_xx = 10 Pa everywhere."""
import pathlib
import shutil
import subprocess
import tempfile
import unittest

from cocopp import calculix, turek_hron

DATA = pathlib.Path(__file__).resolve().parent / "data"
CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
RIGHT = [2, 3, 6, 7]


def cube_deck():
    deck = calculix.Deck("** A unit cube of one C3D8 element pulled along x "
                         "(tests/python/test_calculix.py)")
    deck.nodes((n + 1, *xyz) for n, xyz in enumerate(CORNERS))
    deck.elements("C3D8", [(1, range(1, 9))])
    deck.node_set("LEFT", [1, 4, 5, 8])
    deck.node_set("RIGHT", RIGHT)
    deck.add("*BOUNDARY", "LEFT, 1, 1", "1, 2, 3", "4, 3, 3", "5, 2, 2",
             "*MATERIAL, NAME=STEEL", "*ELASTIC", "1000., 0.",
             "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
             "*STEP", "*STATIC", "*CLOAD", "RIGHT, 1, 2.5",
             "*NODE PRINT, NSET=RIGHT", "U", "*EL PRINT, ELSET=EALL", "S", "*NODE FILE", "U",
             "*END STEP")
    return deck.text()


class DeckWriting(unittest.TestCase):
    def test_the_cube_is_the_deck_ccx_solved(self):
        self.assertEqual(cube_deck(), (DATA / "cube.inp").read_text())

    def test_an_element_of_twenty_nodes_continues_after_sixteen_entries(self):
        deck = calculix.Deck()
        deck.elements("C3D20", [(7, range(1, 21))], elset="WALL")
        lines = deck.text().splitlines()
        self.assertEqual(lines[0], "*ELEMENT, TYPE=C3D20, ELSET=WALL")
        self.assertEqual(lines[1], ", ".join(str(n) for n in [7] + list(range(1, 16))) + ",")
        self.assertEqual(lines[2], "16, 17, 18, 19, 20")
        self.assertEqual(calculix.deck_elements(deck.text()), {7: list(range(1, 21))})

    def test_numbers_keep_thirteen_digits_and_text_stays_text(self):
        deck = calculix.Deck()
        deck.nodes([(1, 1 / 3, -2.5e-7, "0.")])
        self.assertEqual(deck.text().splitlines()[1], "1, 0.3333333333333, -2.5e-07, 0.")

    def test_sets_and_surfaces_one_entry_a_line(self):
        deck = calculix.Deck()
        deck.node_set("A", [3, 4])
        deck.element_set("B", [5])
        deck.surface("C", [(5, "S2"), (6, "S4")])
        self.assertEqual(deck.text(), "*NSET, NSET=A\n3,\n4,\n*ELSET, ELSET=B\n5,\n"
                                      "*SURFACE, NAME=C, TYPE=ELEMENT\n5, S2\n6, S4\n")

    def test_a_deck_read_back_skips_comments_and_print_cards(self):
        text = "*NODE, NSET=N\n1, 0., 1.\n** a comment\n2, 3., 4., 5.\n*NODE PRINT, NSET=N\nU\n"
        self.assertEqual(calculix.deck_nodes(text), {1: [0.0, 1.0, 0.0], 2: [3.0, 4.0, 5.0]})


class ReadingWhatCcxWrote(unittest.TestCase):
    def test_dat_displacements_and_stresses(self):
        displacements = calculix.dat_block(DATA / "cube.dat", "displacements")
        self.assertEqual([int(row[0]) for row in displacements], RIGHT)
        for row in displacements:
            self.assertAlmostEqual(row[1], 0.01, places=12)
        stresses = calculix.dat_block(DATA / "cube.dat", "stresses")
        self.assertEqual(len(stresses), 8)  # C3D8: 8 integration points
        for row in stresses:
            self.assertEqual(row[:2], [1, row[1]])
            self.assertAlmostEqual(row[2], 10.0, places=9)
        self.assertIsNone(calculix.dat_block(DATA / "cube.dat", "forces"))

    def test_dat_keeps_the_last_block_and_drops_the_transformed_mark(self):
        with tempfile.NamedTemporaryFile("w", suffix=".dat") as dat:
            dat.write("\n forces (fx,fy,fz) for set S and time  0.1E+01\n\n"
                      "         9  1.0E+00  2.0E+00  3.0E+00\n\n"
                      " forces (fx,fy,fz) for set S and time  0.2E+01\n\n"
                      "         9 -8.673201E-15  1.605904E-13  9.643104E-03 L\n"
                      "        36  4.0E+00  5.0E+00  6.0E+00 L\n\n")
            dat.flush()
            self.assertEqual(calculix.dat_block(dat.name, "forces"),
                             [[9, -8.673201e-15, 1.605904e-13, 9.643104e-03], [36, 4, 5, 6]])

    def test_frd_coordinates_and_displacements(self):
        frd = calculix.Frd(DATA / "cube.frd")
        self.assertEqual(list(frd.ids), list(range(1, 9)))
        self.assertEqual(frd.coordinates.tolist(), [list(map(float, c)) for c in CORNERS])
        ux = dict(zip(frd.ids, frd.values("DISP")[:, 0]))
        for node in range(1, 9):
            self.assertAlmostEqual(ux[node], 0.01 if node in RIGHT else 0.0, places=12)
        with self.assertRaises(KeyError):
            calculix.Frd(DATA / "cube.frd", {"STRESS"}).values("DISP")

    @unittest.skipUnless(shutil.which("ccx"), "no ccx on PATH (Debian: calculix-ccx)")
    def test_ccx_solves_the_deck_as_written_now(self):
        with tempfile.TemporaryDirectory() as work:
            pathlib.Path(work, "cube.inp").write_text(cube_deck())
            subprocess.run(["ccx", "-i", "cube"], cwd=work, check=True, capture_output=True)
            rows = calculix.dat_block(pathlib.Path(work, "cube.dat"), "displacements")
            self.assertEqual([round(row[1], 12) for row in rows], [0.01] * 4)


class TurekHronFlag(unittest.TestCase):
    def test_the_flag_as_the_benchmark_gives_it(self):
        text = turek_hron.flag_deck("fsi3", nx=20, ny=2, dt=0.001)
        nodes, elements = calculix.deck_nodes(text), calculix.deck_elements(text)
        self.assertEqual(len(elements), 40)
        self.assertTrue(all(len(ids) == 8 for ids in elements.values()))
        tip = int(text.split("*NSET, NSET=POINTA\n")[1].split(",")[0])
        self.assertEqual([round(c, 12) for c in nodes[tip]], [0.6, 0.2, 0.0])  # point A
        xs = [x for x, _, _ in nodes.values()]
        ys = [y for _, y, _ in nodes.values()]
        self.assertAlmostEqual(max(xs), 0.6, places=12)
        self.assertAlmostEqual(min(ys), 0.19, places=12)
        self.assertAlmostEqual(max(ys), 0.21, places=12)
        self.assertIn("5600000, 0.4", text)  # fsi3: mu 2e6 Pa, E = 2 mu (1 + nu)


if __name__ == "__main__":
    unittest.main()
