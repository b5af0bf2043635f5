//! The scene: a plain, GPU-ready description of what the viewport shows.
//!
//! A [`Scene`] holds flat `f32` buffers that are uploaded as they are: face vertices (position, face
//! normal, colour; one copy per face corner so faces are flat-shaded and coloured per face) with
//! triangle indices (polygons fanned), line segments (mesh edges, polylines, segments) and point
//! markers. Building one is linear in the input and reuses its allocations after [`Scene::clear`], so
//! the editor can rebuild it on every slider change.
//!
//! Non-finite input (NaN or infinite coordinates, or values too large for `f32`) is skipped, never
//! uploaded: a face with such a corner, a segment with such an end, a point. [`Scene::skipped`] counts
//! what was left out.

use bytemuck::{Pod, Zeroable};
use cnets_geometry::{DVec3, Line, PolygonMesh, Polyline, QuadGrid};
use glam::Vec3;

use crate::RenderError;
use crate::palette::{self, Color};

/// Bit of [`Segment::flags`] / [`PointInstance::flags`]: draw over everything (no depth test).
pub const FLAG_ON_TOP: u32 = 1;
/// Bit of [`PointInstance::flags`]: draw a disc instead of a square.
pub const FLAG_DISC: u32 = 2;
/// Bit of [`Segment::flags`] / [`PointInstance::flags`]: drawn beside the design (the flat
/// fabrication layer), not part of it: left out of the design's size (W × D × H). Drawn as usual.
pub const FLAG_BESIDE: u32 = 4;

/// One corner of a face as uploaded to the GPU.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable, serde::Serialize, serde::Deserialize)]
pub struct FaceVertex {
    /// World position.
    pub position: [f32; 3],
    /// Unit normal of the face (zero for a degenerate face).
    pub normal: [f32; 3],
    /// Face colour.
    pub color: Color,
    /// Depth layer of the mesh the face belongs to ([`MeshStyle::depth_layer`]): a surface of a
    /// higher layer wins where it coincides with one of a lower layer (no z-fighting).
    pub depth_layer: u32,
}

/// One line segment, drawn as a screen-space quad of `width` pixels.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable, serde::Serialize, serde::Deserialize)]
pub struct Segment {
    /// First end (world).
    pub a: [f32; 3],
    /// Second end (world).
    pub b: [f32; 3],
    /// Colour.
    pub color: Color,
    /// Width in physical pixels.
    pub width: f32,
    /// [`FLAG_ON_TOP`] or 0.
    pub flags: u32,
}

/// One point marker, drawn as a screen-facing square or disc of `size` pixels.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable, serde::Serialize, serde::Deserialize)]
pub struct PointInstance {
    /// World position.
    pub position: [f32; 3],
    /// Colour.
    pub color: Color,
    /// Side length / diameter in physical pixels.
    pub size: f32,
    /// [`FLAG_ON_TOP`] and/or [`FLAG_DISC`].
    pub flags: u32,
}

