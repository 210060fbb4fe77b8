"""CalculiX files: input decks written card by card, and what ccx writes read back (the .dat
file's printed blocks, the .frd file's nodes and results), and a deck's nodes and elements.

    from cocopp import calculix

    deck = calculix.Deck("** A bar of two CPS4 elements")
    deck.nodes([(1, 0.0, 0.0), (2, 1.0, 0.0), (3, 1.0, 1.0), (4, 0.0, 1.0)])
    deck.elements("CPS4", [(1, [1, 2, 3, 4])])
    deck.node_set("LEFT", [1, 4])
    pathlib.Path("bar.inp").write_text(deck.text())

    displacements = calculix.dat_block("bar.dat", "displacements")   # [[node, ux, uy, uz], ...]
"""
import os
import pathlib

import numpy as np

# ccx reads at most 16 entries a data line; an element goes on after a comma, on the next line.
ENTRIES_PER_LINE = 16


def ccx_environment(threads, base=None):
    """The environment the calculix wrapper runs ccx in (solver_wrappers/calculix/ccx_run.cpp's
    ccx_thread_environment), on top of `base` (default os.environ): `threads` of ccx's own, and
    one each for CHOLMOD's OpenMP and OpenBLAS, which otherwise oversubscribe the machine
    (docs/solver-wrappers-calculix.md)."""
    count = str(threads)
    base = os.environ if base is None else base
    # malloc asks for transparent huge pages: a fifth fewer page faults' time (ccx_run.cpp).
    tunables = ":".join(t for t in (base.get("GLIBC_TUNABLES", ""), "glibc.malloc.hugetlb=1") if t)
    return dict(base, OMP_NUM_THREADS=count,
                OMP_THREAD_LIMIT="1", OPENBLAS_NUM_THREADS="1",
                CCX_NPROC_EQUATION_SOLVER=count, CCX_NPROC_RESULTS=count,
                CCX_NPROC_STIFFNESS=count, GLIBC_TUNABLES=tunables)


def number(value):
    """A deck's number: ccx reads numbers from 20-character fields, and 13 significant digits
    fit. Text (e.g. "0.") is written as it is."""
    return value if isinstance(value, str) else f"{value:.13g}"


class Deck:
    """The lines of a CalculiX input deck; text() is the deck. `lines` (comments such as
    "** what this is", or cards) start it."""

    def __init__(self, *lines):
        self.lines = list(lines)

    def add(self, *lines):
        """Cards and data lines as they are (*MATERIAL, *STEP, ...)."""
        self.lines.extend(lines)

    def nodes(self, nodes, nset="NALL"):
        """*NODE: one line per (id, coordinate, ...), coordinates as `number` writes them."""
        self.lines.append(f"*NODE, NSET={nset}")
        self.lines.extend(", ".join([str(node)] + [number(c) for c in coordinates])
                          for node, *coordinates in nodes)

    def elements(self, kind, elements, elset="EALL"):
        """*ELEMENT of TYPE `kind`: per (id, node ids), lines of at most 16 entries, each but the
        last ending in a comma (C3D20: the id and 15 nodes, then 5)."""
        self.lines.append(f"*ELEMENT, TYPE={kind}, ELSET={elset}")
        for element, node_ids in elements:
            entries = [str(element)] + [str(n) for n in node_ids]
            self.lines.append(",\n".join(", ".join(entries[start:start + ENTRIES_PER_LINE])
                                         for start in range(0, len(entries), ENTRIES_PER_LINE)))

    def node_set(self, name, node_ids):
        self.lines.append(f"*NSET, NSET={name}")
        self.lines.extend(f"{node}," for node in node_ids)

    def element_set(self, name, element_ids):
        self.lines.append(f"*ELSET, ELSET={name}")
        self.lines.extend(f"{element}," for element in element_ids)

    def surface(self, name, faces):
        """An element face surface: one (element id, face such as "S2") per line."""
        self.lines.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        self.lines.extend(f"{element}, {face}" for element, face in faces)

    def text(self):
        return "\n".join(self.lines) + "\n"


