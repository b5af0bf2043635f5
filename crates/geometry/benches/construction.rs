//! Criterion benchmarks of the cone-net constructions at 100 × 100 and 1000 × 1000 vertices.

use std::f64::consts::PI;
use std::hint::black_box;

use cnets_geometry::conenet::{
    ConstructInputs, CoplanarInputs, CtubeInputs, construct, construct_coplanar, construct_ctube,
    ctube_mesh,
};
use cnets_geometry::{DVec3, Polyline};
use criterion::{Criterion, criterion_group, criterion_main};

/// The allocator of the `cnets` and editor binaries, so that the figures are what they see.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A smooth open directrix (helix-like arc) with `m` points.
fn directrix(m: usize) -> Polyline {
    Polyline::open(
        (0..m)
            .map(|j| {
                let t = j as f64 / (m - 1) as f64;
                DVec3::new(10.0 * (1.2 * t).cos(), 10.0 * (1.2 * t).sin(), 3.0 * t)
            })
            .collect(),
    )
}

/// A generatrix of `n` points on an arc around X_0 on the inner side of the directrix, in the plane
/// through X_0 perpendicular to the first edge.
fn generatrix(n: usize, d: &Polyline) -> Polyline {
    let (x0, x1) = (d.points[0], d.points[1]);
    let e = (x1 - x0).normalize();
    let inward = (-x0).reject_from(e).normalize();
    let up = e.cross(inward);
    Polyline::open(
        (0..n)
            .map(|i| {
                let s = i as f64 / (n - 1) as f64;
                let phi = PI * (0.2 + 0.6 * s);
                x0 + inward * (1.5 * phi.sin()) + up * (1.5 * phi.cos())
            })
            .collect(),
    )
}

/// Apex values with a gentle profile (no corrections triggered).
fn apex(m: usize) -> Vec<f64> {
    (0..m - 1)
        .map(|k| 1.0 + 0.3 / m as f64 * (k as f64 * 0.05).sin())
        .collect()
}

/// Per-vertex ratios varying smoothly around ½.
fn ratios(n: usize, m: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            (0..m - 1)
                .map(|k| 0.5 + 0.1 * ((i as f64 * 0.01) + (k as f64 * 0.02)).sin())
                .collect()
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    for &size in &[100usize, 1000] {
        let d = directrix(size);
        let g = generatrix(size, &d);
        let a = apex(size);
        let ctube = CtubeInputs::new(d.clone(), g.clone()).apex(a.clone());
        let with_ratios = ConstructInputs::new(d.clone(), g.clone())
            .apex(a.clone())
            .ratios(ratios(size, size));
        let assisted = with_ratios.clone().assistance(0.5);
        let coplanar = CoplanarInputs::new(d.clone(), g.clone())
            .apex(a.clone())
            .ruling_ratios(
                (0..size - 1)
                    .map(|k| 0.5 + 0.1 * (k as f64 * 0.02).sin())
                    .collect::<Vec<_>>(),
            )
            .plane_ratios(
                (0..size - 1)
                    .map(|k| 0.5 + 0.1 * (k as f64 * 0.03).cos())
                    .collect::<Vec<_>>(),
            );
        let coplanar_assisted = coplanar.clone().assistance(0.5);
        let mut group = c.benchmark_group(format!("{size}x{size}"));
        if size >= 1000 {
            group.sample_size(20);
        }
        group.bench_function("ctube_mesh (kernel)", |b| {
            b.iter(|| ctube_mesh(black_box(&ctube)).unwrap())
        });
        group.bench_function("construct_ctube (full)", |b| {
            b.iter(|| construct_ctube(black_box(&ctube)).unwrap())
        });
        group.bench_function("construct ratios", |b| {
            b.iter(|| construct(black_box(&with_ratios)).unwrap())
        });
        group.bench_function("construct ratios + assistance", |b| {
            b.iter(|| construct(black_box(&assisted)).unwrap())
        });
        group.bench_function("construct_coplanar", |b| {
            b.iter(|| construct_coplanar(black_box(&coplanar)).unwrap())
        });
        group.bench_function("construct_coplanar + assistance", |b| {
            b.iter(|| construct_coplanar(black_box(&coplanar_assisted)).unwrap())
        });
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
