//! Closest points on a mesh through the BVH (`mesh_query`): 10⁵ query points against a
//! 10⁵-triangle mesh (a wavy 224 × 224 quad grid fanned into triangles), building included, and
//! the build alone.

use cnets_geometry::mesh_query::MeshQuery;
use cnets_geometry::{DVec3, PolygonMesh};
use criterion::{Criterion, criterion_group, criterion_main};

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn wavy_grid(n: usize) -> PolygonMesh {
    let mut vertices = Vec::with_capacity((n + 1) * (n + 1));
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (i as f64 / n as f64 * 10.0, j as f64 / n as f64 * 10.0);
            vertices.push(DVec3::new(x, y, x.sin() * y.cos()));
        }
    }
    let id = |i: usize, j: usize| (i * (n + 1) + j) as u32;
    let faces: Vec<Vec<u32>> = (0..n)
        .flat_map(|i| {
            (0..n).map(move |j| vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
        })
        .collect();
    PolygonMesh::from_faces(vertices, &faces).expect("a valid grid")
}

fn queries(count: usize) -> Vec<DVec3> {
    let mut seed = 7u64;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| DVec3::new(next() * 12.0 - 1.0, next() * 12.0 - 1.0, next() * 4.0 - 2.0))
        .collect()
}

fn bench(c: &mut Criterion) {
    let mesh = wavy_grid(224); // 50 176 quads = 100 352 triangles
    let points = queries(100_000);
    let mut group = c.benchmark_group("closest_point");
    group.sample_size(10);
    group.bench_function("build 1e5 triangles", |b| {
        b.iter(|| MeshQuery::new(&mesh).unwrap())
    });
    group.bench_function("build + 1e5 queries on 1e5 triangles", |b| {
        b.iter(|| MeshQuery::new(&mesh).unwrap().closest_all(&points).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