/// An axis-aligned bounding box in `f32` world coordinates.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Bounds {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Bounds {
    /// The box of a single point.
    pub fn point(p: Vec3) -> Self {
        Self { min: p, max: p }
    }

    /// The box from two opposite corners (any order).
    pub fn new(a: Vec3, b: Vec3) -> Self {
        Self {
            min: a.min(b),
            max: a.max(b),
        }
    }

    /// The box of `f64` bounds as returned by the geometry types.
    pub fn from_f64((lo, hi): (DVec3, DVec3)) -> Self {
        Self::new(lo.as_vec3(), hi.as_vec3())
    }

    /// The box of the finite points of an iterator; `None` when there are none.
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Option<Self> {
        let mut b: Option<Bounds> = None;
        for p in points.into_iter().filter(|p| p.is_finite()) {
            b = Some(b.map_or(Bounds::point(p), |b| b.including(p)));
        }
        b
    }

    /// The box grown to contain `p`.
    pub fn including(self, p: Vec3) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box containing both.
    pub fn union(self, other: Bounds) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Centre of the box.
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Edge lengths of the box.
    pub fn size(&self) -> Vec3 {
        self.max - self.min
    }

    /// Half the diagonal: the radius of the sphere around the centre through the corners.
    pub fn radius(&self) -> f32 {
        self.size().length() * 0.5
    }

    /// The eight corners.
    pub fn corners(&self) -> [Vec3; 8] {
        let (a, b) = (self.min, self.max);
        [
            Vec3::new(a.x, a.y, a.z),
            Vec3::new(b.x, a.y, a.z),
            Vec3::new(a.x, b.y, a.z),
            Vec3::new(b.x, b.y, a.z),
            Vec3::new(a.x, a.y, b.z),
            Vec3::new(b.x, a.y, b.z),
            Vec3::new(a.x, b.y, b.z),
            Vec3::new(b.x, b.y, b.z),
        ]
    }

    /// Whether `p` lies inside or on the box.
    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
}

/// How the faces of a mesh are coloured.
///
/// Faces are meant to be opaque: a colour with alpha below 255 is blended in draw order, without
/// sorting, so translucent surfaces only look right over what was drawn before them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FaceColors<'a> {
    /// One colour for every face.
    Uniform(Color),
    /// One colour per face, in face order ([`QuadGrid::quads`] order for grids).
    PerFace(&'a [Color]),
    /// One colour per mesh vertex, blended across each face (a value measured at the vertices,
    /// such as the distance to a reference surface).
    PerVertex(&'a [Color]),
}

impl Default for FaceColors<'_> {
    fn default() -> Self {
        FaceColors::Uniform(palette::SURFACE)
    }
}

/// How lines are drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineStyle {
    /// Colour.
    pub color: Color,
    /// Width in physical pixels (at least 1 is drawn).
    pub width: f32,
    /// Draw over the surfaces instead of being hidden by them.
    pub on_top: bool,
}

impl LineStyle {
    /// A depth-tested line of the given colour and width.
    pub fn new(color: Color, width: f32) -> Self {
        Self {
            color,
            width,
            on_top: false,
        }
    }

    /// The same style drawn over everything.
    pub fn on_top(mut self) -> Self {
        self.on_top = true;
        self
    }

    fn flags(&self) -> u32 {
        if self.on_top { FLAG_ON_TOP } else { 0 }
    }

    fn pixel_width(&self) -> f32 {
        if self.width.is_finite() {
            self.width.max(1.0)
        } else {
            1.0
        }
    }
}

impl Default for LineStyle {
    fn default() -> Self {
        Self::new(palette::LINE, 2.0)
    }
}

/// Shape of a point marker.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum PointShape {
    /// A screen-aligned square.
    Square,
    /// A round disc.
    #[default]
    Disc,
}

/// How points are drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointStyle {
    /// Colour.
    pub color: Color,
    /// Diameter / side in physical pixels (at least 1 is drawn).
    pub size: f32,
    /// Square or disc.
    pub shape: PointShape,
    /// Draw over the surfaces (the default for markers such as apices) instead of being hidden
    /// by them.
    pub on_top: bool,
}

impl PointStyle {
    /// A disc of the given colour and size, drawn on top of everything.
    pub fn new(color: Color, size: f32) -> Self {
        Self {
            color,
            size,
            shape: PointShape::Disc,
            on_top: true,
        }
    }

    /// The same style with another shape.
    pub fn shape(mut self, shape: PointShape) -> Self {
        self.shape = shape;
        self
    }

    /// The same style drawn over everything.
    pub fn on_top(mut self) -> Self {
        self.on_top = true;
        self
    }

    /// The same style hidden by surfaces in front of it (with a small depth bias, so points on a
    /// surface still show).
    pub fn depth_tested(mut self) -> Self {
        self.on_top = false;
        self
    }
}

