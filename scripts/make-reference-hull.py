"""Writes graphs/reference/catamaran-hull.obj: the reference hull the catamaran gallery graph fits
its cone-net to — a smooth analytic hull drawn independently of the cone-net construction (as a
designer would model one elsewhere), both halves, as an OBJ of quads.

Stations along the length (keel depth, deck height, half breadth at the deck) are interpolated
with a Catmull-Rom spline; each section is y = b(u) * t^0.55, z = keel(u) + (deck(u) - keel(u)) * t
with t from keel (0) to deck (1), and the bow and stern are rounded a little more than the cone-net
can follow. Deterministic: the same file every run. Usage: python3 scripts/make-reference-hull.py
"""
import math
import os

# u (0 stern .. 1 bow), keel z, deck z, half breadth at the deck
STATIONS = [
    (0.0, 0.05, 2.0, 1.15),
    (0.1, -0.95, 2.0, 1.75),
    (0.2, -1.35, 2.01, 2.0),
    (0.3, -1.58, 2.02, 2.16),
    (0.4, -1.68, 2.03, 2.24),
    (0.5, -1.62, 2.05, 2.22),
    (0.6, -1.40, 2.07, 2.10),
    (0.7, -0.95, 2.11, 1.86),
    (0.8, -0.20, 2.20, 1.48),
    (0.9, 0.85, 2.38, 0.95),
    (1.0, 2.10, 2.60, 0.30),
]
LENGTH = 20.0
ALONG = 60  # quads along the length
DOWN = 16  # quads from keel to deck


def catmull_rom(values, u):
    """Uniform Catmull-Rom through values sampled at u = k / (n - 1)."""
    n = len(values)
    s = u * (n - 1)
    k = min(int(s), n - 2)
    f = s - k
    p0 = values[max(k - 1, 0)]
    p1 = values[k]
    p2 = values[k + 1]
    p3 = values[min(k + 2, n - 1)]
    return 0.5 * (
        2 * p1 + (-p0 + p2) * f + (2 * p0 - 5 * p1 + 4 * p2 - p3) * f * f + (-p0 + 3 * p1 - 3 * p2 + p3) * f ** 3
    )


def point(u, t, side):
    keel = catmull_rom([s[1] for s in STATIONS], u)
    deck = catmull_rom([s[2] for s in STATIONS], u)
    breadth = catmull_rom([s[3] for s in STATIONS], u)
    x = LENGTH * u + 0.35 * math.sin(math.pi * u) * (1.0 - t)  # the keel line leans a little aft
    y = side * breadth * t ** 0.55
    z = keel + (deck - keel) * t
    return (x, y, z)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = os.path.join(root, "graphs", "reference", "catamaran-hull.obj")
    lines = ["# cnets reference hull: an analytic hull (scripts/make-reference-hull.py), both halves"]
    index = {}
    written = 0
    for side, name in ((1, "starboard"), (-1, "port")):
        lines.append("o " + name)
        for i in range(ALONG + 1):
            for k in range(DOWN + 1):
                key = (side, i, k)
                # The keel line (t = 0) is shared by both halves.
                if k == 0 and side == -1:
                    index[key] = index[(1, i, 0)]
                    continue
                x, y, z = point(i / ALONG, k / DOWN, side)
                lines.append("v %.9f %.9f %.9f" % (x, y, z))
                written += 1
                index[key] = written
        for i in range(ALONG):
            for k in range(DOWN):
                a, b = index[(side, i, k)], index[(side, i + 1, k)]
                c, d = index[(side, i + 1, k + 1)], index[(side, i, k + 1)]
                quad = (a, b, c, d) if side == 1 else (a, d, c, b)
                lines.append("f %d %d %d %d" % quad)
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", out)


if __name__ == "__main__":
    main()
