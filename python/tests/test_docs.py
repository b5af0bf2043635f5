"""Docs that run: every fenced code block of docs/python.md and python/README.md, in order, in a
scratch folder with the repository's graphs/ at hand.

- `python` blocks run as written, one namespace per document (a block uses what an earlier one
  made). The Rhino 8 script runs against a stand-in for RhinoCommon built on rhino3dm (`Rhino`,
  `scriptcontext`), with RhinoCommon's rule that a mesh keeps doubles only with
  `UseDoublePrecisionVertices`: it checks the script's logic and that the mesh it adds holds
  cnets' doubles — not that Rhino runs it. The SLURM example runs against a stand-in
  `dask_jobqueue.SLURMCluster` that is a `LocalCluster` with 2 workers.
- `sh` blocks run line by line: `pip install …` with `--dry-run --no-build-isolation --no-index`
  (metadata built, dependencies resolved, nothing downloaded or compiled), `pip wheel` with the
  tests' build profile (it reuses the build), `python -m cnets.hops` on a free port (asked for
  its components, then stopped), `cnets` as the test build's binary. Lines that cannot run here
  are in NOT_RUN with the reason; any other line fails the test.
"""

import concurrent.futures
import os
import re
import subprocess
import sys
import textwrap
import time
import types
import urllib.request
import json

import numpy as np
import pytest

import cnets
from conftest import REPO

import rhino3dm

DOCUMENTS = [REPO / "docs" / "python.md", REPO / "python" / "README.md"]

NOT_RUN = {
    r"%USERPROFILE%\.rhinocode\py39-rh8\python.exe -m pip install cnets-0.1.0-cp39-abi3-win_amd64.whl":
        "installs into Rhino 8's own Python on Windows: there is no Rhino here",
    "~/.rhinocode/py39-rh8/python3.9 -m pip install dist/cnets-0.1.0-cp39-abi3-macosx_11_0_arm64.whl":
        "installs into Rhino 8's own Python on macOS: there is no Rhino here",
    "scripts/windows-wheel.sh":
        "the Windows wheel's own script (12 minutes from cold on 2 cores): run by hand",
}


def code_blocks(path):
    """The fenced blocks of a Markdown file: (language, code, line number), indented blocks (in
    list items) dedented."""
    lines = path.read_text().splitlines()
    out, k = [], 0
    while k < len(lines):
        m = re.match(r"^(\s*)```(\w*)\s*$", lines[k])
        if not m:
            k += 1
            continue
        indent, lang, start = m.group(1), m.group(2), k + 1
        body = []
        k += 1
        while k < len(lines) and lines[k].strip() != "```":
            body.append(lines[k])
            k += 1
        assert k < len(lines), f"{path}:{start}: unclosed code block"
        assert lang, f"{path}:{start}: a code block without a language"
        out.append((lang, textwrap.dedent("\n".join(body)) if indent else "\n".join(body), start))
        k += 1
    return out


def test_every_block_has_a_runnable_language():
    for path in DOCUMENTS:
        blocks = code_blocks(path)
        assert blocks, path
        for lang, _, line in blocks:
            assert lang in ("python", "sh"), f"{path}:{line}: ```{lang} blocks are not run"


# --- stand-ins -----------------------------------------------------------------------------


class _VertexList:
    """RhinoCommon's MeshVertexList as far as the script uses it: doubles only with
    UseDoublePrecisionVertices, else 32-bit floats."""

    def __init__(self):
        self.UseDoublePrecisionVertices = False
        self.points = []

    def Add(self, *args):
        x, y, z = (args[0].X, args[0].Y, args[0].Z) if len(args) == 1 else args
        if not self.UseDoublePrecisionVertices:
            x, y, z = (float(np.float32(c)) for c in (x, y, z))
        self.points.append((x, y, z))
        return len(self.points) - 1


class _FaceList:
    def __init__(self):
        self.faces = []

    def AddFace(self, *indices):
        self.faces.append(list(indices))
        return len(self.faces) - 1


class _Mesh:
    def __init__(self):
        self.Vertices = _VertexList()
        self.Faces = _FaceList()


class _Curve:
    def __init__(self, points):
        self.points = [rhino3dm.Point3d(*p) for p in np.asarray(points).tolist()]

    def TryGetPolyline(self):
        return True, list(self.points)