impl Default for PointStyle {
    fn default() -> Self {
        Self::new(palette::POINT, 8.0)
    }
}

/// The highest depth layer: layers above it are drawn as this one. Layer k moves faces towards the
/// eye by `k ×` [`FACE_LAYER_BIAS`], which stays below the bias of lines (so edges still show).
pub const MAX_DEPTH_LAYER: u32 = 40;

/// Relative depth bias of one depth layer of faces (towards the eye): at 20 m from the camera a
/// layer is 0.4 mm nearer than the one below, far above the depth buffer's resolution and far below
/// what is seen.
pub const FACE_LAYER_BIAS: f32 = 2e-5;

/// How a mesh is drawn: face colours, optional polygon edges and its depth layer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshStyle<'a> {
    /// Face colours.
    pub faces: FaceColors<'a>,
    /// Polygon outlines (not the triangle diagonals); `None` draws no edges.
    pub edges: Option<LineStyle>,
    /// Where coincident surfaces meet, the one of the higher layer is drawn (0 … [`MAX_DEPTH_LAYER`];
    /// the preview gives each previewed node its own layer, so a net fitted onto its reference or
    /// the layers of a facade do not flicker).
    pub depth_layer: u32,
}

impl<'a> MeshStyle<'a> {
    /// Faces coloured as given, with the default edges (thin, dark).
    pub fn new(faces: FaceColors<'a>) -> Self {
        Self {
            faces,
            edges: Some(Self::default_edges()),
            depth_layer: 0,
        }
    }

    /// The same style on another depth layer (clamped to [`MAX_DEPTH_LAYER`]).
    pub fn depth_layer(mut self, layer: u32) -> Self {
        self.depth_layer = layer.min(MAX_DEPTH_LAYER);
        self
    }

    /// The default edge style: 1 px, [`palette::EDGE`].
    pub fn default_edges() -> LineStyle {
        LineStyle::new(palette::EDGE, 1.0)
    }

    /// The same style with other edges (`None`: no edges).
    pub fn edges(mut self, edges: Option<LineStyle>) -> Self {
        self.edges = edges;
        self
    }
}

impl Default for MeshStyle<'_> {
    fn default() -> Self {
        Self::new(FaceColors::default())
    }
}

impl<'a> From<FaceColors<'a>> for MeshStyle<'a> {
    fn from(faces: FaceColors<'a>) -> Self {
        Self::new(faces)
    }
}

/// What one `add_*` call of a mesh put into the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshInfo {
    /// Faces drawn.
    pub faces: usize,
    /// Triangles uploaded for them.
    pub triangles: usize,
    /// Edge segments drawn.
    pub edges: usize,
    /// Faces left out because a corner was not finite.
    pub skipped_faces: usize,
}

/// Counts of what a scene holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneStats {
    /// Triangles of all faces.
    pub triangles: usize,
    /// Line segments (mesh edges, polylines, segments).
    pub segments: usize,
    /// Point markers.
    pub points: usize,
    /// Items left out because of non-finite coordinates.
    pub skipped: usize,
}

/// The buffers of a [`Scene`], for [`Scene::from_parts`] and [`Scene::parts`]; in serde's data
/// model the GPU buffers are their bytes (`crate::scene_bytes`).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SceneParts {
    /// Background (clear) colour.
    pub background: Color,
    /// Face corners.
    #[serde(with = "crate::scene_bytes")]
    pub face_vertices: Vec<FaceVertex>,
    /// Triangle indices into `face_vertices`.
    #[serde(with = "crate::scene_bytes")]
    pub face_indices: Vec<u32>,
    /// Line segments.
    #[serde(with = "crate::scene_bytes")]
    pub segments: Vec<Segment>,
    /// Point markers.
    #[serde(with = "crate::scene_bytes")]
    pub points: Vec<PointInstance>,
    /// The box of everything drawn.
    pub bounds: Option<Bounds>,
    /// Items left out because of non-finite coordinates.
    pub skipped: usize,
}

