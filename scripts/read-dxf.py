"""Reads a DXF file with the independent `ezdxf` reader and prints what it found as JSON.

Used by the Rust export tests (crates/nodes/tests/it/export_dxf_ezdxf.rs) to prove that other tools open
the DXF files cnets writes. Usage: python3 scripts/read-dxf.py FILE.dxf
Exit 0 with the JSON report; exit 2 when ezdxf is missing or the file cannot be read.
"""
import json
import sys

try:
    import ezdxf
except ImportError as e:  # pragma: no cover - reported to the Rust test
    sys.stderr.write("ezdxf is not installed: run scripts/install-test-deps.sh (%s)\n" % e)
    sys.exit(2)


def read_entities(layout):
    """The LWPOLYLINE and TEXT entities of a layout or block: layer, closed flag, points; text."""
    polylines = []
    for e in layout.query("LWPOLYLINE"):
        polylines.append(
            {
                "layer": e.dxf.layer,
                "closed": bool(e.closed),
                "points": [[p[0], p[1]] for p in e.get_points("xy")],
            }
        )
    texts = []
    for e in layout.query("TEXT"):
        texts.append(
            {
                "layer": e.dxf.layer,
                "text": e.dxf.text,
                "insert": [e.dxf.insert[0], e.dxf.insert[1]],
            }
        )
    return polylines, texts


def main() -> None:
    if len(sys.argv) != 2:
        sys.stderr.write("usage: python3 scripts/read-dxf.py FILE.dxf\n")
        sys.exit(2)
    try:
        doc = ezdxf.readfile(sys.argv[1])
    except (IOError, ezdxf.DXFStructureError) as e:
        sys.stderr.write("ezdxf could not read the file: %s\n" % e)
        sys.exit(2)
    auditor = doc.audit()
    msp = doc.modelspace()
    polylines, texts = read_entities(msp)
    # Named blocks (one per nested sheet) with their entities, and where model space inserts them.
    blocks = []
    for block in doc.blocks:
        if block.name.startswith("*"):
            continue
        block_polylines, block_texts = read_entities(block)
        base = block.block.dxf.base_point
        blocks.append(
            {
                "name": block.name,
                "base": [base[0], base[1]],
                "lwpolylines": block_polylines,
                "texts": block_texts,
            }
        )
    inserts = [
        {"name": e.dxf.name, "insert": [e.dxf.insert[0], e.dxf.insert[1]], "layer": e.dxf.layer}
        for e in msp.query("INSERT")
    ]
    report = {
        "ezdxf": ezdxf.__version__,
        "dxfversion": doc.dxfversion,
        "insunits": doc.header.get("$INSUNITS", None),
        "layers": sorted(layer.dxf.name for layer in doc.layers),
        "audit_errors": len(auditor.errors),
        "audit_fixes": len(auditor.fixes),
        "audit_messages": [str(f.message) for f in list(auditor.errors) + list(auditor.fixes)],
        "measurement": doc.header.get("$MEASUREMENT", None),
        "extmin": list(doc.header.get("$EXTMIN", (0, 0, 0)))[:2] if "$EXTMIN" in doc.header else None,
        "extmax": list(doc.header.get("$EXTMAX", (0, 0, 0)))[:2] if "$EXTMAX" in doc.header else None,
        "entity_types": sorted({e.dxftype() for e in msp}),
        "lwpolylines": polylines,
        "texts": texts,
        "blocks": blocks,
        "inserts": inserts,
    }
    sys.stdout.write(json.dumps(report))


if __name__ == "__main__":
    main()
