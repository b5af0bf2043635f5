"""The shipped library (graphs/library): each reusable cluster does what its description says,
every port is documented, and the command line lists them (`cnets nodes --library`). Hops serves
them (test_hops.py::test_the_shipped_library_is_served); the editor's palette shows them
(crates/editor/tests/library_components.rs)."""

import json
import re
import subprocess

import numpy as np
import pytest

import cnets
from conftest import LIBRARY, REPO, arc, lifted

COMPONENTS = {
    "strip-fabrication": (["mesh", "direction", "sheet_width", "sheet_height", "spacing", "name"],
                          ["outlines", "sheets", "utilization", "max_length_error", "svg", "dxf"]),
    "support-structure": (["directrix", "mesh", "apex", "factor", "direction"],
                          ["axes", "layer", "beams"]),
    "reference-fit": (["mesh", "reference"], ["mean_squared", "max_distance", "max_planarity"]),
    "closed-tube": (["profile", "path", "apex", "ratios"], ["mesh", "closure_gap", "max_planarity"]),
}


def _cluster(name):
    return f"cluster:{LIBRARY / (name + '.ron')}"


def _net():
    """A cone-net drawn as the docs advise (the generatrix off the directrix)."""
    d = arc(12, degrees=90.0)
    return d, cnets.construct(d, lifted(6), apex=0.95, ratios=np.linspace(0.45, 0.55, 11))


def _planarity(quads):
    """The libigl planarity of quads (K, 4, 3)."""
    d1, d2 = quads[:, 2] - quads[:, 0], quads[:, 3] - quads[:, 1]
    n = np.cross(d1, d2)
    dist = np.abs(np.einsum("ij,ij->i", quads[:, 1] - quads[:, 0], n)) / np.linalg.norm(n, axis=1)
    return dist / ((np.linalg.norm(d1, axis=1) + np.linalg.norm(d2, axis=1)) / 2)


@pytest.mark.parametrize("name", sorted(COMPONENTS))
def test_every_component_documents_its_ports(name):
    interface = cnets._cnets.node_interface(_cluster(name))
    inputs, outputs = COMPONENTS[name]
    assert [p["name"] for p in interface["inputs"]] == inputs
    assert [p["name"] for p in interface["outputs"]] == outputs
    assert len(interface["doc"]) > 80, "the graph's description says what it is for"
    for port in interface["inputs"] + interface["outputs"]:
        assert len(port["doc"]) > 20 and port["doc"] != port["name"], port


def test_strip_fabrication_unrolls_nests_and_writes_sheets(tmp_path):
    _, net = _net()
    out = cnets.eval(_cluster("strip-fabrication"), mesh=net, sheet_width=12.0, sheet_height=2.0,
                     spacing=0.02, name="facade-strips", _out=tmp_path)
    assert len(out["outlines"]) == 5, "one strip between each pair of neighbouring rows"
    assert out["max_length_error"] <= 1e-9, "every edge keeps its length"
    assert len(out["sheets"]) == 5 and 0 < out["utilization"] <= 1
    for outline in out["outlines"]:
        assert outline.closed and np.all(outline.points[:, 2] == 0.0)
        extent = np.ptp(outline.points[:, :2], axis=0)
        assert extent[0] <= 12.0 and extent[1] <= 2.0, "each strip fits its sheet"
    svg, dxf = tmp_path / "facade-strips.svg", tmp_path / "facade-strips.dxf"
    assert out["svg"] == str(svg) and out["dxf"] == str(dxf)
    assert "D0" in svg.read_text() and "D4" in svg.read_text()
    assert "LWPOLYLINE" in dxf.read_text()
    by_columns = cnets.eval(_cluster("strip-fabrication"), mesh=net, direction="generatrix",
                            sheet_width=12.0, sheet_height=2.0, _out=tmp_path / "columns")
    assert len(by_columns["outlines"]) == 11


def test_support_structure_axes_layer_and_beams():
    d, net = _net()
    out = cnets.eval(_cluster("support-structure"), directrix=d, mesh=net, apex=net.apex, factor=0.85)
    axes, layer, beams = out["axes"], out["layer"], out["beams"]
    n, m = net.vertices.shape[:2]
    assert axes.shape == (n * m, 2, 3)
    np.testing.assert_array_equal(axes[:, 1], net.vertices.reshape(-1, 3))
    np.testing.assert_array_equal(axes[:, 0], np.tile(d, (n, 1)))
    # Every vertex of the second layer lies on its node axis.
    x = np.tile(d, (n, 1))
    along = np.cross(layer.vertices.reshape(-1, 3) - x, axes[:, 1] - x)
    assert np.abs(along).max() < 1e-12 * np.abs(net.vertices).max() ** 2
    assert len(beams) == m, "one beam strip per column (direction generatrix)"
    for strip in beams:
        assert strip.vertices.shape == (2, n, 3)
        assert _planarity(strip.vertices.reshape(-1, 3)[strip.faces()]).max() < 1e-9


