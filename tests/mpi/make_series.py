#!/usr/bin/env python3
"""Generated time series for `interfere-mpi clash --distribute frames` (issue #31, item 3; docs/mpi.md,
"Time series"), from make_scenes.py's scenes (deterministic).

  tiny/            make_scenes.py's 75 tiny bodies, with two motions:
    motion.csv          make_scenes.py's 6 frames: t001, t007 and touch_a slide, so their clashes move
                        on the bodies and keep their ids from frame 0 on (the blocks' borders are run
                        again from further back);
    cluster.csv         12 frames: clusters 0 and 5 (6 bodies each) move rigidly, each as a whole,
                        cluster 0 towards cluster 1 (their pairs' clashes stay where they are on the
                        bodies: the ids need no history), touch_a slides off touch_b, alone moves.
  fe12/            make_scenes.py's FE model with 12 displacement steps beside 3 STL boxes.
Usage: make_series.py OUT_DIR
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_scenes  # noqa: E402


def cluster_motion(path, frames=12):
    with open(path, "w") as f:
        f.write("frame,time,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n")
        for fr in range(frames):
            moves = [("t%03d" % n, (0.3 * fr, 0.0, 0.0)) for n in range(0, 6)]       # cluster 0, towards cluster 1
            moves += [("t%03d" % n, (0.0, 0.0, 0.2 * fr)) for n in range(30, 36)]   # cluster 5, up
            moves += [("touch_a", (-0.05 * fr, 0.0, 0.0)), ("alone", (0.0, 1.0 * fr, 0.0))]
            for b, (dx, dy, dz) in moves:
                f.write("%d,%g,%s,1,0,0,%g,0,1,0,%g,0,0,1,%g\n" % (fr, 0.1 * fr, b, dx, dy, dz))


if __name__ == "__main__":
    out = sys.argv[1]
    make_scenes.tiny(os.path.join(out, "tiny"))
    cluster_motion(os.path.join(out, "tiny", "cluster.csv"))
    make_scenes.fe(os.path.join(out, "fe12"), steps=12)
