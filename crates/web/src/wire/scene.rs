//! The preview across the wire: the display options a request carries, and the scene, its
//! figures and its picks an answer carries.

use std::sync::Arc;

use cnets_editor::preview::{
    ColorMode, DistanceFigures, DistanceSide, Layer, LegendInfo, MeshFigures, MeshKind, PickCurve,
    PickGeometry, PickMesh, Picks, PreviewOptions, PreviewStats,
};
use cnets_geometry::fabrication::FaceClass;
use cnets_geometry::{PolygonMesh, Polyline, QuadGrid};
use cnets_render::{Bounds, Color, Legend, Scene, SceneParts};

use super::WireError;
use super::codec::{Reader, Res, Writer};

pub(super) fn options(w: &mut Writer, o: &PreviewOptions) {
    w.u8(match o.color_mode {
        ColorMode::Configuration => 0,
        ColorMode::Planarity => 1,
        ColorMode::Plain => 2,
        ColorMode::Distance => 3,
    });
    w.opt(o.distance_to.as_ref(), |w, uid| w.u64(*uid));
    w.u8(side_index(o.distance_side));
    let layers = Layer::ALL
        .iter()
        .enumerate()
        .fold(0u32, |acc, (k, l)| acc | (u32::from(o.shows(*l)) << k));
    w.u32(layers);
    w.f64(o.planarity_limit());
}

pub(super) fn read_options(r: &mut Reader) -> Res<PreviewOptions> {
    let mut o = PreviewOptions::default();
    o.color_mode = match r.u8()? {
        0 => ColorMode::Configuration,
        1 => ColorMode::Planarity,
        2 => ColorMode::Plain,
        3 => ColorMode::Distance,
        _ => return Err(WireError("unknown colour mode")),
    };
    o.distance_to = r.opt(Reader::u64)?;
    o.distance_side = read_side(r)?;
    let layers = r.u32()?;
    for (k, l) in Layer::ALL.iter().enumerate() {
        o.set(*l, layers & (1 << k) != 0);
    }
    let limit = r.f64()?;
    if limit != o.planarity_limit() && !o.set_planarity_limit(limit) {
        return Err(WireError("planarity limit out of range"));
    }
    Ok(o)
}

pub(super) fn scene(w: &mut Writer, s: &Scene) {
    w.raw(&s.background.0);
    w.pods(s.face_vertices());
    w.pods(s.face_indices());
    w.pods(s.segments());
    w.pods(s.points());
    w.opt(s.bounds().as_ref(), |w, b| {
        w.pods(&[b.min.to_array(), b.max.to_array()]);
    });
    w.u64(s.skipped() as u64);
}

pub(super) fn read_scene(r: &mut Reader) -> Res<Scene> {
    let mut background = [0u8; 4];
    background.copy_from_slice(r.take(4)?);
    let parts = SceneParts {
        background: Color(background),
        face_vertices: r.pods()?,
        face_indices: r.pods()?,
        segments: r.pods()?,
        points: r.pods()?,
        bounds: r.opt(|r| {
            let corners: Vec<[f32; 3]> = r.pods()?;
            match corners[..] {
                [min, max] => Ok(Bounds::new(min.into(), max.into())),
                _ => Err(WireError("a box has two corners")),
            }
        })?,
        skipped: r.usize()?,
    };
    Scene::from_parts(parts).ok_or(WireError("a triangle index past the vertices"))
}

pub(super) fn class_index(c: FaceClass) -> u8 {
    FaceClass::ALL.iter().position(|k| *k == c).unwrap_or(0) as u8
}

pub(super) fn read_class(r: &mut Reader) -> Res<FaceClass> {
    FaceClass::ALL
        .get(usize::from(r.u8()?))
        .copied()
        .ok_or(WireError("unknown face class"))
}

fn side_index(side: DistanceSide) -> u8 {
    match side {
        DistanceSide::Net => 0,
        DistanceSide::Reference => 1,
    }
}

fn read_side(r: &mut Reader) -> Res<DistanceSide> {
    match r.u8()? {
        0 => Ok(DistanceSide::Net),
        1 => Ok(DistanceSide::Reference),
        _ => Err(WireError("unknown distance side")),
    }
}

fn kind_index(kind: MeshKind) -> u8 {
    match kind {
        MeshKind::ConeNet => 0,
        MeshKind::Mesh => 1,
        MeshKind::Reference => 2,
    }
}

