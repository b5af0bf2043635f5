//! Every registered node, fed random and hostile inputs (NaN, ±inf, huge and tiny numbers,
//! coincident points, empty and ragged lists, degenerate meshes, wrong types, odd texts), never
//! panics: it returns outputs or an error with a message, and its outputs never hold a non-finite
//! number (overflows and NaN passed along become the node's error). Export nodes write into a
//! fresh temporary folder.

use std::path::PathBuf;
use std::sync::Arc;

use cnets_engine::eval::evaluate_node;
use cnets_engine::{Access, Items, NodeContext, NodeDef, NodeError, Record, Value, ValueType};
use cnets_geometry::{DVec3, Line, Plane, PolygonMesh, Polyline, QuadGrid};
use proptest::prelude::*;

/// A small deterministic generator (splitmix64), seeded by proptest, so one case is one seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn chance(&mut self, percent: usize) -> bool {
        self.below(100) < percent
    }

    fn pick<T: Clone>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())].clone()
    }

    fn coordinate(&mut self) -> f64 {
        (self.next() % 2001) as f64 / 100.0 - 10.0
    }

    fn number(&mut self) -> f64 {
        if self.chance(70) {
            self.coordinate()
        } else {
            self.pick(&[
                0.0,
                -0.0,
                1.0,
                -1.0,
                0.5,
                2.0,
                f64::NAN,
                f64::INFINITY,
                f64::NEG_INFINITY,
                1e300,
                -1e300,
                1e-300,
                f64::MIN_POSITIVE,
                f64::EPSILON,
            ])
        }
    }

    fn point(&mut self) -> DVec3 {
        if self.chance(90) {
            DVec3::new(self.coordinate(), self.coordinate(), self.coordinate())
        } else {
            DVec3::new(self.number(), self.number(), self.number())
        }
    }

    fn points(&mut self, max: usize) -> Vec<DVec3> {
        let n = self.below(max + 1);
        let mut points: Vec<DVec3> = (0..n).map(|_| self.point()).collect();
        if n > 1 && self.chance(15) {
            points[1] = points[0]; // a zero-length edge
        }
        points
    }

    fn quad_grid(&mut self) -> QuadGrid {
        let (rows, cols) = (1 + self.below(5), 1 + self.below(5));
        let noise = self.pick(&[0.0, 0.0, 0.01, 1.0]);
        let vertices = (0..rows * cols)
            .map(|k| {
                let (i, j) = ((k / cols) as f64, (k % cols) as f64);
                DVec3::new(j, i, 0.0) + noise * self.point()
            })
            .collect();
        let grid = QuadGrid::new(rows, cols, vertices).expect("consistent size");
        grid.with_wrap(self.chance(15), self.chance(15))
    }

    fn text(&mut self) -> String {
        self.pick(&[
            "",
            "x",
            "directrix",
            "generatrix",
            "linear",
            "bezier",
            "spline",
            "gaussian",
            "number",
            "point",
            "csv",
            "json",
            "obj",
            "svg",
            "out",
            "../escape",
            "/absolute",
            "a/b",
            "config",
            "planarity",
            "\u{0}",
            "ünïcödé",
        ])
        .to_string()
    }

    /// One item of type `ty` (sometimes of another type, to test type errors).
    fn item(&mut self, ty: &ValueType) -> Value {
        let ty = if self.chance(10) {
            self.pick(&[ValueType::Number, ValueType::Text, ValueType::Point])
        } else {
            ty.base().clone()
        };
        match ty {
            ValueType::Number | ValueType::Any => Value::Number(self.number()),
            ValueType::Integer => Value::Integer(self.below(64) as i64 - 3),
            ValueType::Boolean => Value::Boolean(self.chance(50)),
            ValueType::Text => Value::text(self.text()),
            ValueType::Point => Value::Point(self.point()),
            ValueType::Vector => Value::Vector(self.point()),
            ValueType::Plane => match Plane::from_normal(self.point(), self.point()) {
                Ok(plane) => Value::Plane(Arc::new(plane)),
                Err(_) => Value::Null,
            },
            ValueType::Lines => Value::Lines(Arc::new(
                (0..self.below(4))
                    .map(|_| Line::new(self.point(), self.point()))
                    .collect(),
            )),
            ValueType::Polyline => {
                let points = self.points(8);
                Value::Polyline(Arc::new(if self.chance(25) {
                    Polyline::closed(points)
                } else {
                    Polyline::open(points)
                }))
            }
            ValueType::QuadMesh => Value::QuadMesh(Arc::new(self.quad_grid())),
            ValueType::Mesh => Value::Mesh(Arc::new(PolygonMesh::from(&self.quad_grid()))),
            ValueType::Record => Value::Record(Arc::new(Record::new())),
            ValueType::List(inner) => self.item(&inner),
        }
    }

    /// A list of items; sometimes packed (a row of plain numbers or vectors, as JSON input and the
    /// construction nodes make them) when all its items allow it.
    fn list(&mut self, ty: &ValueType) -> Value {
        let items: Vec<Value> = (0..self.below(6)).map(|_| self.item(ty)).collect();
        if self.chance(30) {
            let len = items.len();
            if let Some(numbers) = plain_items(&items, |v| match v {
                Value::Number(x) => Some(*x),
                _ => None,
            }) {
                return Value::List(Items::numbers(Arc::new(numbers), 0..len));
            }
            if let Some(vectors) = plain_items(&items, |v| match v {
                Value::Vector(p) => Some(*p),
                _ => None,
            }) {
                return Value::List(Items::vectors(Arc::new(vectors), 0..len));
            }
        }
        Value::list(items)
    }

    /// A value for an input port: absent (its default), empty, an item, a list or a table.
    fn input(&mut self, ty: &ValueType, access: Access, default: Option<&Value>) -> Value {
        match self.below(10) {
            0 => default.cloned().unwrap_or(Value::Null),
            1 => Value::Null,
            2 => self.list(ty),
            3 if access != Access::Item => {
                Value::list((0..self.below(5)).map(|_| self.list(ty)).collect())
            }
            _ => self.item(ty),
        }
    }
}

