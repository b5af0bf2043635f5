//! The scene's GPU buffers across the web page's worker boundary, two ways side by side: as their
//! bytes (what `SceneParts` does, `scene_bytes`) and element by element (serde's derive on
//! `FaceVertex`, `Segment` and `PointInstance`, postcard writing each field). A 300 × 300 net:
//! 357 604 face corners, 536 406 index entries, 179 400 edge segments.
//!
//! `cargo bench -p cnets-render --bench scene_wire`

use std::hint::black_box;

use cnets_geometry::{DVec3, QuadGrid};
use cnets_render::{FaceColors, FaceVertex, PointInstance, Scene, Segment, palette};
use criterion::{Criterion, criterion_group, criterion_main};

fn net(n: usize) -> Scene {
    let vertices = (0..n * n)
        .map(|k| {
            let (i, j) = ((k / n) as f64, (k % n) as f64);
            DVec3::new(i, j, (0.1 * i).sin() * (0.1 * j).cos())
        })
        .collect();
    let grid = QuadGrid::new(n, n, vertices).expect("a grid");
    let mut scene = Scene::new();
    scene
        .add_quad_grid(&grid, FaceColors::Uniform(palette::SURFACE))
        .expect("drawn");
    scene
}

/// The buffers element by element: serde's derive on each item.
#[derive(serde::Serialize, serde::Deserialize)]
struct ByElement {
    face_vertices: Vec<FaceVertex>,
    face_indices: Vec<u32>,
    segments: Vec<Segment>,
    points: Vec<PointInstance>,
}

fn encodings(c: &mut Criterion) {
    let scene = net(300);
    let parts = scene.parts();
    let by_element = ByElement {
        face_vertices: parts.face_vertices.clone(),
        face_indices: parts.face_indices.clone(),
        segments: parts.segments.clone(),
        points: parts.points.clone(),
    };
    let bytes = postcard::to_allocvec(&scene).expect("encodes");
    let elements = postcard::to_allocvec(&by_element).expect("encodes");
    println!(
        "message: {} bytes as bytes, {} bytes element by element",
        bytes.len(),
        elements.len()
    );
    let mut group = c.benchmark_group("scene 300 x 300 across the wire");
    group.sample_size(20);
    group.bench_function("as bytes: encode + decode", |b| {
        b.iter(|| {
            let message = postcard::to_allocvec(black_box(&scene)).expect("encodes");
            postcard::from_bytes::<Scene>(&message).expect("decodes")
        })
    });
    group.bench_function("element by element: encode + decode", |b| {
        b.iter(|| {
            let message = postcard::to_allocvec(black_box(&by_element)).expect("encodes");
            postcard::from_bytes::<ByElement>(&message).expect("decodes")
        })
    });
    group.finish();
}

criterion_group!(benches, encodings);
criterion_main!(benches);