fn read_kind(r: &mut Reader) -> Res<MeshKind> {
    match r.u8()? {
        0 => Ok(MeshKind::ConeNet),
        1 => Ok(MeshKind::Mesh),
        2 => Ok(MeshKind::Reference),
        _ => Err(WireError("unknown mesh kind")),
    }
}

pub(super) fn stats(w: &mut Writer, s: &PreviewStats) {
    w.u64(s.vertices as u64);
    w.u64(s.faces as u64);
    w.opt(s.max_planarity.as_ref(), |w, p| w.f64(*p));
    w.opt(s.max_planarity_mesh.as_ref(), |w, m| w.str(m));
    w.len(s.meshes.len());
    for m in &s.meshes {
        w.str(&m.name);
        w.u8(kind_index(m.kind));
        w.u64(m.vertices as u64);
        w.u64(m.faces as u64);
        w.opt(m.max_planarity.as_ref(), |w, p| w.f64(*p));
    }
    match &s.legend {
        LegendInfo::None => w.u8(0),
        LegendInfo::Classes(classes) => {
            w.u8(1);
            w.len(classes.len());
            for (c, n) in classes {
                w.u8(class_index(*c));
                w.u64(*n as u64);
            }
        }
        LegendInfo::Planarity(l) | LegendInfo::Distance(l) => {
            w.u8(if matches!(s.legend, LegendInfo::Distance(_)) {
                3
            } else {
                2
            });
            w.str(&l.title);
            w.f64(l.min);
            w.f64(l.max);
            w.len(l.stops.len());
            for (x, c) in &l.stops {
                w.f64(*x);
                w.raw(&c.0);
            }
            w.strs(&l.labels);
        }
    }
    w.u64(s.apices as u64);
    w.opt(s.distance.as_ref(), |w, d| {
        w.str(&d.reference);
        w.strs(&d.net);
        for x in [
            d.rms,
            d.max,
            d.net_rms,
            d.net_max,
            d.reference_rms,
            d.reference_max,
        ] {
            w.f64(x);
        }
        w.u64(d.samples.0 as u64);
        w.u64(d.samples.1 as u64);
        w.u8(side_index(d.side));
        w.u64(d.vertices as u64);
        w.f64(d.colour_max);
    });
    w.opt(s.distance_status.as_ref(), |w, t| w.str(t));
    w.f64(s.build_ms);
}

pub(super) fn read_stats(r: &mut Reader) -> Res<PreviewStats> {
    let vertices = r.usize()?;
    let faces = r.usize()?;
    let max_planarity = r.opt(Reader::f64)?;
    let max_planarity_mesh = r.opt(Reader::string)?;
    // A name (its length), a kind, two counts and an optional number: at least 26 bytes each.
    let n = r.len(26)?;
    let meshes = (0..n)
        .map(|_| {
            Ok(MeshFigures {
                name: r.string()?,
                kind: read_kind(r)?,
                vertices: r.usize()?,
                faces: r.usize()?,
                max_planarity: r.opt(Reader::f64)?,
            })
        })
        .collect::<Res<_>>()?;
    let legend = match r.u8()? {
        0 => LegendInfo::None,
        1 => {
            let n = r.len(9)?;
            LegendInfo::Classes(
                (0..n)
                    .map(|_| Ok((read_class(r)?, r.usize()?)))
                    .collect::<Res<_>>()?,
            )
        }
        kind @ (2 | 3) => {
            let title = r.string()?;
            let min = r.f64()?;
            let max = r.f64()?;
            let n = r.len(12)?;
            let stops = (0..n)
                .map(|_| {
                    let x = r.f64()?;
                    let mut c = [0u8; 4];
                    c.copy_from_slice(r.take(4)?);
                    Ok((x, Color(c)))
                })
                .collect::<Res<_>>()?;
            let legend = Legend {
                title,
                min,
                max,
                stops,
                labels: r.strings()?,
            };
            if kind == 3 {
                LegendInfo::Distance(legend)
            } else {
                LegendInfo::Planarity(legend)
            }
        }
        _ => return Err(WireError("unknown legend")),
    };
    Ok(PreviewStats {
        vertices,
        faces,
        max_planarity,
        max_planarity_mesh,
        meshes,
        legend,
        apices: r.usize()?,
        distance: r.opt(|r| {
            Ok(DistanceFigures {
                reference: r.string()?,
                net: r.strings()?,
                rms: r.f64()?,
                max: r.f64()?,
                net_rms: r.f64()?,
                net_max: r.f64()?,
                reference_rms: r.f64()?,
                reference_max: r.f64()?,
                samples: (r.usize()?, r.usize()?),
                side: read_side(r)?,
                vertices: r.usize()?,
                colour_max: r.f64()?,
            })
        })?,
        distance_status: r.opt(Reader::string)?,
        build_ms: r.f64()?,
    })
}