/// The plain data of every item, when `read` accepts them all.
fn plain_items<T>(items: &[Value], read: impl Fn(&Value) -> Option<T>) -> Option<Vec<T>> {
    items.iter().map(read).collect()
}

/// Where a non-finite number hides in `v`, if anywhere.
fn non_finite(v: &Value) -> Option<String> {
    let bad = |p: &DVec3| !p.is_finite();
    match v {
        Value::Number(x) if !x.is_finite() => Some(format!("number {x}")),
        Value::Point(p) | Value::Vector(p) if bad(p) => Some(format!("point {p}")),
        Value::Plane(p) if bad(&p.origin) || bad(&p.normal) => Some("plane".into()),
        Value::Lines(l) if l.iter().any(|l| bad(&l.start) || bad(&l.end)) => Some("line".into()),
        Value::Polyline(p) if p.points.iter().any(bad) => Some("polyline point".into()),
        Value::QuadMesh(g) if g.vertices.iter().any(bad) => Some("quad mesh vertex".into()),
        Value::Mesh(m) if m.vertices.iter().any(bad) => Some("mesh vertex".into()),
        Value::List(items) => items.iter().find_map(non_finite),
        Value::Record(r) => r
            .fields()
            .iter()
            .find_map(|(name, v)| non_finite(v).map(|what| format!("{name}: {what}"))),
        _ => None,
    }
}

/// A folder for the exports of one test (the tests run side by side in one process).
fn out_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cnets-hostile-{test}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary folder");
    dir
}

fn check(def: &NodeDef, rng: &mut Rng, ctx: &NodeContext) -> Result<(), TestCaseError> {
    let inputs: Vec<Value> = def
        .inputs
        .iter()
        .map(|port| rng.input(&port.ty, port.access, port.default.as_ref()))
        .collect();
    match evaluate_node(def, ctx, &inputs) {
        Ok(outputs) => {
            prop_assert_eq!(outputs.values.len(), def.outputs.len());
            for (port, value) in def.outputs.iter().zip(&outputs.values) {
                let found = non_finite(value);
                prop_assert!(
                    found.is_none(),
                    "{}.{}: {:?} on inputs {:?}",
                    def.id,
                    port.name,
                    found,
                    inputs
                );
            }
        }
        Err(error) => {
            // A panic is a bug: never the answer to an input.
            prop_assert!(
                !matches!(error, NodeError::Panicked(_)),
                "{}: {} on inputs {:?}",
                def.id,
                error,
                inputs
            );
            let message = error.to_string();
            prop_assert!(
                !message.starts_with("node panicked"),
                "{}: {} on inputs {:?}",
                def.id,
                message,
                inputs
            );
            prop_assert!(!message.trim().is_empty(), "{}: empty error", def.id);
        }
    }
    Ok(())
}

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn no_node_panics_or_outputs_non_finite_numbers(seed in any::<u64>()) {
        let registry = cnets_nodes::registry();
        let defs: Vec<_> = registry.iter().collect();
        let mut rng = Rng(seed);
        let def = rng.pick(&defs);
        let ctx = NodeContext::new(Some(out_dir("random")), None);
        check(def, &mut rng, &ctx)?;
    }
}

#[test]
fn every_node_survives_its_defaults_and_empty_inputs() {
    let registry = cnets_nodes::registry();
    let ctx = NodeContext::new(Some(out_dir("defaults")), None);
    for def in registry.iter() {
        let id = &def.id;
        for empty in [false, true] {
            let inputs: Vec<Value> = def
                .inputs
                .iter()
                .map(|p| match (&p.default, empty) {
                    (Some(d), false) => d.clone(),
                    _ => Value::Null,
                })
                .collect();
            if let Err(error) = evaluate_node(def, &ctx, &inputs) {
                assert!(!matches!(error, NodeError::Panicked(_)), "{id}: {error}");
            }
        }
    }
}
