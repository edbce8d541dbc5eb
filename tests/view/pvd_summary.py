"""Run by ParaView's Python (pvpython, or python3 with python3-paraview): loads a .pvd series with
paraview.simple.PVDReader and prints, per time step, what ParaView read back as JSON, for
tests/view/check_pvd.py (issue #25, item 3). Usage: pvpython pvd_summary.py FILE.pvd
"""
import json
import math
import sys

from paraview import servermanager
from paraview.simple import PVDReader
from vtkmodules.util.numpy_support import vtk_to_numpy


def strings(field, name):
    a = field.GetAbstractArray(name)
    return None if a is None else [a.GetValue(i) for i in range(a.GetNumberOfValues())]


def cell_points(block, c):
    ids = block.GetCell(c).GetPointIds()
    return [ids.GetId(i) for i in range(ids.GetNumberOfIds())]


def bodies_summary(block):
    cd, pd = block.GetCellData(), block.GetPointData()
    cell_arrays = {cd.GetArrayName(i): vtk_to_numpy(cd.GetArray(i)) for i in range(cd.GetNumberOfArrays())}
    depth = vtk_to_numpy(pd.GetArray("penetration_depth")) if pd.GetArray("penetration_depth") else None
    points = vtk_to_numpy(block.GetPoints().GetData()) if block.GetNumberOfPoints() else None
    per_body = {}
    for c in range(block.GetNumberOfCells()):
        b = int(cell_arrays["body"][c])
        e = per_body.setdefault(b, {"cells": 0, "cell_type": set(), "points": set(), "clash_flagged": 0, "source_ids": []})
        e["cells"] += 1
        e["cell_type"].add(block.GetCellType(c))
        e["points"].update(cell_points(block, c))
        e["clash_flagged"] += int(cell_arrays["clash"][c] != 0)
        if "source_id" in cell_arrays:
            e["source_ids"].append(int(cell_arrays["source_id"][c]))
    out = {}
    for b, e in per_body.items():
        pts = sorted(e["points"])
        lo = [float(min(points[p][k] for p in pts)) for k in range(3)]
        hi = [float(max(points[p][k] for p in pts)) for k in range(3)]
        d = None
        if depth is not None:
            known = [float(depth[p]) for p in pts if not math.isnan(depth[p])]
            d = [min(known), max(known)] if known else None
        out[b] = {"cells": e["cells"], "cell_types": sorted(e["cell_type"]), "box": [lo, hi], "clash_flagged": e["clash_flagged"],
                  "source_ids": e["source_ids"], "depth_range": d}
    return {"points": block.GetNumberOfPoints(), "cells": block.GetNumberOfCells(), "cell_arrays": sorted(cell_arrays),
            "point_arrays": [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())],
            "body_names": strings(block.GetFieldData(), "body_names"), "body_ids": strings(block.GetFieldData(), "body_ids"),
            "per_body": out}


def clashes_summary(block):
    cd = block.GetCellData()
    arrays = {cd.GetArrayName(i): vtk_to_numpy(cd.GetArray(i)) for i in range(cd.GetNumberOfArrays())}
    per_clash = {}
    for c in range(block.GetNumberOfCells()):
        k = int(arrays["clash_index"][c])
        e = per_clash.setdefault(k, {"region_triangles": 0, "curve_points": [], "witness_points": [], "verdicts": set(), "clash_flagged": 0})
        g = int(arrays["geometry"][c])
        n = len(cell_points(block, c))
        if g == 0:
            e["region_triangles"] += int(block.GetCellType(c) == 5 and n == 3)  # VTK_TRIANGLE
        elif g == 1:
            e["curve_points"].append(n)
        else:
            e["witness_points"].append(n)
        e["verdicts"].add(int(arrays["verdict"][c]))
        e["clash_flagged"] += int(arrays["clash"][c] != 0)
    for e in per_clash.values():
        e["verdicts"] = sorted(e["verdicts"])
    return {"points": block.GetNumberOfPoints(), "cells": block.GetNumberOfCells(), "cell_arrays": sorted(arrays),
            "clash_ids": strings(block.GetFieldData(), "clash_ids"), "verdict_names": strings(block.GetFieldData(), "verdict_names"),
            "per_clash": per_clash}


def main():
    reader = PVDReader(FileName=sys.argv[1])
    tv = reader.TimestepValues  # a list, a single number for one step, or empty
    times = [] if tv is None else [float(tv)] if isinstance(tv, (int, float)) else [float(t) for t in tv]
    steps = []
    for t in times or [0.0]:
        reader.UpdatePipeline(t)
        data = servermanager.Fetch(reader)
        step = {"time": t}
        it = data.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            block = it.GetCurrentDataObject()
            if block.GetFieldData().GetAbstractArray("body_names") is not None:
                step["bodies"] = bodies_summary(block)
            elif block.GetFieldData().GetAbstractArray("clash_ids") is not None:
                step["clashes"] = clashes_summary(block)
            it.GoToNextItem()
        steps.append(step)
    print("PVD_SUMMARY " + json.dumps({"times": times, "steps": steps}))


main()
