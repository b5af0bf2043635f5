#!/usr/bin/env python3
"""Writes the editor's benchmark graphs (issue 26):

- scale-1001.ron and scale-5001.ron: a slider feeding B branches of add → multiply → expression →
  clamp, 1 + 4·B nodes (B = 250, 1250), laid out in a grid;
- slow-nest.ron: graphs/facade.ron with a slider on its support layer's factor, so a drag re-runs
  the previewed support layer and beams and, below them, the unrolled strips and their nesting
  (fab.nest, about 0.6 s), which are not previewed.

    scripts/scale-graphs.py OUT_DIR

Used by `cnets-editor --bench-drag` (docs/editor.md, Latency at project size)."""
import pathlib
import sys


def graph(branches: int) -> str:
    nodes = [
        '        "slider": (type: "param.number", position: (0.0, 0.0), '
        'inputs: {"value": 0.5, "min": 0.0, "max": 1.0}),'
    ]
    edges = []
    for b in range(branches):
        y = 120.0 * b
        for k, (kind, inputs) in enumerate(
            [
                ("math.add", '{"b": %d.0}' % (b % 7)),
                ("math.multiply", '{"b": 1.5}'),
                ("math.expression", '{"expression": "sin(x) + x^2"}'),
                ("math.clamp", '{"min": -1.0, "max": 4.0}'),
            ]
        ):
            nodes.append(
                f'        "n{b}_{k}": (type: "{kind}", position: ({300.0 + 260.0 * k}, {y}), '
                f"inputs: {inputs}),"
            )
        edges += [
            f'"slider.value -> n{b}_0.a"',
            f'"n{b}_0.result -> n{b}_1.a"',
            f'"n{b}_1.result -> n{b}_2.x"',
            f'"n{b}_2.result -> n{b}_3.value"',
        ]
    return (
        "(\n    version: 1,\n    name: \"scale %d\",\n    nodes: {\n%s\n    },\n    edges: [\n        %s,\n    ],\n)\n"
        % (1 + 4 * branches, "\n".join(nodes), ",\n        ".join(edges))
    )


def slow_nest(facade: str) -> str:
    """facade.ron with a `lean` slider driving `support.factor`."""
    slider = (
        '        "lean": (type: "param.number", position: (1100.0, -200.0), '
        'inputs: {"value": 0.92, "min": 0.85, "max": 0.98}),\n'
    )
    text = facade.replace("    nodes: {\n", "    nodes: {\n" + slider, 1)
    return text.replace("    edges: [\n", '    edges: [\n        "lean.value -> support.factor",\n', 1)


def main() -> None:
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "target/bench-graphs")
    out.mkdir(parents=True, exist_ok=True)
    for branches in (250, 1250):
        path = out / f"scale-{1 + 4 * branches}.ron"
        path.write_text(graph(branches))
        print(path)
    graphs = pathlib.Path(__file__).resolve().parent.parent / "graphs"
    path = out / "slow-nest.ron"
    # Its imported files (if any) resolve beside the shipped graph.
    path.write_text(slow_nest((graphs / "facade.ron").read_text()))
    print(path)


if __name__ == "__main__":
    main()
