#!/usr/bin/env python3
"""A scene whose bodies use every field the interfere-mpi body records abbreviate behind flags (review
of 8b228c5, issue #31: id equal to the entry's or not, name equal to the id or not, path '/'+name,
equal to the name, or other, file as given with '..' and './', identity pose bit for bit or with
-0.0 / a tiny translation, tags, units other than mm, names/paths/tags with quotes, backslashes,
newlines and non-ASCII that mimic the report's own layout), repeated meshes in equal relative poses (units
joined into classes: core_runs) and in different ones. Usage: review_make_metadata_scene.py OUT_DIR"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_scenes  # noqa: E402


def main(out):
    os.makedirs(os.path.join(out, "parts", "sub"), exist_ok=True)
    make_scenes.write_stl(os.path.join(out, "parts", "box.stl"), make_scenes.box((0, 0, 0), (1, 1, 1)))
    make_scenes.write_stl(os.path.join(out, "parts", "plate.stl"), make_scenes.box((0, 0, 0), (10, 10, 1)))
    make_scenes.write_stl(os.path.join(out, "parts", "ball.stl"), make_scenes.sphere((0, 0, 0), 0.8, 12, 8))
    I = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0]
    bodies = [
        {"file": "parts/plate.stl", "id": "plate"},                                           # all defaults
        {"file": "parts/box.stl", "id": "bolt-1", "name": "Bolt", "path": "/Asm/Fasteners/Bolt",
         "transform": [1, 0, 0, 0.5, 0, 1, 0, 0.5, 0, 0, 1, 0.5], "tags": ["fastener", "m6"]},
        {"file": "parts/box.stl", "id": "bolt-2", "name": "bolt-2", "path": "bolt-2",          # name == id, path == name
         "transform": [1, 0, 0, 3.5, 0, 1, 0, 0.5, 0, 0, 1, 0.5], "tags": ["fastener"]},
        {"file": "./parts/sub/../box.stl", "id": "bolt-3", "name": "B3", "path": "/B3",       # path == '/' + name, odd file
         "transform": [1, 0, 0, 6.5, 0, 1, 0, 0.5, 0, 0, 1, 0.75]},
        {"file": "parts/box.stl", "id": "zero", "transform": [1, -0.0, 0, -0.0, 0, 1, 0, 0, 0, 0, 1, 0]},  # -0.0: not the identity bit for bit
        {"file": "parts/box.stl", "id": "tiny", "transform": [1, 0, 0, 1e-60, 0, 1, 0, 0, 0, 0, 1, 0]},
        {"file": "parts/box.stl", "id": "ident", "transform": I},
        {"file": "parts/ball.stl", "id": "ball-in", "units": "in", "transform": [1, 0, 0, 0.3, 0, 1, 0, 0.3, 0, 0, 1, 0.1],
         "tags": ["ball"]},                                                                       # inches: 25.4 x
        {"file": "parts/ball.stl", "id": "ball", "name": "ball", "path": "/ball", "transform": [0, -1, 0, 8, 1, 0, 0, 8, 0, 0, 1, 1.2]},
        {"file": "parts/box.stl", "id": "odd", "name": "Bolt \"M6\" \\ \u00fcn\u00ef\n  \"triangles\": 7,", "path": "/A/\"q\"/\t",
         "transform": [1, 0, 0, 8.2, 0, 1, 0, 8.2, 0, 0, 1, 0.9], "tags": ["t,1", "\"x\""]},   # text the report edit must not trip on
    ]
    tests = [{"name": "hard", "a": ["all"], "mode": "hard"},
             {"name": "near", "a": ["tag:fastener"], "b": ["id:plate"], "mode": "clearance", "clearance": 0.4}]
    with open(os.path.join(out, "scene.json"), "w") as f:
        json.dump({"units": "mm", "bodies": bodies, "tests": tests}, f, indent=1)


if __name__ == "__main__":
    main(sys.argv[1])
