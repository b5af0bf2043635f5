"""Contracts that once regressed, through every door: the Python API, the `cnets` command line and
(for shapes) the graph file."""

import json
import subprocess
import sys
import textwrap

import numpy as np

import cnets
from conftest import arc, profile


def test_ctube_takes_one_normal_per_directrix_edge_shared_by_every_row(cnets_bin, tmp_path):
    d, g = arc(8), profile(5)
    m = len(d)
    # The bisecting planes (ratio ½) are shared by every row: their normals, from one row.
    shared = np.array(cnets.construct(d, g, apex=0.9, ratios=0.5).planes[0])
    # (M−1, 3) and the same normals repeated for every row, (N, M−1, 3), build the same net.
    one = cnets.ctube(d, g, apex=0.9, normals=shared)
    per_row = cnets.ctube(d, g, apex=0.9, normals=np.broadcast_to(shared, (len(g), m - 1, 3)))
    assert one.vertices.shape == (5, 8, 3)
    np.testing.assert_array_equal(one.vertices, per_row.vertices)
    # A nested list of M−1 vectors is the same shape.
    listed = cnets.ctube(d, g, apex=0.9, normals=shared.tolist())
    np.testing.assert_array_equal(listed.vertices, one.vertices)
    # The command line's answer for the same inputs, bit for bit.
    inputs = {
        "directrix": [list(map(float, p)) for p in d],
        "generatrix": [list(map(float, p)) for p in g],
        "apex": 0.9,
        "normals": shared.tolist(),
    }
    path = tmp_path / "inputs.json"
    path.write_text(json.dumps(inputs))
    out = subprocess.run(
        [str(cnets_bin), "eval", "ctube.construct", "--inputs", str(path), "--outputs", "mesh"],
        capture_output=True, text=True, check=True,
    )
    mesh = json.loads(out.stdout)["mesh"]
    cli = np.asarray(mesh["vertices"], dtype=np.float64).reshape(mesh["rows"], mesh["cols"], 3)
    np.testing.assert_array_equal(cli, one.vertices)


def test_an_explicit_budget_over_the_address_limit_is_clamped_with_a_warning(tmp_path):
    # A child process under an address-space limit of 8 000 000 kB asks for 6 GB: it is granted
    # half the limit, with a ResourceWarning naming both figures, and the evaluation runs.
    script = textwrap.dedent(
        """
        import resource, warnings
        resource.setrlimit(resource.RLIMIT_AS, (8_000_000 * 1024, resource.RLIM_INFINITY))
        import cnets
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            out = cnets.eval("math.add", a=1.0, b=2.0, _max_memory="6G")
        print(out["result"])
        print([str(w.message) for w in caught if issubclass(w.category, ResourceWarning)])
        """
    )
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         cwd=str(tmp_path))
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert float(lines[0]) == 3.0
    assert "6 GB" in lines[1] and "8.2 GB" in lines[1] and "4.1 GB" in lines[1], lines[1]
