"""The supported coordinate range in Python (issue #23, item 7; docs/robustness.md, 'Coordinate
range'): meshes built from arrays are checked like files: 0, or 2^-250 <= |x| <= 2^100."""
import math
import unittest

import interfere as itf

TRI = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def tet(size):
    return [(0.0, 0.0, 0.0), (size, 0.0, 0.0), (0.0, size, 0.0), (0.0, 0.0, size)]


class TestCoordinateRange(unittest.TestCase):
    def test_bounds_are_accepted(self):
        itf.TriMesh(tet(2.0 ** 100), TRI)
        itf.TriMesh(tet(2.0 ** -250), TRI)

    def test_outside_is_rejected_with_the_vertex(self):
        for size, text in ((1e110, "x = 1e+110"), (math.nextafter(2.0 ** 100, math.inf), "x = 1.2676506002282297e+30"),
                           (math.nextafter(2.0 ** -250, 0.0), "x = 5.527147875260444e-76")):
            with self.assertRaises(ValueError) as ctx:
                itf.TriMesh(tet(size), TRI)
            self.assertIn("vertex 1", str(ctx.exception))
            self.assertIn(text + " is outside the supported coordinate range", str(ctx.exception))


if __name__ == "__main__":
    unittest.main()
