//! What the view draws: the scene from the last evaluation, what it drew by node, its figures,
//! and the guides and highlights handed to the GPU with it.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use cnets_geometry::DVec3;
use cnets_render::{Bounds, Color, Scene, Segment};

use super::gpu::Guides;
use crate::preview::{Picks, PreviewStats};

/// The colour of fold outlines.
const FOLD_OUTLINE: Color = Color::rgb(0xff, 0x6a, 0x00);

/// The scene shown and what was handed to the GPU.
pub struct Drawn {
    /// The scene from the last finished evaluation.
    pub scene: Arc<Scene>,
    /// Bumped by every new scene.
    pub version: u64,
    /// Figures of the scene.
    pub stats: PreviewStats,
    /// What the scene drew, by node.
    pub picks: Arc<Picks>,
    /// The box of the drawn surfaces and curves (markers such as apices left out).
    pub bounds: Option<Bounds>,
    /// Scene versions handed to the GPU (one per frame at most): the app reads it to know when a
    /// change reached the picture.
    pub handed_version: u64,
    /// The folded faces are outlined (the legend's fold entry).
    pub folds_shown: bool,
    /// The outlines drawn on top (the folds, while shown).
    pub highlight: Arc<Vec<Segment>>,
    /// Pictures rendered by the GPU (see [`Drawn::pictures_rendered`]).
    pub(super) pictures: Arc<AtomicU64>,
    /// The grid and highlight segments handed to the GPU.
    pub(super) guides: Guides,
    /// What the guides were made for (camera, size, grid shown, plane, highlight).
    pub(super) guides_key: Option<GuidesKey>,
}

/// What the guides depend on: the camera, the picture's size in pixels, whether the grid is
/// shown, the construction plane and the highlight's identity.
pub(super) type GuidesKey = (cnets_render::Camera, [u32; 2], bool, super::CPlane, usize);

impl Default for Drawn {
    fn default() -> Self {
        Self {
            scene: Arc::new(Scene::new()),
            version: 0,
            stats: PreviewStats::default(),
            picks: Arc::new(Picks::default()),
            bounds: None,
            handed_version: 0,
            folds_shown: false,
            highlight: Arc::new(Vec::new()),
            pictures: Arc::default(),
            guides: Guides::default(),
            guides_key: None,
        }
    }
}

impl Drawn {
    /// Replaces the scene and what was drawn in it (fold outlines follow the new scene).
    pub(super) fn set(&mut self, scene: Arc<Scene>, stats: PreviewStats, picks: Arc<Picks>) {
        self.bounds = drawn_bounds(&scene);
        self.scene = scene;
        self.stats = stats;
        self.picks = picks;
        self.version += 1;
        if self.folds_shown {
            self.highlight = Arc::new(self.fold_outlines());
        }
    }

    /// How many pictures the GPU has rendered into the view's texture so far.
    pub fn pictures_rendered(&self) -> u64 {
        self.pictures.load(Ordering::Relaxed)
    }

    /// Outlines the faces that are not (++)(++).
    pub(super) fn outline_folds(&mut self) {
        self.folds_shown = true;
        self.highlight = Arc::new(self.fold_outlines());
    }

    /// Clears the fold outlines.
    pub(super) fn clear_folds(&mut self) {
        self.folds_shown = false;
        self.highlight = Arc::new(Vec::new());
    }

    /// Outlines of the faces that are not (++)(++), drawn on top.
    fn fold_outlines(&self) -> Vec<Segment> {
        let f = |p: DVec3| [p.x as f32, p.y as f32, p.z as f32];
        let mut segments = Vec::new();
        for (m, face) in self.picks.folded_faces() {
            let corners = self.picks.meshes[m].geometry.face_corners(face);
            for k in 0..corners.len() {
                segments.push(Segment {
                    a: f(corners[k]),
                    b: f(corners[(k + 1) % corners.len()]),
                    color: FOLD_OUTLINE,
                    width: 2.5,
                    flags: cnets_render::scene::FLAG_ON_TOP,
                });
            }
        }
        segments
    }
}

/// The box of a scene's surfaces and curves (point markers such as apices can lie far away; the
/// flat fabrication layer drawn beside the design is not part of it).
fn drawn_bounds(scene: &Scene) -> Option<Bounds> {
    let faces = scene
        .face_vertices()
        .iter()
        .map(|v| glam::Vec3::from(v.position));
    let lines = scene
        .segments()
        .iter()
        .filter(|s| s.flags & cnets_render::FLAG_BESIDE == 0)
        .flat_map(|s| [glam::Vec3::from(s.a), glam::Vec3::from(s.b)]);
    Bounds::from_points(faces.chain(lines).filter(|p| p.is_finite()))
}
