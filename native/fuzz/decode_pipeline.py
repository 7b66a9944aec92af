#!/usr/bin/env python3
"""Prints what fuzz_pipeline makes of an input: the options, the points with their radii, the edges, and the
longest edge and whole length in radii. Mirrors the decoding in fuzz_pipeline.cpp.
  native/fuzz/decode_pipeline.py FILE..."""
import math
import struct
import sys

SPECIAL = [0.0, -0.0, 1e300, -1e300, 1e-300, -1e-300, 5e-324, 2.2250738585072009e-308, 1.7976931348623157e308,
           -1.7976931348623157e308, 2.2250738585072014e-308, 1e308, 1e154, 1e-154, 2e8, -2e8, 1e8, -1e8, 1e15, -1e15,
           1e-15, 1e-8, 1e-12, 1e6, 1e-6, 1e12, 1e20, 1e-20, 1e100, 1e-100, 1 + 2.220446049250313e-16,
           1 - 1.1102230246251565e-16, 0.5, 1.0, 2.0, 3.0, 1e3, -1e3, 1e-3, 4e9, 9007199254740992.0,
           18014398509481986.0, 2147483648.0, -2147483649.0, 1e-310, 3e-320, 65504.0, 1e10]


class Bytes:
    def __init__(self, data):
        self.data, self.pos = data, 0

    def next(self):
        if self.pos < len(self.data):
            self.pos += 1
            return self.data[self.pos - 1]
        return 0

    def value(self, radius, previous):
        s = self.next()
        if s < 0xC0:
            return (s + 8) / 32 if radius else (s - 96) / 16
        if s < 0xF0:
            return SPECIAL[s - 0xC0]
        if s < 0xF8:
            return struct.unpack("<d", bytes(self.next() for _ in range(8)))[0]
        return previous + (s - 0xFB) * 1e-7 * previous


def decode(data):
    b = Bytes(data)
    mode = b.next()
    opts = [f"levels={(mode >> 1) & 1}", "crossings=" + ("keep" if mode & 4 else "separate"),
            "caps=" + ("open" if mode & 8 else "flat"), "fit=" + ["onto", "inward", "none", "none"][(mode >> 4) & 3],
            "refinement=" + ["uniform", "curvature", "dihedral", "curvature"][(mode >> 6) & 3]]
    if mode & 1:
        print("  " + " ".join(opts) + "\n  SWC mode:\n" + data[1:].decode("latin-1"))
        return
    n_byte, flags = b.next(), b.next()
    n = 2 + n_byte % 31
    per_edge, extra = flags & 1, (flags >> 1) & 3
    opts += ["sampling=" + ("unidirectional" if flags & 8 else "bidirectional"), f"curvature={bool(flags & 16)}",
             f"root0={bool(flags & 32)}", f"uniform_levels={0 if flags & 64 else 1}",
             "radius per " + ("edge" if per_edge else "point")]
    points, radius, edges, edge_radius = [], [], [], []
    prev, prev_r = [0.0, 0.0, 0.0], 1.0
    for _ in range(n):
        p = [b.value(False, prev[k]) for k in range(3)]
        points.append(p)
        prev = p
        if not per_edge:
            prev_r = b.value(True, prev_r)
            radius.append(prev_r)
    for i in range(1, n):
        edges.append((b.next() % i, i))
    for _ in range(extra):
        edges.append((b.next() % n, b.next() % n))
    if per_edge:
        for _ in edges:
            prev_r = b.value(True, prev_r)
            edge_radius.append(prev_r)
    print("  " + " ".join(opts))
    for i, p in enumerate(points):
        print(f"  point {i}: ({p[0]:.6g}, {p[1]:.6g}, {p[2]:.6g})" + (f" r={radius[i]:.6g}" if radius else ""))
    worst, total = 0.0, 0.0
    for e, (a, c) in enumerate(edges):
        try:
            length = math.dist(points[a], points[c])
        except (OverflowError, ValueError):
            length = math.inf
        r = edge_radius[e] if per_edge else min(radius[a], radius[c])
        ratio = length / r if r > 0 else math.inf
        total += length if math.isfinite(length) else math.inf
        worst = max(worst, ratio) if not math.isnan(ratio) else worst
        print(f"  edge {a}-{c}: length {length:.6g}" + (f" r={edge_radius[e]:.6g}" if per_edge else "") +
              f" ({ratio:.3g} radii)")
    print(f"  longest edge {worst:.3g} radii")


for path in sys.argv[1:]:
    print(path)
    decode(open(path, "rb").read())
