#!/usr/bin/env bash
# Cross-builds the Windows x86-64 wheel of the cnets Python package (abi3: one wheel for CPython
# ≥ 3.9, what Rhino 8 on Windows needs) on Linux, then checks it as far as Linux allows:
#
#   - the wheel's name and its WHEEL tags are cp39-abi3-win_amd64;
#   - it holds cnets/_cnets.pyd, every module of python/cnets, the stub and py.typed, and a RECORD
#     whose sha256 hashes and sizes match the files;
#   - `objdump -p` of the .pyd: a PE32+ x86-64 DLL exporting PyInit__cnets that imports only
#     Windows system DLLs and python3.dll (no python3X.dll, no MinGW runtime DLL).
#
# It installs what it needs when missing (Debian's mingw-w64 through apt — with sudo when not
# root —, the x86_64-pc-windows-gnu target through rustup, maturin into target/windows-venv) and
# builds `maturin build --release --target x86_64-pc-windows-gnu` with PyO3's
# generate-import-lib feature (it writes python3.dll's import library: no Windows Python
# needed). The build runs on a copy of the last commit's workspace in target/windows/src (the
# feature adds python3-dll-a to that copy's Cargo.lock, never to the checkout's; other people's
# uncommitted edits stay out of it) with its own target folder, target/windows/build.
#
# Usage: scripts/windows-wheel.sh [OUT_DIR]      (default target/wheels)
# Not part of scripts/test.sh: a cold build took 12 min 24 s on the shared 2-core machine.
# docs/python.md says what this does and does not test.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
out="${1:-$root/target/wheels}"
mkdir -p "$out"
out=$(cd "$out" && pwd)
target=x86_64-pc-windows-gnu

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@"; else
    echo "windows-wheel: need root to run: $*" >&2; return 1; fi
}

if ! command -v x86_64-w64-mingw32-gcc >/dev/null || ! command -v x86_64-w64-mingw32-objdump >/dev/null; then
  echo "== installing mingw-w64 (apt)"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq mingw-w64 >/dev/null
fi
if ! rustup target list --installed 2>/dev/null | grep -qx "$target"; then
  echo "== adding the $target target (rustup)"
  rustup target add "$target"
fi
venv="$root/target/windows-venv"
if [ ! -x "$venv/bin/maturin" ]; then
  echo "== installing maturin into $venv"
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip --disable-pip-version-check -q install "maturin>=1.16,<2"
fi

echo "== the workspace of $(git rev-parse --short HEAD) into target/windows/src"
src="$root/target/windows/src"
rm -rf "$src"
mkdir -p "$src"
git archive HEAD Cargo.toml Cargo.lock rustfmt.toml crates tests python vendor | tar -x -C "$src"

echo "== maturin build --release --target $target"
rm -f "$out"/cnets-*-win_amd64.whl
(
  cd "$src"
  # No clippy wrapper or other build settings from the environment (scripts/test.sh exports some).
  env -u RUSTC_WORKSPACE_WRAPPER -u CLIPPY_ARGS CARGO_TARGET_DIR="$root/target/windows/build" \
    "$venv/bin/maturin" build --release --target "$target" --features pyo3/generate-import-lib \
    -m python/Cargo.toml -o "$out"
)
wheel=$(ls "$out"/cnets-*-win_amd64.whl)
echo "== checking $(basename "$wheel")"
"$venv/bin/python" - "$wheel" "$root/python/cnets" <<'EOF'
import base64, hashlib, os, re, subprocess, sys, tempfile, zipfile

wheel, package = sys.argv[1], sys.argv[2]
name = os.path.basename(wheel)
problems = []
if not re.fullmatch(r"cnets-[0-9.]+-cp39-abi3-win_amd64\.whl", name):
    problems.append(f"the file name {name} is not cnets-<version>-cp39-abi3-win_amd64.whl")
with zipfile.ZipFile(wheel) as z:
    names = z.namelist()
    info = [n for n in names if n.endswith(".dist-info/WHEEL")]
    tags = [l.split(": ", 1)[1] for l in z.read(info[0]).decode().splitlines() if l.startswith("Tag: ")]
    if tags != ["cp39-abi3-win_amd64"]:
        problems.append(f"WHEEL tags {tags}, expected ['cp39-abi3-win_amd64']")
    expected = {f"cnets/{f}" for f in os.listdir(package) if f.endswith((".py", ".pyi")) or f == "py.typed"}
    expected.add("cnets/_cnets.pyd")
    missing = sorted(expected - set(names))
    if missing:
        problems.append(f"missing from the wheel: {missing}")
    stray = sorted(n for n in names if n.endswith((".so", ".dylib")) or "__pycache__" in n)
    if stray:
        problems.append(f"not for Windows: {stray}")
    record = [n for n in names if n.endswith(".dist-info/RECORD")][0]
    for line in z.read(record).decode().splitlines():
        path, digest, size = line.rsplit(",", 2)
        if path == record:
            continue
        data = z.read(path)
        want = "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        if digest != want or int(size) != len(data):
            problems.append(f"RECORD does not match {path}")
    with tempfile.TemporaryDirectory() as tmp:
        pyd = z.extract("cnets/_cnets.pyd", tmp)
        dump = subprocess.run(["x86_64-w64-mingw32-objdump", "-p", pyd], capture_output=True,
                              text=True, check=True).stdout
        head = subprocess.run(["x86_64-w64-mingw32-objdump", "-f", pyd], capture_output=True,
                              text=True, check=True).stdout
size = os.path.getsize(wheel)
if "pei-x86-64" not in head:
    problems.append(f"the .pyd is not a PE32+ x86-64 file: {head.strip()}")
if "Magic\t\t\t020b" not in dump or "DLL" not in dump:
    problems.append("the .pyd is not a PE32+ DLL")
if not re.search(r"\]\s+PyInit__cnets$", dump, re.M):
    problems.append("the .pyd does not export PyInit__cnets")
dlls = re.findall(r"^\s*DLL Name: (\S+)", dump, re.M)
system = {
    "kernel32.dll", "ntdll.dll", "advapi32.dll", "userenv.dll", "ws2_32.dll", "bcrypt.dll",
    "bcryptprimitives.dll", "msvcrt.dll", "ucrtbase.dll", "user32.dll", "shell32.dll",
    "ole32.dll", "oleaut32.dll", "psapi.dll", "secur32.dll", "crypt32.dll", "synchronization.dll",
}
allowed = lambda d: d.lower() in system or d.lower().startswith("api-ms-win-") or d == "python3.dll"
foreign = [d for d in dlls if not allowed(d)]
if foreign:
    problems.append(f"imports DLLs that are neither Windows' nor python3.dll: {foreign}")
if "python3.dll" not in dlls:
    problems.append(f"does not import python3.dll (imports {dlls})")
print(f"wheel: {name} ({size / 1e6:.1f} MB), tag cp39-abi3-win_amd64")
print(f"contents: {len(names)} files, RECORD hashes checked")
print(f"_cnets.pyd imports: {', '.join(dlls)}")
if problems:
    print("windows-wheel: FAILED", *problems, sep="\n  ", file=sys.stderr)
    sys.exit(1)
print("windows-wheel: every check passed")
EOF
echo "$wheel"
