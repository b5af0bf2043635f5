#!/usr/bin/env bash
# The memory cases of issue 27 §2 through the `cnets` binary, each under `ulimit -v` (the address
# space a container or a batch job would give): every hostile reader file, the JSON input
# conversion, the streamed writers and the flatten ladder with the *default* budget. Each case must
# end in a result or a clear error (exit 0, 1 or 2 — never an abort), with its peak resident memory
# (`eval --timing`: the process's VmHWM) at most the budget + 256 MB. The files are built here,
# small (a 256 MB budget), so the whole run takes well under a minute.
#
# Usage: scripts/test-limits.sh [CNETS_BINARY]   (default: target/debug/cnets, built if missing)
# Called by scripts/test.sh after `cargo test`.
set -euo pipefail
cd "$(dirname "$0")/.."

cnets="${1:-${CARGO_TARGET_DIR:-$PWD/target}/debug/cnets}"
if [ ! -x "$cnets" ]; then
  cargo build -q -p cnets
fi
cnets="$(cd "$(dirname "$cnets")" && pwd)/$(basename "$cnets")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"

budget_mb=256
budget="${budget_mb}M"
# The address space the issue allows: 2 × the budget + 1 GB.
address_kb=$(( (2 * budget_mb + 1024) * 1024 ))
failed=0

# run NAME LIMIT_KB NODE INPUTS [MAX_MEMORY]: cnets eval under ulimit -v, checked.
run() {
  local name="$1" limit_kb="$2" node="$3" inputs="$4" memory="${5:-$budget}"
  local start end code peak
  start=$(date +%s.%N)
  set +e
  ( ulimit -v "$limit_kb"; exec timeout 300 "$cnets" eval "$node" --inputs "$inputs" \
      --max-memory "$memory" --timing >"$name.out" 2>"$name.err" )
  code=$?
  set -e
  end=$(date +%s.%N)
  peak=$(sed -n 's/^peak memory: \([0-9.]*\) MB$/\1/p' "$name.err" | tail -1)
  local line
  line=$(grep -m1 '^error:' "$name.err" | cut -c1-160 || true)
  printf '%-22s exit %3s  %6.2f s  peak %8s MB  %s\n' "$name" "$code" \
    "$(awk -v a="$end" -v b="$start" 'BEGIN { print a - b }')" "${peak:-?}" "${line:-(result)}"
  if [ "$code" -gt 2 ]; then
    echo "  FAILED: $name ended with exit $code (an abort or a crash); stderr:" >&2
    tail -5 "$name.err" >&2
    failed=1
  elif [ -n "$peak" ] && [ "$memory" = "$budget" ] && \
       [ "$(awk -v p="$peak" -v b="$budget_mb" 'BEGIN { print (p > b + 256) }')" = 1 ]; then
    echo "  FAILED: $name peaked at $peak MB, more than the budget + 256 MB" >&2
    failed=1
  fi
}

python3 - <<'PY'
import base64, json, struct

def positions(n):
    return b"".join(struct.pack("<3f", (k % 7) * 0.125, (k % 5) * 0.25, 0.0) for k in range(n))

def gltf(vertices, uri, nodes):
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": vertices * 12, "uri": uri}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": vertices * 12}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": vertices,
                       "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    }
    doc.update(nodes)
    return doc

def data_uri(b):
    return "data:application/octet-stream;base64," + base64.b64encode(b).decode()

# PLY: 242 bytes declaring a billion items.
with open("junk.ply", "wb") as f:
    f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
            b"property float y\nproperty float z\nelement junk 1000000000\nproperty uchar a\n"
            b"end_header\n" + bytes(36))

