"""Draws the first sheets of a nested DXF cutting file to a PNG with ezdxf's drawing add-on and
matplotlib, one sheet a row, for the documentation (docs/fabrication.md, worked example).

Usage: python3 scripts/draw-dxf.py FILE.dxf OUT.png WIDTH HEIGHT PITCH COUNT
WIDTH, HEIGHT: the sheet size in the drawing's units (mm); PITCH: the distance from one sheet's
left edge to the next (`fab.nest`: sheet width + gap); COUNT: how many sheets to draw. The sheet
edges are drawn in grey by this script (they are not in the DXF). Needs `ezdxf` and `matplotlib`.
"""
import sys

try:
    import ezdxf
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from ezdxf.addons.drawing import Frontend, RenderContext
    from ezdxf.addons.drawing.config import BackgroundPolicy, ColorPolicy, Configuration
    from ezdxf.addons.drawing.matplotlib import MatplotlibBackend
except ImportError as e:  # pragma: no cover
    sys.stderr.write("needs ezdxf and matplotlib (pip install ezdxf matplotlib): %s\n" % e)
    sys.exit(2)


def main() -> None:
    if len(sys.argv) != 7:
        sys.stderr.write(__doc__)
        sys.exit(2)
    path, out = sys.argv[1], sys.argv[2]
    width, height, pitch = (float(x) for x in sys.argv[3:6])
    count = int(sys.argv[6])
    doc = ezdxf.readfile(path)
    config = Configuration(
        background_policy=BackgroundPolicy.WHITE,
        color_policy=ColorPolicy.COLOR,
        min_lineweight=0.3,
    )
    fig, axes = plt.subplots(count, 1, figsize=(12, 12 * count * height / width * 1.08))
    if count == 1:
        axes = [axes]
    for s, ax in enumerate(axes):
        Frontend(RenderContext(doc), MatplotlibBackend(ax), config=config).draw_layout(
            doc.modelspace(), finalize=False
        )
        x0 = s * pitch
        ax.plot(
            [x0, x0 + width, x0 + width, x0, x0],
            [0, 0, height, height, 0],
            color="0.6",
            linewidth=0.8,
        )
        margin = 0.02 * width
        ax.set_xlim(x0 - margin, x0 + width + margin)
        ax.set_ylim(-margin, height + margin)
        ax.set_aspect("equal", adjustable="box")
        ax.axis("off")
        ax.set_title("block SHEET_%d" % (s + 1), fontsize=10, loc="left")
    fig.tight_layout()
    fig.savefig(out, dpi=110, facecolor="white")


if __name__ == "__main__":
    main()
