"""Writes a DXF test drawing with the independent `ezdxf` writer: one entity of every kind that
`io.read_polylines` reads (LINE, LWPOLYLINE with a bulge, 3D POLYLINE, ARC, CIRCLE, ELLIPSE, SPLINE,
and an ARC in a tilted object coordinate system), plus a TEXT that is not a curve.

Used by crates/nodes/tests/it/read_polylines_dxf.rs. Usage: python3 scripts/write-dxf.py OUT.dxf
Exit 2 when ezdxf is missing.
"""
import math
import sys

try:
    import ezdxf
except ImportError as e:  # pragma: no cover - reported to the Rust test
    sys.stderr.write("ezdxf is not installed: run scripts/install-test-deps.sh (%s)\n" % e)
    sys.exit(2)


def main() -> None:
    if len(sys.argv) != 2:
        sys.stderr.write("usage: python3 scripts/write-dxf.py OUT.dxf\n")
        sys.exit(2)
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    msp.add_line((0, 0, 0), (3, 4, 5))
    # A 2 x 1 rectangle whose top edge is a half circle: bulge 1 at (2,1) makes the edge to (0,1)
    # a counter-clockwise half circle about (1,1), through (1,2).
    msp.add_lwpolyline([(0, 0, 0), (2, 0, 0), (2, 1, 1), (0, 1, 0)], format="xyb", close=True)
    msp.add_polyline3d([(0, 0, 0), (1, 0, 1), (1, 1, 2)])
    msp.add_arc(center=(5, 5, 0), radius=2, start_angle=0, end_angle=90)
    msp.add_circle(center=(-5, 0, 0), radius=1.5)
    msp.add_ellipse(center=(0, -5, 0), major_axis=(3, 0, 0), ratio=0.5)
    # A clamped cubic B-spline through its end control points.
    msp.add_open_spline([(0, 0, 0), (1, 2, 0), (3, 2, 0), (4, 0, 0)], degree=3)
    # An arc in the plane x = 10 (extrusion +x): centre given in object coordinates.
    msp.add_arc(center=(0, 0, 10), radius=1, start_angle=0, end_angle=180, dxfattribs={"extrusion": (1, 0, 0)})
    msp.add_text("not a curve")
    doc.saveas(sys.argv[1])


if __name__ == "__main__":
    main()
