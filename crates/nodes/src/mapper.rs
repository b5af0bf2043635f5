//! Graph mappers: functions y = f(x) given by a curve type and draggable handles.
//!
//! The curve type (`kind`) and its handles (`handles`, points in the unit square of the graph, z
//! ignored) are plain node inputs, so they are stored in the graph file and an editor can show them
//! as a draggable widget. The definitions of every kind's handles are in `docs/inputs.md` and on
//! [`cnets_geometry::curves::MapperKind`].

use cnets_engine::prelude::*;
use cnets_geometry::curves::GraphMapper;
use cnets_geometry::curves::mapper::Domains;
use glam::DVec2;

node! {
    /// A graph mapper (as Grasshopper's Graph Mapper): a function drawn in a unit square by a curve
    /// `kind` and its `handles`, stretched onto the x domain [x_start, x_end] and the y range
    /// [y_start, y_end]. Samples f at `count` evenly spaced x from x_start to x_end, or, when
    /// `values` is given, maps each of them. Kinds: linear (handles A, B), bezier (P0, tangent
    /// handles P1, P2, P3), parabola (vertex V, point P), power (A, B, shape point C), sine
    /// (consecutive extrema A, B), gaussian (peak P, flank point W over baseline 0), sqrt (A, B),
    /// conic (P0, control P1, P2, shoulder S), piecewise (2+ points), spline (2+ points, smooth and
    /// monotone where the points are). No handles (or an empty list): the kind's default handles.
    /// Count 0 gives empty lists; count 1 samples x_start; an empty x domain is an error.
    #[node(id = "mapper.graph", category = "Mappers", name = "Graph mapper")]
    pub fn graph(
        /// Curve type: linear, bezier, parabola, power, sine, gaussian, sqrt, conic, piecewise or spline.
        #[ui(widget = Hidden)]
        kind: k::Choice<crate::choices::MapperCurve> = "linear",
        /// Handles (u, v, ignored z) in the unit square of the graph; empty: the kind's defaults.
        #[ui(widget = MapperHandles, range = 0.0..=1.0)]
        handles: Option<k::List<k::Point>>,
        /// x mapped to u = 0.
        x_start: k::Number = 0.0,
        /// x mapped to u = 1 (≠ x_start).
        x_end: k::Number = 1.0,
        /// y at v = 0.
        y_start: k::Number = 0.0,
        /// y at v = 1.
        y_end: k::Number = 1.0,
        /// Number of evenly spaced samples (≥ 0); ignored when `values` is given.
        count: k::Integer = 10,
        /// Values to map instead of sampling.
        values: Option<k::List<k::Number>>,
    ) -> (
        /// The mapped values f(x).
        y: k::List<k::Number>,
        /// The x of each sample (the values themselves when `values` is given).
        x: k::List<k::Number>,
    ) {
        let handles: Vec<DVec2> = match handles {
            Some(h) if !h.is_empty() => h.iter().map(|p| p.truncate()).collect(),
            _ => kind.default_handles(),
        };
        let mapper = GraphMapper::new(kind, &handles)?;
        let domains = Domains { x_start, x_end, y_start, y_end };
        match values {
            Some(xs) => {
                let ys = mapper.map_values(&xs, domains)?;
                Ok((ys, xs))
            }
            None => {
                let n = usize::try_from(count)
                    .map_err(|_| NodeError::new(format!("count must be 0 or more, got {count}")))?;
                let (xs, ys) = mapper.sample(n, domains)?;
                Ok((ys, xs))
            }
        }
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![graph()]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(named: &[(&str, Value)]) -> Result<Vec<Value>, String> {
        crate::testing::run_named(&graph(), named)
    }

    fn numbers(v: &Value) -> Vec<f64> {
        v.as_list()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    }

    fn handles(hs: &[(f64, f64)]) -> Value {
        Value::list(
            hs.iter()
                .map(|&(u, v)| Value::Point(DVec3::new(u, v, 0.0)))
                .collect(),
        )
    }

    #[test]
    fn samples_count_values_over_the_domains() {
        let out = run(&[
            ("count", Value::Integer(5)),
            ("x_start", Value::Number(10.0)),
            ("x_end", Value::Number(14.0)),
            ("y_start", Value::Number(1.0)),
            ("y_end", Value::Number(3.0)),
        ])
        .unwrap();
        assert_eq!(numbers(&out[0]), vec![1.0, 1.5, 2.0, 2.5, 3.0]);
        assert_eq!(numbers(&out[1]), vec![10.0, 11.0, 12.0, 13.0, 14.0]);
    }

    #[test]
    fn every_kind_hits_its_handles_through_the_node() {
        // Handles that are not the defaults, mapped onto a non-unit domain.
        // (kind, handles, indices of the on-curve handles)
        type Case = (&'static str, Vec<(f64, f64)>, Vec<usize>);
        let cases: Vec<Case> = vec![
            ("linear", vec![(0.2, 0.1), (0.7, 0.9)], vec![0, 1]),
            (
                "bezier",
                vec![(0.1, 0.2), (0.3, 0.9), (0.6, 0.0), (0.9, 0.8)],
                vec![0, 3],
            ),
            ("parabola", vec![(0.4, 0.2), (0.9, 0.7)], vec![0, 1]),
            (
                "power",
                vec![(0.1, 0.1), (0.9, 0.8), (0.6, 0.2)],
                vec![0, 1, 2],
            ),
            ("sine", vec![(0.2, 0.9), (0.45, 0.1)], vec![0, 1]),
            ("gaussian", vec![(0.6, 0.8), (0.4, 0.3)], vec![0, 1]),
            ("sqrt", vec![(0.1, 0.3), (0.8, 0.6)], vec![0, 1]),
            (
                "conic",
                vec![(0.0, 0.0), (0.2, 0.8), (1.0, 1.0), (0.3, 0.6)],
                vec![0, 2, 3],
            ),
            (
                "piecewise",
                vec![(0.7, 0.1), (0.1, 0.5), (0.4, 0.9)],
                vec![0, 1, 2],
            ),
            (
                "spline",
                vec![(0.0, 0.2), (0.3, 0.7), (0.5, 0.4), (1.0, 0.9)],
                vec![0, 1, 2, 3],
            ),
        ];
        let (x0, x1, y0, y1) = (-2.0, 6.0, 10.0, 5.0);
        for (kind, hs, on_curve) in cases {
            let xs: Vec<f64> = on_curve.iter().map(|&i| x0 + hs[i].0 * (x1 - x0)).collect();
            let out = run(&[
                ("kind", Value::text(kind)),
                ("handles", handles(&hs)),
                ("x_start", Value::Number(x0)),
                ("x_end", Value::Number(x1)),
                ("y_start", Value::Number(y0)),
                ("y_end", Value::Number(y1)),
                (
                    "values",
                    Value::list(xs.iter().map(|&x| Value::Number(x)).collect()),
                ),
            ])
            .unwrap_or_else(|e| panic!("{kind}: {e}"));
            for (y, &i) in numbers(&out[0]).iter().zip(&on_curve) {
                let expected = y0 + hs[i].1 * (y1 - y0);
                assert!(
                    (y - expected).abs() < 1e-9,
                    "{kind} handle {i}: {y} vs {expected}"
                );
            }
        }
    }

    #[test]
    fn edge_inputs() {
        let out = run(&[("count", Value::Integer(0))]).unwrap();
        assert!(numbers(&out[0]).is_empty());
        let out = run(&[("count", Value::Integer(1)), ("kind", Value::text("sine"))]).unwrap();
        assert_eq!(numbers(&out[0]), vec![0.0]);
        assert!(
            run(&[("count", Value::Integer(-1))])
                .unwrap_err()
                .contains("count")
        );
        let e = run(&[("x_end", Value::Number(0.0))]).unwrap_err();
        assert!(e.contains("x domain is empty"), "{e}");
        let e = run(&[("kind", Value::text("wiggle"))]).unwrap_err();
        assert!(e.contains("gaussian"), "{e}");
        let e = run(&[
            ("kind", Value::text("power")),
            ("handles", handles(&[(0.0, 0.0)])),
        ])
        .unwrap_err();
        assert!(e.contains("3 for a power graph"), "{e}");
        let e = run(&[("values", Value::list(vec![Value::Number(f64::NAN)]))]).unwrap_err();
        assert!(e.contains("not finite"), "{e}");
        let out = run(&[("values", Value::list(vec![]))]).unwrap();
        assert!(numbers(&out[0]).is_empty());
        // Empty handles mean the defaults.
        let out = run(&[
            ("kind", Value::text("gaussian")),
            ("handles", Value::list(vec![])),
            ("count", Value::Integer(3)),
        ])
        .unwrap();
        assert_eq!(numbers(&out[0])[1], 1.0);
    }

    #[test]
    fn values_tables_map_row_by_row() {
        let row = |xs: &[f64]| Value::list(xs.iter().map(|&x| Value::Number(x)).collect());
        let table = Value::list(vec![row(&[0.0, 1.0]), row(&[0.5])]);
        let out = run(&[("kind", Value::text("parabola")), ("values", table)]).unwrap();
        let rows = out[0].as_list().unwrap();
        assert_eq!(numbers(&rows[0]), vec![0.0, 0.0]);
        assert_eq!(numbers(&rows[1]), vec![1.0]);
    }
}
