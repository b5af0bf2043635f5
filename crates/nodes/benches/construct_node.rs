//! The construction nodes as the engine runs them (`cnets eval … --timing` measures the same
//! call): typed inputs in (decoded from JSON as `cnets eval` does, or as plain values from an
//! upstream node), the kernel, the output values (mesh, planes, configurations, quality) out.
//! The kernel alone is benchmarked in `cnets-geometry`'s `construction` bench.

use std::f64::consts::PI;
use std::hint::black_box;

use cnets_engine::eval::evaluate_node;
use cnets_engine::value::json::from_json;
use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, Polyline};
use criterion::{Criterion, criterion_group, criterion_main};

/// The allocator of the `cnets` and editor binaries, so that the figures are what they see.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The same smooth design as the kernel benchmark: a helix-like directrix of `m` points and an
/// arc generatrix of `n` points around its first point.
fn design(n: usize, m: usize) -> (Polyline, Polyline) {
    let d: Vec<DVec3> = (0..m)
        .map(|j| {
            let t = j as f64 / (m - 1) as f64;
            DVec3::new(10.0 * (1.2 * t).cos(), 10.0 * (1.2 * t).sin(), 3.0 * t)
        })
        .collect();
    let (x0, x1) = (d[0], d[1]);
    let e = (x1 - x0).normalize();
    let inward = (-x0).reject_from(e).normalize();
    let up = e.cross(inward);
    let g = (0..n)
        .map(|i| {
            let phi = PI * (0.2 + 0.6 * i as f64 / (n - 1) as f64);
            x0 + inward * (1.5 * phi.sin()) + up * (1.5 * phi.cos())
        })
        .collect();
    (Polyline::open(d), Polyline::open(g))
}

/// How the inputs reach the node.
#[derive(Clone, Copy)]
enum Source {
    /// Decoded from JSON for the ports' types, as `cnets eval` does (an array of numbers becomes
    /// one packed row).
    Json,
    /// Lists of number values, as an upstream node's outputs are.
    Values,
}

/// The inputs of `cnets.construct` in port order: a per-vertex ratio table and assistance α.
fn construct_inputs(size: usize, alpha: f64, source: Source) -> Vec<Value> {
    let (d, g) = design(size, size);
    let apex: Vec<f64> = (0..size - 1)
        .map(|k| 1.0 + 0.3 / size as f64 * (k as f64 * 0.05).sin())
        .collect();
    let ratios: Vec<Vec<f64>> = (0..size)
        .map(|i| {
            (0..size - 1)
                .map(|k| 0.5 + 0.1 * ((i as f64 * 0.01) + (k as f64 * 0.02)).sin())
                .collect()
        })
        .collect();
    let registry = cnets_nodes::registry();
    let def = registry.get("cnets.construct").expect("registered");
    def.inputs
        .iter()
        .map(|port| {
            let numbers = |json: serde_json::Value, values: Value| match source {
                Source::Json => from_json(&json, &port.ty).expect("decodes"),
                Source::Values => values,
            };
            match port.name.as_ref() {
                "directrix" => Value::Polyline(d.clone().into()),
                "generatrix" => Value::Polyline(g.clone().into()),
                "apex" => numbers(serde_json::json!(apex), numbers_value(&apex)),
                "ratios" => numbers(
                    serde_json::json!(ratios),
                    Value::list(ratios.iter().map(|row| numbers_value(row)).collect()),
                ),
                "assistance" => Value::Number(alpha),
                _ => port.default.clone().unwrap_or(Value::Null),
            }
        })
        .collect()
}

fn numbers_value(values: &[f64]) -> Value {
    Value::list(values.iter().map(|&x| Value::Number(x)).collect())
}

fn bench(c: &mut Criterion) {
    let registry = cnets_nodes::registry();
    let def = registry.get("cnets.construct").expect("registered");
    let ctx = NodeContext::default();
    for &size in &[100usize, 1000] {
        let mut group = c.benchmark_group(format!("node {size}x{size}"));
        if size >= 1000 {
            group.sample_size(20);
        }
        for (name, alpha, source) in [
            ("cnets.construct ratios", -1.0, Source::Json),
            ("cnets.construct ratios + assistance", 0.5, Source::Json),
            ("cnets.construct ratios (value input)", -1.0, Source::Values),
            (
                "cnets.construct ratios + assistance (value input)",
                0.5,
                Source::Values,
            ),
        ] {
            let inputs = construct_inputs(size, alpha, source);
            group.bench_function(name, |b| {
                b.iter(|| evaluate_node(def, &ctx, black_box(&inputs)).expect("constructs"))
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