# glTF: the same child 99 990 times, its mesh 30 000 vertices.
nodes = {"nodes": [{"children": [1] * 99990}, {"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
json.dump(gltf(30000, data_uri(positions(30000)), nodes), open("repeat.gltf", "w"))

# GLB: 1 000 buffers all naming a 10 MB binary chunk.
n = 10_000_000 // 12
doc = gltf(n, "x", {"nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})
doc["buffers"] = [{"byteLength": n * 12}] * 1000
js = json.dumps(doc).encode()
js += b" " * (-len(js) % 4)
bin_ = positions(n)
bin_ += bytes(-len(bin_) % 4)
with open("shared.glb", "wb") as f:
    f.write(b"glTF" + struct.pack("<II", 2, 12 + 8 + len(js) + 8 + len(bin_)))
    f.write(struct.pack("<I", len(js)) + b"JSON" + js)
    f.write(struct.pack("<I", len(bin_)) + b"BIN\0" + bin_)

# data: URI of 100 MB.
json.dump(gltf(6_000_000, data_uri(bytes(72_000_000)), {"nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}), open("uri.gltf", "w"))

# DXF: 100 000 circles; one LWPOLYLINE of 100 000 bulged vertices.
with open("circles.dxf", "w") as f:
    f.write("0\nSECTION\n2\nENTITIES\n")
    for k in range(100_000):
        f.write(f"0\nCIRCLE\n8\n0\n10\n{k}.0\n20\n0.0\n30\n0.0\n40\n1.0\n")
    f.write("0\nENDSEC\n0\nEOF\n")
with open("bulges.dxf", "w") as f:
    f.write("0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\n0\n90\n100000\n70\n0\n")
    for k in range(100_000):
        f.write(f"10\n{k}.0\n20\n0.0\n42\n0.5\n")
    f.write("0\nENDSEC\n0\nEOF\n")

# SVG: 10^5 cubic curves; an entity expanded to 2 GB inside `d`.
with open("curves.svg", "w") as f:
    f.write('<svg xmlns="http://www.w3.org/2000/svg">')
    for k in range(100_000):
        f.write(f'<path d="M{k} 0 C1 1 2 2 3 3"/>')
    f.write("</svg>")
with open("entity.svg", "w") as f:
    f.write('<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY e "' + "L1 1 " * 200_000 + '">]>'
            '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 ' + "&e;" * 2000 + '"/></svg>')

# CSV: one line of 3·10^7 columns. OBJ: 60 MB of faces.
with open("wide.csv", "w") as f:
    f.write("1," * 30_000_000)
with open("big.obj", "w") as f:
    f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    f.write("f 1 2 3\n" * 7_500_000)

# The inputs.
for name, fmt, node in [("junk.ply", "ply", "mesh"), ("repeat.gltf", "gltf", "mesh"),
                        ("shared.glb", "glb", "mesh"), ("uri.gltf", "gltf", "mesh"),
                        ("big.obj", "obj", "mesh"), ("circles.dxf", "dxf", "poly"),
                        ("bulges.dxf", "dxf", "poly"), ("curves.svg", "svg", "poly"),
                        ("entity.svg", "svg", "poly"), ("wide.csv", "csv", "poly")]:
    inputs = {"path": name, "format": fmt}
    if node == "poly":
        inputs["segments"] = 10000
    json.dump(inputs, open(name + ".json", "w"))

# math.add on a JSON list of 2·10^7 numbers (2·10^8 in the issue).
with open("add.json", "w") as f:
    f.write('{"b": 1.5, "a": [' + ",".join("0.5" for _ in range(20_000_000)) + "]}")
json.dump({"count": 2_000_000}, open("circle.json", "w"))
# curve.spline through 5·10^5 points (its arc-length table once took 16 bytes × 64 per span: 512 MB).
with open("spline.json", "w") as f:
    f.write('{"count": 1000, "points": [' + ",".join(f"[{k * 0.001}, {(k % 97) * 0.01}, 0]" for k in range(500_000)) + "]}")
PY

echo "== memory cases under ulimit -v ${address_kb} kB, budget ${budget}"
for f in junk.ply repeat.gltf shared.glb uri.gltf big.obj; do
  run "$f" "$address_kb" io.read_mesh "$f.json"
done
for f in circles.dxf bulges.dxf curves.svg entity.svg wide.csv; do
  run "$f" "$address_kb" io.read_polylines "$f.json"
done
run "math.add 2e7" "$address_kb" math.add add.json
run "curve.spline 5e5" "$address_kb" curve.spline spline.json

# The writers: a 2·10^6-point circle as JSON and CSV through `cnets run` (streamed).
for node in io.export_json io.export_csv; do
  cat >"$node.ron" <<EOF
(version: 1, nodes: {
    "c": (type: "curve.circle", inputs: {"count": 2000000}),
    "e": (type: "$node"),
}, edges: ["c.curve -> e.value"])
EOF
  set +e
  ( ulimit -v "$address_kb"; exec timeout 300 "$cnets" run "$node.ron" --out out \
      --max-memory "$budget" >"$node.out" 2>"$node.err" )
  code=$?
  set -e
  printf '%-22s exit %3s  %s\n' "$node" "$code" "$(ls -l out 2>/dev/null | tail -n +2 | wc -l) files"
  if [ "$code" -ne 0 ]; then
    echo "  FAILED: $node: exit $code" >&2
    cat "$node.err" >&2
    failed=1
  fi
done

# The flatten ladder with the default budget (half of what ulimit -v leaves): stops, no abort.
{
  echo '(version: 1, nodes: {'
  echo '    "a0": (type: "param.series", inputs: {"count": 4}),'
  echo '    "b0": (type: "param.series", inputs: {"count": 4}),'
  for k in $(seq 1 28); do
    echo "    \"a$k\": (type: \"list.flatten\"), \"b$k\": (type: \"list.flatten\"),"
  done
  echo '}, edges: ['
  for k in $(seq 1 28); do
    out=list; [ "$k" = 1 ] && out=values
    for n in a b; do
      echo "    \"a$((k - 1)).$out -> $n$k.tree\", \"b$((k - 1)).$out -> $n$k.tree\","
    done
  done
  echo '])'
} >ladder.ron
ladder_kb=$(( 2 * 1024 * 1024 ))
set +e
( ulimit -v "$ladder_kb"; exec timeout 300 "$cnets" run ladder.ron >ladder.out 2>ladder.err )
code=$?
set -e
printf '%-22s exit %3s  %s\n' "flatten ladder" "$code" "$(grep -m1 '^error' ladder.err | cut -c1-140)"
if [ "$code" -gt 2 ]; then
  echo "  FAILED: the flatten ladder under ulimit -v ${ladder_kb} kB ended with exit $code" >&2
  tail -5 ladder.err >&2
  failed=1
fi

# pq.unroll_strips of a 3000 × 1000 net at --max-memory 1G (it peaked at 1.44 GB): the node
# declares what it will build, so it ends in a clear error, not past the budget.
cat >unroll.ron <<'EOF'
(version: 1, nodes: {
    "d": (type: "curve.arc", inputs: {"radius": 50.0, "start": 0.0, "end": 90.0, "count": 1000}),
    "g": (type: "curve.arc", inputs: {"centre": (60.0, 0.0, 0.0), "radius": 5.0, "start": 100.0, "end": 260.0, "plane": ZX, "count": 3000}),
    "net": (type: "cnets.construct", preview: false),
    "u": (type: "pq.unroll_strips"),
}, edges: ["d.curve -> net.directrix", "g.curve -> net.generatrix", "net.mesh -> u.mesh"])
EOF
set +e
( ulimit -v $(( (2 * 1024 + 1024) * 1024 )); exec timeout 300 "$cnets" run unroll.ron --max-memory 1G \
    >unroll.out 2>unroll.err )
code=$?
set -e
printf '%-22s exit %3s  %s\n' "unroll 3000 x 1000" "$code" "$(grep -m1 '^error' unroll.err | cut -c1-140)"
if [ "$code" -ne 1 ] || ! grep -q "pq.unroll_strips): unrolling the strips of a mesh of 3000000 vertices needs" unroll.err; then
  echo "  FAILED: pq.unroll_strips of a 3000 × 1000 net at --max-memory 1G (exit $code):" >&2
  tail -3 unroll.err >&2
  failed=1
fi

# The same ladder with an explicit budget above what the process may safely use (`--max-memory 6G`
# under ulimit -v 8000000 aborted once): the budget is clamped to the default's bound, with a
# warning naming both figures, and the run ends in a clear error, not an abort.
set +e
( ulimit -v 8000000; exec timeout 300 "$cnets" run ladder.ron --max-memory 6G \
    >ladder6.out 2>ladder6.err )
code=$?
set -e
printf '%-22s exit %3s  %s\n' "ladder, 6G asked" "$code" "$(grep -m1 '^error' ladder6.err | cut -c1-140)"
if [ "$code" -gt 2 ]; then
  echo "  FAILED: the flatten ladder with --max-memory 6G under ulimit -v 8000000 ended with exit $code" >&2
  tail -5 ladder6.err >&2
  failed=1
elif ! grep -q '^warning: the memory budget asked for (6 GB).*8.2 GB.*4.1 GB' ladder6.err; then
  echo "  FAILED: no warning naming the asked budget (6 GB), the address limit (8.2 GB) and the budget (4.1 GB):" >&2
  head -5 ladder6.err >&2
  failed=1
fi

if [ "$failed" -ne 0 ]; then
  echo "test-limits.sh: some memory cases failed (above)" >&2
  exit 1
fi
echo "test-limits.sh: every case ended in a result or a clear error within its limits"
