#!/usr/bin/env python3
"""Adversarial time series for `interfere-mpi clash --distribute frames` (review of 92c0a27, issue #31,
item 3): clashes placed at the blocks' borders for every K, so that the border check and the reruns
are exercised where they are weakest. Deterministic.

  border/scene.json + motion9.csv (9 frames), motion3.csv and motion1.csv (3 frames and 1, for K > frames):
    wall      10 x 10 x 1 plate, static.
    slider    1 mm cube sliding along the wall's top 0.6 mm a frame (a clash that moves on both
              bodies every frame: its id is carried from frame 0 to the end, so every border needs
              history and the reruns chain back to frame 0).
    blink     a cube that enters the wall in frame 4 only (a clash of one frame, at a border for
              some K).
    twice     a cube in the wall in frames 2 and 5 only, at the same place (one id, two separate
              frames: merged by id across blocks).
    comb      one body with two prongs 2 mm apart, moved 1.2 mm a frame through plate2 (two clashes
              of one pair whose nearest-location matching crosses: the prong that moved is nearer
              the other prong's previous clash).
    toucher   a cube touching the wall's side, then pressed 0.2 mm in, then touching again, then
              apart, alternating every frame (the verdict, part of the id, changes at borders).
    plate2    10 x 10 x 1 plate, static, at y = 20.
Usage: review_make_border_series.py OUT_DIR
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_scenes  # noqa: E402


def cube(c, h):
    return make_scenes.box((c[0] - h, c[1] - h, c[2] - h), (c[0] + h, c[1] + h, c[2] + h))


def main(out):
    d = os.path.join(out, "border")
    os.makedirs(d, exist_ok=True)
    w = make_scenes.write_stl
    w(os.path.join(d, "wall.stl"), make_scenes.box((0, 0, 0), (10, 10, 1)))
    w(os.path.join(d, "plate2.stl"), make_scenes.box((0, 20, 0), (10, 30, 1)))
    w(os.path.join(d, "slider.stl"), cube((0.7, 2.3, 1.2), 0.5))       # 0.3 mm into the wall's top
    w(os.path.join(d, "blink.stl"), cube((5.2, 5.3, 1.3), 0.5))        # 0.2 mm in, when at z offset 0
    w(os.path.join(d, "twice.stl"), cube((8.1, 8.2, 1.35), 0.5))
    w(os.path.join(d, "comb.stl"), cube((1.1, 24.9, 0.5), 0.3) + cube((3.1, 24.9, 0.5), 0.3))
    w(os.path.join(d, "toucher.stl"), make_scenes.box((10, 4, 0.2), (11, 5, 0.8)))  # touching the wall's x = 10 side
    bodies = [{"file": n + ".stl", "id": n} for n in ("wall", "plate2", "slider", "blink", "twice", "comb", "toucher")]
    tests = [{"name": "hard", "a": ["all"], "mode": "hard"},
             {"name": "gap", "a": ["id:toucher", "id:slider"], "b": ["id:wall"], "mode": "clearance", "clearance": 0.5}]
    make_scenes.scene(os.path.join(d, "scene.json"), bodies, tests)

    def motion(path, frames):
        with open(path, "w") as f:
            f.write("frame,time,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n")
            for fr in range(frames):
                moves = [("slider", (0.6 * fr, 0.0, 0.0)),
                         ("blink", (0.0, 0.0, 0.0 if fr == 4 else 5.0)),
                         ("twice", (0.0, 0.0, 0.0 if fr in (2, 5) else 5.0)),
                         ("comb", (1.2 * fr, 0.0, 0.0)),
                         ("toucher", (-0.2 * (fr % 4 == 1) + 0.3 * (fr % 4 == 3), 0.0, 0.0))]
                for b, (dx, dy, dz) in moves:
                    f.write("%d,%g,%s,1,0,0,%.17g,0,1,0,%.17g,0,0,1,%.17g\n" % (fr, 0.1 * fr, b, dx, dy, dz))

    motion(os.path.join(d, "motion9.csv"), 9)
    motion(os.path.join(d, "motion3.csv"), 3)
    motion(os.path.join(d, "motion1.csv"), 1)


if __name__ == "__main__":
    main(sys.argv[1])
