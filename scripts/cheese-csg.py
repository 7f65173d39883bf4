#!/usr/bin/env python3
"""Writes a cheese as an OpenSCAD .csg file: a 10-unit cube minus K spheres
(radius 0.6 to 1.4, $fn = 32) centred anywhere in it or just outside, from a
seeded generator, the shape of strata-bench's cheese scene (its own random
numbers, not the same spheres). For whole-process benchmarks that need a file.

    scripts/cheese-csg.py K [SEED] > cheese.csg
"""
import random
import sys


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: scripts/cheese-csg.py K [SEED] > cheese.csg")
    k = int(sys.argv[1])
    rng = random.Random(int(sys.argv[2]) if len(sys.argv) == 3 else 1)
    out = ["difference() {", "\tcube(size = [10, 10, 10], center = false);"]
    for _ in range(k):
        x, y, z = (rng.uniform(-0.5, 10.5) for _ in range(3))
        r = rng.uniform(0.6, 1.4)
        out.append("\tmultmatrix([[1, 0, 0, %.6g], [0, 1, 0, %.6g], [0, 0, 1, %.6g], [0, 0, 0, 1]]) {" % (x, y, z))
        out.append("\t\tsphere($fn = 32, $fa = 12, $fs = 2, r = %.6g);" % r)
        out.append("\t}")
    out.append("}")
    print("\n".join(out))


if __name__ == "__main__":
    main()