def rhino_stand_in(curves):
    """`Rhino` and `scriptcontext` modules for the Rhino 8 script: the picks return `curves` in
    order; `scriptcontext.doc.added` collects what the script adds."""
    rhino = types.ModuleType("Rhino")
    picks = iter(curves)

    class Result:
        Success, Cancel = "Success", "Cancel"

    class ObjRef:
        def __init__(self, curve):
            self._curve = curve

        def Curve(self):
            return self._curve

    def get_one_object(prompt, accept_nothing, filter):
        return Result.Success, ObjRef(_Curve(next(picks)))

    rhino.Commands = types.SimpleNamespace(Result=Result)
    rhino.Input = types.SimpleNamespace(RhinoGet=types.SimpleNamespace(GetOneObject=get_one_object))
    rhino.DocObjects = types.SimpleNamespace(ObjectType=types.SimpleNamespace(Curve=4))
    rhino.Geometry = types.SimpleNamespace(Mesh=_Mesh, Point3d=rhino3dm.Point3d)
    sc = types.ModuleType("scriptcontext")
    added = []
    sc.doc = types.SimpleNamespace(
        Objects=types.SimpleNamespace(AddMesh=lambda mesh: added.append(mesh) or len(added)),
        Views=types.SimpleNamespace(Redraw=lambda: None),
        added=added,
    )
    return rhino, sc


def jobqueue_stand_in():
    """`dask_jobqueue` whose SLURMCluster is a 2-worker LocalCluster (no SLURM here)."""
    from dask.distributed import LocalCluster

    module = types.ModuleType("dask_jobqueue")

    class SLURMCluster(LocalCluster):
        def __init__(self, **kwargs):
            self.slurm = kwargs
            super().__init__(n_workers=2, threads_per_worker=1, processes=True,
                             dashboard_address=":0")

        def scale(self, n=None, jobs=0, **kwargs):
            if jobs:
                self.jobs = jobs  # the two local workers stand for the jobs
                return None
            return super().scale(n, **kwargs)  # closing scales to 0

    module.SLURMCluster = SLURMCluster
    return module


# --- running -------------------------------------------------------------------------------


def _python_env():
    env = dict(os.environ)
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")
    return env


_PASSED = set()


def run_sh(line, scratch, cnets_bin):
    """Runs one documented shell line as the module docstring says (a `pip install` line that
    passed once is not run again)."""
    if line.startswith("pip install") and line in _PASSED:
        return
    _run_sh(line, scratch, cnets_bin)
    _PASSED.add(line)


def _run_sh(line, scratch, cnets_bin):
    words = line.split()
    env = _python_env()
    if words[:2] == ["pip", "install"]:
        spec = line.split("install", 1)[1].strip().strip('"')
        result = subprocess.run(
            [sys.executable, "-m", "pip", "install", "--dry-run", "--no-build-isolation",
             "--no-index", "--disable-pip-version-check", spec],
            cwd=str(REPO), env=env, capture_output=True, text=True, timeout=300)
        assert result.returncode == 0, (line, result.stdout, result.stderr)
        assert "Would install cnets" in result.stdout, (line, result.stdout)
        assert "does not provide the extra" not in result.stdout + result.stderr, (line, result.stderr)
        return
    if words[:2] == ["pip", "wheel"]:
        profile = os.environ.get("CNETS_PYTHON_PROFILE", "dev")
        target = scratch / "dist"
        args = [w if w != "dist" else str(target) for w in words[2:]]
        result = subprocess.run(
            [sys.executable, "-m", "pip", "wheel", "--no-build-isolation",
             "--disable-pip-version-check", f"--config-settings=build-args=--profile {profile}", *args],
            cwd=str(REPO), env=env, capture_output=True, text=True, timeout=900)
        assert result.returncode == 0, (line, result.stdout, result.stderr)
        wheels = list(target.glob("cnets-*-cp39-abi3-*.whl"))
        assert len(wheels) == 1, list(target.iterdir())
        return
    if words[:3] == ["python", "-m", "cnets.hops"]:
        # Port 0: the server picks a free one and names it in its start line (no other process
        # can take a probed port before it binds).
        args = ["0" if w == "5000" else w for w in words[3:]]
        log = open(scratch / "hops.log", "w+b")
        proc = subprocess.Popen([sys.executable, "-m", "cnets.hops", *args], cwd=str(scratch),
                                stdout=log, stderr=subprocess.STDOUT)
        try:
            deadline = time.monotonic() + 120
            while (found := re.search(r" on http://127\.0\.0\.1:(\d+)/",
                                      (scratch / "hops.log").read_text())) is None:
                assert proc.poll() is None and time.monotonic() < deadline, \
                    (scratch / "hops.log").read_text()
                time.sleep(0.05)
            port = int(found.group(1))
            while True:
                try:
                    with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=30) as r:
                        listing = json.loads(r.read())
                    break
                except OSError:
                    assert proc.poll() is None and time.monotonic() < deadline, \
                        (scratch / "hops.log").read_text()
                    time.sleep(0.1)
            uris = {c["Uri"] for c in listing}
            assert "/cnets_construct" in uris
            if "--library" in words:
                assert "/strip-fabrication" in uris, uris
        finally:
            proc.terminate()
            proc.wait(timeout=10)
            log.close()
        return
    if words[0] == "cnets":
        result = subprocess.run([str(cnets_bin), *words[1:]], cwd=str(scratch), env=env,
                                capture_output=True, text=True, timeout=120)
        assert result.returncode == 0, (line, result.stderr)
        assert "warning" not in result.stderr, result.stderr
        if "--library" in words:
            assert result.stdout.count("cluster:graphs/library/") == 4, result.stdout
        return
    raise AssertionError(f"a documented command this test does not know how to run: {line!r}")