/// A renderable scene: GPU-ready buffers plus the background colour. See the module docs.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// What is drawn: the background and the buffers.
    parts: SceneParts,
    /// Scratch: a mesh's vertices converted to f32 (NaN where not representable).
    scratch: Vec<Vec3>,
    /// Scratch: edge keys of a polygon mesh for de-duplication.
    edge_keys: Vec<u64>,
}

impl Default for Scene {
    fn default() -> Self {
        Self::new()
    }
}

/// `p` as f32, or `None` when it is not finite in f32.
#[inline]
fn to_f32(p: DVec3) -> Option<Vec3> {
    let v = p.as_vec3();
    v.is_finite().then_some(v)
}

impl Scene {
    /// An empty scene with the default background.
    pub fn new() -> Self {
        Self {
            parts: SceneParts {
                background: palette::BACKGROUND,
                ..SceneParts::default()
            },
            scratch: Vec::new(),
            edge_keys: Vec::new(),
        }
    }

    /// A scene from the buffers another scene's accessors returned ([`Scene::face_vertices`],
    /// [`Scene::face_indices`], [`Scene::segments`], [`Scene::points`], [`Scene::bounds`],
    /// [`Scene::skipped`]): a scene sent between the web page and its Web Worker. `None` when a
    /// triangle is incomplete or an index points past the face vertices.
    pub fn from_parts(parts: SceneParts) -> Option<Self> {
        let n = parts.face_vertices.len();
        if !parts.face_indices.len().is_multiple_of(3)
            || parts.face_indices.iter().any(|&i| i as usize >= n)
        {
            return None;
        }
        Some(Self {
            parts,
            scratch: Vec::new(),
            edge_keys: Vec::new(),
        })
    }

    /// Background (clear) colour of the image.
    pub fn background(&self) -> Color {
        self.parts.background
    }

    /// What is drawn: the background and the buffers (what [`Scene::from_parts`] takes back).
    pub fn parts(&self) -> &SceneParts {
        &self.parts
    }

    /// The same scene with another background colour.
    pub fn with_background(mut self, background: Color) -> Self {
        self.parts.background = background;
        self
    }

    /// Removes all content, keeping the background and the allocated capacity.
    pub fn clear(&mut self) {
        self.parts.face_vertices.clear();
        self.parts.face_indices.clear();
        self.parts.segments.clear();
        self.parts.points.clear();
        self.parts.bounds = None;
        self.parts.skipped = 0;
    }

    /// Sets `flag` on the segments and point markers added since there were `segments` and
    /// `points` of them (e.g. [`FLAG_BESIDE`] on what one part of the preview drew).
    pub fn flag_since(&mut self, segments: usize, points: usize, flag: u32) {
        self.parts
            .segments
            .iter_mut()
            .skip(segments)
            .for_each(|s| s.flags |= flag);
        self.parts
            .points
            .iter_mut()
            .skip(points)
            .for_each(|p| p.flags |= flag);
    }

    /// True when nothing would be drawn but the background.
    pub fn is_empty(&self) -> bool {
        self.parts.face_indices.is_empty()
            && self.parts.segments.is_empty()
            && self.parts.points.is_empty()
    }

    /// Bounding box of everything drawn; `None` for an empty scene.
    pub fn bounds(&self) -> Option<Bounds> {
        self.parts.bounds
    }

    /// Face corners, as uploaded.
    pub fn face_vertices(&self) -> &[FaceVertex] {
        &self.parts.face_vertices
    }

    /// Triangle indices into [`Scene::face_vertices`], three per triangle.
    pub fn face_indices(&self) -> &[u32] {
        &self.parts.face_indices
    }

    /// All line segments (mesh edges, polylines, segments), as uploaded.
    pub fn segments(&self) -> &[Segment] {
        &self.parts.segments
    }

    /// All point markers, as uploaded.
    pub fn points(&self) -> &[PointInstance] {
        &self.parts.points
    }