# --- what ccx writes ------------------------------------------------------------------------

def dat_blocks(path, title):
    """Every block in a ccx .dat file whose header starts with `title` (e.g. "displacements"
    for a *NODE PRINT of U, "stresses" for an *EL PRINT of S), in the file's order: one list of
    numbers per line, the node (or element and integration point) first; the L with which ccx
    marks values in a transformed system is dropped."""
    blocks, inside = [], False
    with open(path) as f:
        for line in f:
            if line.startswith(" " + title):
                blocks.append([])
                inside = True
            elif inside and line.strip():
                blocks[-1].append([float(v) for v in line.split() if v != "L"])
            elif inside and blocks[-1]:
                inside = False
    return blocks


def dat_block(path, title):
    """The last of dat_blocks(path, title), or None if the file has no such block."""
    blocks = dat_blocks(path, title)
    return blocks[-1] if blocks else None


class Frd:
    """The node coordinates and the last result block of each name (DISP, STRESS, PE, FORC) of
    one .frd file; `values(name)` is indexed like `ids` and `coordinates`."""

    def __init__(self, path, names=None):
        """Read `path`; `names` (e.g. {"FORC"}) limits the result blocks read, for speed."""
        self.path = pathlib.Path(path)
        nodes, blocks = {}, {}
        with open(self.path) as f:
            lines = iter(f)
            for line in lines:
                if line.startswith("    2C"):
                    nodes.update(_frd_rows(lines, 3))
                elif line.startswith(" -4"):
                    name = line[5:13].strip()
                    wanted = names is None or name in names
                    rows = _frd_rows(lines, None, keep=wanted)
                    if wanted:
                        blocks[name] = rows
        if not nodes:
            raise ValueError(f"{self.path}: no node coordinates (is it a CalculiX .frd file?)")
        self.ids = np.array(sorted(nodes))
        self.coordinates = np.array([nodes[i] for i in self.ids])
        self._blocks = blocks

    def values(self, name):
        if name not in self._blocks:
            raise KeyError(f"{self.path}: no {name} block (request it in *NODE FILE or *EL FILE)")
        rows = self._blocks[name]
        width = len(next(iter(rows.values())))
        return np.array([rows.get(i, [np.nan] * width) for i in self.ids])


def _frd_rows(lines, count, keep=True):
    """{node: values} of the " -1" lines of an .frd block, up to its " -3" line: fixed columns,
    a node number of 10 characters after 3, then values of 12 (`count` of them, or as many as
    the line holds)."""
    rows = {}
    for line in lines:
        if line.startswith(" -3"):
            break
        if keep and line.startswith(" -1"):
            width = count or (len(line.rstrip("\n")) - 13) // 12
            rows[int(line[3:13])] = [float(line[13 + 12 * k:25 + 12 * k]) for k in range(width)]
    return rows


# --- reading a deck -------------------------------------------------------------------------

def _data_lines(text, card):
    """The data lines of every card of a deck named `card` (e.g. "*NODE"; not *NODE PRINT);
    comment lines (**) are skipped."""
    inside = False
    for line in text.splitlines():
        if line.startswith("**"):
            continue
        if line.startswith("*"):
            inside = line.split(",")[0].strip().upper() == card
            continue
        if inside and line.strip():
            yield line


def deck_nodes(text):
    """Node id -> [x, y, z] of a deck's *NODE cards (a missing z is 0)."""
    nodes = {}
    for line in _data_lines(text, "*NODE"):
        fields = [float(v) for v in line.split(",") if v.strip()]
        nodes[int(fields[0])] = (fields[1:] + [0.0, 0.0])[:3]
    return nodes


def deck_elements(text):
    """Element id -> node ids of a deck's *ELEMENT cards; a data line ending in a comma
    continues on the next."""
    elements, ids = {}, []
    for line in _data_lines(text, "*ELEMENT"):
        ids += [int(v) for v in line.replace(",", " ").split()]
        if not line.rstrip().endswith(","):
            elements[ids[0]], ids = ids[1:], []
    return elements