def run_python(code, namespace, scratch):
    if re.search(r"^\s*import Rhino", code, re.M):
        directrix, generatrix = namespace["directrix"], namespace["generatrix"]
        rhino, sc = rhino_stand_in([directrix, generatrix])
        saved = {k: sys.modules.get(k) for k in ("Rhino", "scriptcontext")}
        sys.modules.update(Rhino=rhino, scriptcontext=sc)
        try:
            exec(compile(code, "rhino-script", "exec"), {"__name__": "__main__"})
        finally:
            for k, v in saved.items():
                if v is None:
                    sys.modules.pop(k, None)
                else:
                    sys.modules[k] = v
        (mesh,) = sc.doc.added
        expected = cnets.construct(directrix, generatrix, apex=0.95)
        np.testing.assert_array_equal(np.array(mesh.Vertices.points), expected.vertices.reshape(-1, 3))
        assert mesh.Faces.faces == expected.faces().tolist()
        return
    if "dask_jobqueue" in code:
        saved = sys.modules.get("dask_jobqueue")
        sys.modules["dask_jobqueue"] = jobqueue_stand_in()
        try:
            exec(compile(code, "docs", "exec"), namespace)
        finally:
            if saved is None:
                sys.modules.pop("dask_jobqueue", None)
            else:
                sys.modules["dask_jobqueue"] = saved
        return
    exec(compile(code, "docs", "exec"), namespace)


@pytest.mark.parametrize("document", DOCUMENTS, ids=lambda p: p.name)
def test_the_code_blocks_run(document, tmp_path, monkeypatch, cnets_bin, capsys):
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    (scratch / "graphs").symlink_to(REPO / "graphs")
    monkeypatch.chdir(scratch)
    namespace = {"__name__": "__docs__"}
    skipped = []
    for lang, code, line in code_blocks(document):
        started = time.monotonic()
        try:
            if lang == "python":
                run_python(code, namespace, scratch)
            else:
                commands = []
                for raw in code.splitlines():
                    command = re.sub(r"\s{2,}#.*$", "", raw).strip()
                    if not command or command.startswith("#"):
                        continue
                    if command in NOT_RUN:
                        skipped.append(command)
                        continue
                    commands.append(command)
                # The pip dry runs are independent: side by side (2 s each, mostly waiting).
                with concurrent.futures.ThreadPoolExecutor(4) as pool:
                    list(pool.map(lambda c: run_sh(c, scratch, cnets_bin),
                                  [c for c in commands if c.startswith("pip install")]))
                for command in commands:
                    if not command.startswith("pip install"):
                        run_sh(command, scratch, cnets_bin)
        except Exception as e:
            raise AssertionError(f"{document.name}:{line}: the ```{lang} block failed: {e!r}") from e
        print(f"{document.name}:{line}: ```{lang} block: {time.monotonic() - started:.1f} s")
    if document.name == "python.md":
        assert sorted(skipped) == sorted(NOT_RUN), "every line that is not run is documented here"
        # What the page says the examples give.
        assert set(namespace["facade"]) == {"facade"}
        assert namespace["wall"].vertices.shape == (5, 25, 3)
        assert "assistance: expected a number, got a list ([0.5, 0.2])" in capsys.readouterr().out
        assert namespace["out"]["layer"].vertices.shape == (20, 40, 3)
        assert (scratch / "net.3dm").is_file() and (scratch / "scene.3dm").is_file()
        assert len(namespace["df"]) == 36 and namespace["df"]["error"].isna().all()
        assert (scratch / "designs" / "design-0035").is_dir()
    else:
        assert namespace["net"].vertices.shape == (8, 20, 3)