def test_reference_fit_measures_distances_to_a_surface():
    _, net = _net()
    itself = cnets.PolygonMesh(net.vertices.reshape(-1, 3), net.faces().tolist())
    same = cnets.eval(_cluster("reference-fit"), mesh=net, reference=itself)
    # The symmetric measure samples both meshes: a mesh against itself is 0 to rounding.
    assert same["mean_squared"] < 1e-24 and same["max_distance"] < 1e-12
    assert same["max_planarity"] < 1e-12
    # A flat 5 × 4 grid at height 0 against the plane z = 0.25 over the same 4 × 3 m: every
    # point of either 0.25 from the other, both ways (mean_squared is the symmetric measure,
    # max_distance the Hausdorff distance).
    xs, ys = np.meshgrid(np.linspace(0, 4, 5), np.linspace(0, 3, 4))
    grid = np.stack([xs, ys, np.zeros_like(xs)], axis=-1)
    plane = cnets.PolygonMesh([[0, 0, 0.25], [4, 0, 0.25], [4, 3, 0.25], [0, 3, 0.25]],
                              [[0, 1, 2, 3]])
    off = cnets.eval(_cluster("reference-fit"), mesh=grid, reference=plane)
    assert off["mean_squared"] == pytest.approx(0.0625, rel=1e-12)
    assert off["max_distance"] == pytest.approx(0.25, rel=1e-12)
    # A reference larger than the net: its overhang, up to 10 m out, is measured back to the net
    # (what the one-way figure never saw).
    wide = cnets.PolygonMesh([[-10, -10, 0.25], [10, -10, 0.25], [10, 10, 0.25], [-10, 10, 0.25]],
                             [[0, 1, 2, 3]])
    over = cnets.eval(_cluster("reference-fit"), mesh=grid, reference=wide)
    assert over["max_distance"] > 9.0 and over["mean_squared"] > 1.0


def test_closed_tube_wraps_and_measures_its_closure():
    profile = cnets.eval("curve.circle", centre=(0, 0, 0), radius=0.5,
                         plane={"origin": (0, 0, 0), "normal": (1, 0, 0)}, count=10)["curve"]
    assert profile.closed
    straight = np.c_[np.linspace(0, 6, 13), np.zeros(13), np.zeros(13)]
    out = cnets.eval(_cluster("closed-tube"), profile=profile, path=straight)
    mesh = out["mesh"]
    assert mesh.wrap_rows and mesh.vertices.shape == (10, 13, 3)
    assert len(mesh.faces()) == 10 * 12, "the seam quads join the last profile point to the first"
    # A translation (apex 1, ratios ½ along a straight path): every section is the profile moved
    # along the path, so the last lies exactly the path's length from the first.
    np.testing.assert_allclose(mesh.vertices[:, -1] - mesh.vertices[:, 0],
                               np.tile([6.0, 0.0, 0.0], (10, 1)), atol=1e-12)
    assert out["closure_gap"] == pytest.approx(6.0, rel=1e-12)
    assert out["max_planarity"] < 1e-12
    # Around a closed path (the paper's Fig. 11 tube) the Monge tube misses its start; the
    # gap is measure.closure's, the quantity `cnets optimize graphs/tube-closure.ron` drives to 0.
    path = cnets.eval("curve.spline", points=[(4, 0, 0), (0, 4, 3), (-4, 0, 0), (0, -4, 3)],
                      closed=True, count=40)["curve"]
    ring = cnets.eval("curve.circle", centre=(4, 0, 0), radius=0.8,
                      plane={"origin": (4, 0, 0), "normal": (0, 2, 1)}, count=8)["curve"]
    tube = cnets.eval(_cluster("closed-tube"), profile=ring, path=path)
    gap = cnets.eval("measure.closure", mesh=tube["mesh"])["max"]
    assert tube["closure_gap"] == gap > 0.1


def test_the_command_line_lists_the_library(cnets_bin):
    result = subprocess.run([str(cnets_bin), "nodes", "--library", "graphs/library", "--json"],
                            cwd=str(REPO), capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert "warning" not in result.stderr, result.stderr
    listed = {d["id"]: d for d in json.loads(result.stdout)}
    for name, (inputs, outputs) in COMPONENTS.items():
        d = listed[f"cluster:graphs/library/{name}.ron"]
        assert [p["name"] for p in d["inputs"]] == inputs
        assert [p["name"] for p in d["outputs"]] == outputs
        assert all(p["doc"] for p in d["inputs"] + d["outputs"])
    assert "export" in listed["cluster:graphs/library/strip-fabrication.ron"]["flags"]
    text = subprocess.run([str(cnets_bin), "nodes", "--library", "graphs/library"], cwd=str(REPO),
                          capture_output=True, text=True, timeout=120).stdout
    assert len(re.findall(r"cluster:graphs/library/", text)) == 4


def test_the_command_line_runs_a_library_component(cnets_bin, tmp_path):
    """`cnets eval cluster:…` on the strip fabrication writes its sheets into --out."""
    _, net = _net()
    inputs = {"mesh": {"rows": 6, "cols": 12, "wrap_rows": False, "wrap_cols": False,
                       "vertices": net.vertices.reshape(-1, 3).tolist()},
              "sheet_width": 12.0, "sheet_height": 2.0}
    (tmp_path / "in.json").write_text(json.dumps(inputs))
    result = subprocess.run(
        [str(cnets_bin), "eval", f"cluster:{LIBRARY / 'strip-fabrication.ron'}", "--inputs",
         str(tmp_path / "in.json"), "--outputs", "utilization,svg", "--out", str(tmp_path / "out")],
        cwd=str(tmp_path), capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "out" / "strips.svg").is_file()
    assert 0 < json.loads(result.stdout)["utilization"] <= 1


def test_a_graph_without_an_interface_is_no_component():
    """A graph file with no graph.input or graph.output node is told apart by its error's type
    (Hops leaves it out of its component list by that type, not by the message's words)."""
    from cnets import _cnets

    with pytest.raises(_cnets.NoInterfaceError) as e:
        _cnets.node_interface(f"cluster:{REPO / 'graphs' / 'torus-monge.ron'}")
    assert isinstance(e.value, cnets.CnetsError)
    assert "no graph.input or graph.output" in str(e.value)
    # A graph that does not load is a plain CnetsError, not this one.
    with pytest.raises(cnets.CnetsError) as e:
        _cnets.node_interface(f"cluster:{REPO / 'graphs' / 'no-such-graph.ron'}")
    assert not isinstance(e.value, _cnets.NoInterfaceError)
