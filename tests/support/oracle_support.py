"""Shared by the numpy oracles (tests/structure/check_structure.py,
tests/fem/check_fem.py): the failures list with check(), and MEDIT .mesh
hexahedra read by tokens. Needs numpy."""
import numpy as np

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def read_medit(path):
    """MEDIT .mesh by tokens (meshio's reader wants each count on its own line)."""
    with open(path) as f:
        tokens = " ".join(line.split("#")[0] for line in f).split()
    points = hexes = None
    i = 0
    while i < len(tokens):
        word = tokens[i].lower()
        if word == "vertices":
            n = int(tokens[i + 1])
            points = np.array(tokens[i + 2:i + 2 + 4 * n], dtype=float).reshape(n, 4)[:, :3]
            i += 2 + 4 * n
        elif word == "hexahedra":
            n = int(tokens[i + 1])
            hexes = np.array(tokens[i + 2:i + 2 + 9 * n], dtype=np.int64).reshape(n, 9)[:, :8] - 1
            i += 2 + 9 * n
        else:
            i += 1
    return points, hexes
