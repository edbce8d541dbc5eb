"""Structured hexahedral blocks for the FE test models (tests/cli/test_fem_inputs.py, tests/mpi/make_scenes.py):
node ids, coordinates and HEX8 connectivity in VTK/Abaqus corner order."""

CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]


def hex_box(box, n, first_node, first_elem):
    """n^3 HEX8 on box ((x0, x1), (y0, y1), (z0, z1)): ([(node id, (x, y, z))], [(element id, [8 node ids])]),
    nodes x fastest, ids counted up from first_node and first_elem, VTK/Abaqus order."""
    nodes, idx = [], {}
    for k in range(n + 1):
        for j in range(n + 1):
            for i in range(n + 1):
                idx[(i, j, k)] = first_node + len(nodes)
                nodes.append((idx[(i, j, k)], tuple(box[a][0] + (box[a][1] - box[a][0]) * (i, j, k)[a] / n for a in range(3))))
    elems = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                elems.append((first_elem + len(elems), [idx[(i + a, j + b, k + c)] for a, b, c in CORNERS]))
    return nodes, elems