pub(super) fn picks(w: &mut Writer, p: &Picks) {
    w.len(p.meshes.len());
    for m in &p.meshes {
        w.str(&m.node);
        w.str(&m.output);
        w.opt(m.item.as_ref(), |w, i| w.u64(*i as u64));
        match &m.geometry {
            PickGeometry::Grid(g) => {
                w.u8(0);
                w.u64(g.rows as u64);
                w.u64(g.cols as u64);
                w.bool(g.wrap_rows);
                w.bool(g.wrap_cols);
                w.dvec3s(&g.vertices);
            }
            PickGeometry::Mesh(mesh) => {
                w.u8(1);
                w.dvec3s(&mesh.vertices);
                w.pods(&mesh.indices);
                w.pods(&mesh.face_starts);
            }
        }
        w.opt(m.classes.as_ref(), |w, classes| {
            let bytes: Vec<u8> = classes.iter().map(|c| class_index(*c)).collect();
            w.bytes(&bytes);
        });
        w.pods(&m.planarity);
    }
    w.len(p.curves.len());
    for c in &p.curves {
        w.str(&c.node);
        w.str(&c.output);
        w.dvec3s(&c.polyline.points);
        w.bool(c.polyline.closed);
    }
}

pub(super) fn read_picks(r: &mut Reader) -> Res<Picks> {
    let n = r.len(8)?;
    let mut meshes = Vec::with_capacity(n);
    for _ in 0..n {
        let node = r.string()?;
        let output = r.string()?;
        let item = r.opt(Reader::usize)?;
        let geometry = match r.u8()? {
            0 => {
                let rows = r.usize()?;
                let cols = r.usize()?;
                let wrap_rows = r.bool()?;
                let wrap_cols = r.bool()?;
                let vertices = r.dvec3s()?;
                if rows.checked_mul(cols) != Some(vertices.len()) {
                    return Err(WireError("a grid's vertex count is not rows × columns"));
                }
                PickGeometry::Grid(Arc::new(QuadGrid {
                    rows,
                    cols,
                    wrap_rows,
                    wrap_cols,
                    vertices,
                    classes: Vec::new(),
                }))
            }
            1 => {
                let vertices = r.dvec3s()?;
                let indices: Vec<u32> = r.pods()?;
                let face_starts: Vec<u32> = r.pods()?;
                let ordered = face_starts.windows(2).all(|w| w[0] <= w[1])
                    && face_starts
                        .last()
                        .is_none_or(|&s| s as usize <= indices.len());
                if !ordered || indices.iter().any(|&i| i as usize >= vertices.len()) {
                    return Err(WireError("a polygon mesh's indices are out of range"));
                }
                PickGeometry::Mesh(Arc::new(PolygonMesh {
                    vertices,
                    indices,
                    face_starts,
                    parts: Default::default(),
                    classes: Vec::new(),
                }))
            }
            _ => return Err(WireError("unknown mesh kind")),
        };
        let classes = r.opt(|r| {
            r.bytes()?
                .iter()
                .map(|&k| {
                    FaceClass::ALL
                        .get(usize::from(k))
                        .copied()
                        .ok_or(WireError("unknown face class"))
                })
                .collect()
        })?;
        meshes.push(PickMesh {
            node,
            output,
            item,
            geometry,
            classes,
            planarity: r.pods()?,
        });
    }
    let n = r.len(8)?;
    let mut curves = Vec::with_capacity(n);
    for _ in 0..n {
        let node = r.string()?;
        let output = r.string()?;
        let points = r.dvec3s()?;
        let closed = r.bool()?;
        curves.push(PickCurve {
            node,
            output,
            polyline: Arc::new(Polyline { points, closed }),
        });
    }
    Ok(Picks { meshes, curves })
}