    /// All drawn positions: face corners, segment ends and points (e.g. for tight framing).
    pub fn positions(&self) -> impl Iterator<Item = Vec3> + '_ {
        self.parts
            .face_vertices
            .iter()
            .map(|v| Vec3::from(v.position))
            .chain(
                self.parts
                    .segments
                    .iter()
                    .flat_map(|s| [Vec3::from(s.a), Vec3::from(s.b)]),
            )
            .chain(self.parts.points.iter().map(|p| Vec3::from(p.position)))
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.parts.face_indices.len() / 3
    }

    /// Number of items left out because of non-finite coordinates.
    pub fn skipped(&self) -> usize {
        self.parts.skipped
    }

    /// Counts of what the scene holds.
    pub fn stats(&self) -> SceneStats {
        SceneStats {
            triangles: self.triangle_count(),
            segments: self.parts.segments.len(),
            points: self.parts.points.len(),
            skipped: self.parts.skipped,
        }
    }

    fn grow_bounds(&mut self, lo: Vec3, hi: Vec3) {
        let b = Bounds { min: lo, max: hi };
        self.parts.bounds = Some(self.parts.bounds.map_or(b, |old| old.union(b)));
    }

    /// Adds a quad grid: each quad two triangles, edges along the grid lines (each drawn once).
    ///
    /// `style` is a [`MeshStyle`] or just [`FaceColors`] (default edges). Per-face colours follow
    /// [`QuadGrid::quads`] order. Fails on an inconsistent grid or a wrong number of colours.
    pub fn add_quad_grid<'a>(
        &mut self,
        grid: &QuadGrid,
        style: impl Into<MeshStyle<'a>>,
    ) -> Result<MeshInfo, RenderError> {
        let style = style.into();
        grid.validate()?;
        let (qr, qc) = (grid.quad_rows(), grid.quad_cols());
        let quad_count = qr * qc;
        check_colors(&style.faces, quad_count, grid.vertices.len())?;

        let mut verts = std::mem::take(&mut self.scratch);
        verts.clear();
        verts.extend(
            grid.vertices
                .iter()
                .map(|&p| to_f32(p).unwrap_or(Vec3::NAN)),
        );
        let mut info = MeshInfo::default();
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));

        self.parts.face_vertices.reserve(quad_count * 4);
        self.parts.face_indices.reserve(quad_count * 6);
        for i in 0..qr {
            for j in 0..qc {
                let idx = grid.quad_indices(i, j);
                let c = idx.map(|k| verts[k]);
                if !c.iter().all(|p| p.is_finite()) {
                    info.skipped_faces += 1;
                    continue;
                }
                // Newell normal of a quad: cross product of the diagonals (computed in f64).
                let p = idx.map(|k| grid.vertices[k]);
                let n = (p[2] - p[0])
                    .cross(p[3] - p[1])
                    .normalize_or_zero()
                    .as_vec3();
                let base = self.parts.face_vertices.len() as u32;
                for (q, &k) in c.into_iter().zip(&idx) {
                    lo = lo.min(q);
                    hi = hi.max(q);
                    self.parts.face_vertices.push(FaceVertex {
                        position: q.to_array(),
                        normal: n.to_array(),
                        color: corner_color(&style.faces, i * qc + j, k),
                        depth_layer: style.depth_layer.min(MAX_DEPTH_LAYER),
                    });
                }
                self.parts.face_indices.extend_from_slice(&[
                    base,
                    base + 1,
                    base + 2,
                    base,
                    base + 2,
                    base + 3,
                ]);
                info.faces += 1;
                info.triangles += 2;
            }
        }

        if let Some(edge_style) = style.edges {
            let (color, width, flags) = (
                edge_style.color,
                edge_style.pixel_width(),
                edge_style.flags(),
            );
            let cols = grid.cols;
            let before = self.parts.segments.len();
            let push = |a: usize, b: usize, segs: &mut Vec<Segment>| {
                let (pa, pb) = (verts[a], verts[b]);
                if pa.is_finite() && pb.is_finite() {
                    segs.push(Segment {
                        a: pa.to_array(),
                        b: pb.to_array(),
                        color,
                        width,
                        flags,
                    });
                }
            };
            if qr > 0 {
                for i in 0..grid.rows {
                    for j in 0..qc {
                        push(
                            i * cols + j,
                            i * cols + (j + 1) % cols,
                            &mut self.parts.segments,
                        );
                    }
                }
            }
            if qc > 0 {
                for i in 0..qr {
                    for j in 0..cols {
                        push(
                            i * cols + j,
                            ((i + 1) % grid.rows) * cols + j,
                            &mut self.parts.segments,
                        );
                    }
                }
            }
            info.edges = self.parts.segments.len() - before;
            // Edges of skipped faces may still be drawn when both ends are finite: extend bounds.
            for s in &self.parts.segments[before..] {
                for q in [Vec3::from(s.a), Vec3::from(s.b)] {
                    lo = lo.min(q);
                    hi = hi.max(q);
                }
            }
        }
        self.scratch = verts;
        if lo.cmple(hi).all() {
            self.grow_bounds(lo, hi);
        }
        self.parts.skipped += info.skipped_faces;
        Ok(info)
    }

    /// Adds a polygon mesh: faces fanned into triangles, edges drawn as the polygon outlines (each
    /// shared edge once, no triangle diagonals).
    ///
    /// Fails on invalid face indices or a wrong number of per-face colours.
    pub fn add_polygon_mesh<'a>(
        &mut self,
        mesh: &PolygonMesh,
        style: impl Into<MeshStyle<'a>>,
    ) -> Result<MeshInfo, RenderError> {
        let style = style.into();
        mesh.validate()?;
        check_colors(&style.faces, mesh.face_count(), mesh.vertices.len())?;

        let mut verts = std::mem::take(&mut self.scratch);
        verts.clear();
        verts.extend(
            mesh.vertices
                .iter()
                .map(|&p| to_f32(p).unwrap_or(Vec3::NAN)),
        );
        let mut info = MeshInfo::default();
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        let mut keys = std::mem::take(&mut self.edge_keys);
        keys.clear();

        self.parts.face_vertices.reserve(mesh.indices.len());
        for (k, face) in mesh.faces().enumerate() {
            if !face.iter().all(|&v| verts[v as usize].is_finite()) {
                info.skipped_faces += 1;
                continue;
            }
            // Newell normal relative to the first corner (f64).
            let p0 = mesh.vertices[face[0] as usize];
            let mut n = DVec3::ZERO;
            for w in 1..face.len() - 1 {
                let a = mesh.vertices[face[w] as usize] - p0;
                let b = mesh.vertices[face[w + 1] as usize] - p0;
                n += a.cross(b);
            }
            let n = n.normalize_or_zero().as_vec3().to_array();
            let base = self.parts.face_vertices.len() as u32;
            for &v in face {
                let q = verts[v as usize];
                lo = lo.min(q);
                hi = hi.max(q);
                self.parts.face_vertices.push(FaceVertex {
                    position: q.to_array(),
                    normal: n,
                    color: corner_color(&style.faces, k, v as usize),
                    depth_layer: style.depth_layer.min(MAX_DEPTH_LAYER),
                });
            }
            for w in 1..face.len() as u32 - 1 {
                self.parts
                    .face_indices
                    .extend_from_slice(&[base, base + w, base + w + 1]);
            }
            info.faces += 1;
            info.triangles += face.len() - 2;
            if style.edges.is_some() {
                for w in 0..face.len() {
                    let (a, b) = (face[w], face[(w + 1) % face.len()]);
                    let (a, b) = (a.min(b), a.max(b));
                    if a != b {
                        keys.push((u64::from(a) << 32) | u64::from(b));
                    }
                }
            }
        }

        if let Some(edge_style) = style.edges {
            keys.sort_unstable();
            keys.dedup();
            let (color, width, flags) = (
                edge_style.color,
                edge_style.pixel_width(),
                edge_style.flags(),
            );
            self.parts.segments.reserve(keys.len());
            for &key in &keys {
                let (pa, pb) = (
                    verts[(key >> 32) as usize],
                    verts[(key & 0xffff_ffff) as usize],
                );
                self.parts.segments.push(Segment {
                    a: pa.to_array(),
                    b: pb.to_array(),
                    color,
                    width,
                    flags,
                });
            }
            info.edges = keys.len();
        }
        self.scratch = verts;
        self.edge_keys = keys;
        if lo.cmple(hi).all() {
            self.grow_bounds(lo, hi);
        }
        self.parts.skipped += info.skipped_faces;
        Ok(info)
    }

    /// Adds the edges of a polyline (including the closing edge of a closed one). Returns the
    /// number of segments added.
    pub fn add_polyline(&mut self, polyline: &Polyline, style: LineStyle) -> usize {
        self.add_segment_iter(polyline.edges(), style)
    }

    /// Adds line segments. Returns the number of segments added.
    pub fn add_lines(&mut self, lines: &[Line], style: LineStyle) -> usize {
        self.add_segment_iter(lines.iter().map(|l| (l.start, l.end)), style)
    }

    fn add_segment_iter(
        &mut self,
        it: impl Iterator<Item = (DVec3, DVec3)>,
        style: LineStyle,
    ) -> usize {
        let (color, width, flags) = (style.color, style.pixel_width(), style.flags());
        let before = self.parts.segments.len();
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for (a, b) in it {
            match (to_f32(a), to_f32(b)) {
                (Some(a), Some(b)) => {
                    lo = lo.min(a).min(b);
                    hi = hi.max(a).max(b);
                    self.parts.segments.push(Segment {
                        a: a.to_array(),
                        b: b.to_array(),
                        color,
                        width,
                        flags,
                    });
                }
                _ => self.parts.skipped += 1,
            }
        }
        if lo.cmple(hi).all() {
            self.grow_bounds(lo, hi);
        }
        self.parts.segments.len() - before
    }

    /// Adds point markers (e.g. cone apices). Returns the number of points added.
    pub fn add_points(&mut self, points: &[DVec3], style: PointStyle) -> usize {
        let size = if style.size.is_finite() {
            style.size.max(1.0)
        } else {
            1.0
        };
        let mut flags = if style.on_top { FLAG_ON_TOP } else { 0 };
        if style.shape == PointShape::Disc {
            flags |= FLAG_DISC;
        }
        let before = self.parts.points.len();
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for &p in points {
            match to_f32(p) {
                Some(q) => {
                    lo = lo.min(q);
                    hi = hi.max(q);
                    self.parts.points.push(PointInstance {
                        position: q.to_array(),
                        color: style.color,
                        size,
                        flags,
                    });
                }
                None => self.parts.skipped += 1,
            }
        }
        if lo.cmple(hi).all() {
            self.grow_bounds(lo, hi);
        }
        self.parts.points.len() - before
    }
}

fn check_colors(colors: &FaceColors<'_>, faces: usize, vertices: usize) -> Result<(), RenderError> {
    match colors {
        FaceColors::PerFace(cs) if cs.len() != faces => Err(RenderError::ColorCount {
            expected: faces,
            got: cs.len(),
        }),
        FaceColors::PerVertex(cs) if cs.len() != vertices => Err(RenderError::ColorCount {
            expected: vertices,
            got: cs.len(),
        }),
        _ => Ok(()),
    }
}

/// The colour of corner `vertex` of face `face`.
#[inline]
fn corner_color(colors: &FaceColors<'_>, face: usize, vertex: usize) -> Color {
    match *colors {
        FaceColors::Uniform(c) => c,
        FaceColors::PerFace(cs) => cs[face],
        FaceColors::PerVertex(cs) => cs[vertex],
    }
}
