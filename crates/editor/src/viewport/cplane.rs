//! Construction planes: the plane points are drawn on, handles move in and the grid lies in. A
//! plane has an origin and orthonormal axes `u`, `v` (right and up in the plane's own view) and
//! `normal = u × v`. The world planes XY, XZ and YZ are presets ([`CPlane::XY`], …); others are
//! made from three points ([`CPlane::from_three_points`]) or fitted through points
//! ([`CPlane::fit`]), and a graph keeps them by name (`cplanes` in the graph file).

use cnets_engine::file::NamedPlane;
use cnets_engine::numbers::snap;
use cnets_geometry::DVec3;

use super::screen::WorldPlane;

/// Why no construction plane was made.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CPlaneError {
    /// The first two of three clicked points coincide.
    #[error("the first two points coincide: pick three distinct points")]
    Coincide,
    /// Three clicked points lie on one line.
    #[error("the three points lie on one line: pick a point off it")]
    ThreeOnALine,
    /// Fewer than three points to fit through.
    #[error("a plane needs three points or more, found {0}")]
    TooFewPoints(usize),
    /// The points to fit through lie on one line.
    #[error("the points lie on one line: no plane through them")]
    OnALine,
    /// Nothing selected to fit through.
    #[error(
        "CPlane through a curve or row: select a node whose curve is previewed, or click a \
         vertex or face of a net to fit through its row"
    )]
    NothingToFit,
    /// The fit through what was selected failed.
    #[error("CPlane through {what}: {error}")]
    Through {
        /// What it went through (`row 3 of net`, `the curve of outline`).
        what: String,
        /// Why it failed.
        error: Box<CPlaneError>,
    },
}

/// A construction plane: origin and orthonormal axes (f64).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CPlane {
    /// The grid's origin.
    pub origin: DVec3,
    /// First in-plane axis (unit).
    pub u: DVec3,
    /// Second in-plane axis (unit, perpendicular to `u`).
    pub v: DVec3,
    /// The unit normal, `u × v`.
    pub normal: DVec3,
}

impl Default for CPlane {
    fn default() -> Self {
        CPlane::XY
    }
}

/// How far from unit length or perpendicular loaded axes may be and still be taken as they are.
const ORTHONORMAL_TOLERANCE: f64 = 1e-12;

impl CPlane {
    /// World XY (the Top view's and, unless set, the Perspective view's).
    pub const XY: CPlane = CPlane {
        origin: DVec3::ZERO,
        u: DVec3::X,
        v: DVec3::Y,
        normal: DVec3::Z,
    };
    /// World XZ (the Front view's).
    pub const XZ: CPlane = CPlane {
        origin: DVec3::ZERO,
        u: DVec3::X,
        v: DVec3::Z,
        normal: DVec3::NEG_Y,
    };
    /// World YZ (the Right view's).
    pub const YZ: CPlane = CPlane {
        origin: DVec3::ZERO,
        u: DVec3::Y,
        v: DVec3::Z,
        normal: DVec3::X,
    };

    /// The world planes, for menus.
    pub const ALL: [CPlane; 3] = [CPlane::XY, CPlane::XZ, CPlane::YZ];

    /// Menu label of a world plane; `"CPlane"` for any other.
    pub fn label(&self) -> &'static str {
        match *self {
            p if p == CPlane::XY => "World XY",
            p if p == CPlane::XZ => "World XZ",
            p if p == CPlane::YZ => "World YZ",
            _ => "CPlane",
        }
    }

    /// Whether this is one of the world planes.
    pub fn is_world(&self) -> bool {
        CPlane::ALL.contains(self)
    }

    /// The plane through `origin` with first axis along `u` and `v` in the plane of `u` and `v`
    /// (made perpendicular to `u` and unit; axes already orthonormal are kept bit for bit).
    /// `None` when they are (nearly) parallel, zero or not finite.
    pub fn from_axes(origin: DVec3, u: DVec3, v: DVec3) -> Option<CPlane> {
        if !(origin.is_finite() && u.is_finite() && v.is_finite()) {
            return None;
        }
        let orthonormal = (u.length() - 1.0).abs() <= ORTHONORMAL_TOLERANCE
            && (v.length() - 1.0).abs() <= ORTHONORMAL_TOLERANCE
            && u.dot(v).abs() <= ORTHONORMAL_TOLERANCE;
        let (u, v) = if orthonormal {
            (u, v)
        } else {
            let u = u.try_normalize()?;
            let v = v - u * v.dot(u);
            if v.length() <= 1e-9 * u.length().max(1.0) {
                return None;
            }
            (u, v.try_normalize()?)
        };
        let normal = u.cross(v);
        let normal = if (normal.length() - 1.0).abs() <= ORTHONORMAL_TOLERANCE {
            normal
        } else {
            normal.try_normalize()?
        };
        Some(CPlane {
            origin,
            u,
            v,
            normal,
        })
    }

    /// The plane through three points: origin at `a`, `u` towards `b`, the normal from the
    /// three. An error when they are (nearly) on one line.
    pub fn from_three_points(a: DVec3, b: DVec3, c: DVec3) -> Result<CPlane, CPlaneError> {
        let (ab, ac) = (b - a, c - a);
        let scale = ab.length().max(ac.length());
        if !(scale.is_finite() && scale > 0.0) || ab.length() <= 1e-12 * scale {
            return Err(CPlaneError::Coincide);
        }
        let n = ab.cross(ac);
        // The sine of the angle at `a` between the two directions.
        if n.length() <= 1e-9 * ab.length() * ac.length() {
            return Err(CPlaneError::ThreeOnALine);
        }
        CPlane::from_axes(a, ab, ac).ok_or(CPlaneError::ThreeOnALine)
    }

    /// The best-fit plane through `points` (least squares): origin at their centroid, normal the
    /// direction of least spread (the smallest eigenvector of their covariance), `u` the
    /// direction of most spread. An error with fewer than three points or when they lie on one
    /// line.
    pub fn fit(points: &[DVec3]) -> Result<CPlane, CPlaneError> {
        let points: Vec<DVec3> = points.iter().copied().filter(|p| p.is_finite()).collect();
        if points.len() < 3 {
            return Err(CPlaneError::TooFewPoints(points.len()));
        }
        let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
        let mut cov = [[0.0f64; 3]; 3];
        for p in &points {
            let d = (*p - centroid).to_array();
            for (i, row) in cov.iter_mut().enumerate() {
                for (j, c) in row.iter_mut().enumerate() {
                    *c += d[i] * d[j];
                }
            }
        }
        let (values, vectors) = symmetric_eigen(cov);
        // Ascending eigenvalues: the normal is the first, u the last.
        let mut order = [0, 1, 2];
        order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
        let (middle, large) = (values[order[1]], values[order[2]]);
        if large.is_nan() || large <= 0.0 || middle <= 1e-18 * large {
            return Err(CPlaneError::OnALine);
        }
        let u = vectors[order[2]];
        let normal = vectors[order[0]];
        CPlane::from_axes(centroid, u, normal.cross(u)).ok_or(CPlaneError::OnALine)
    }

    /// The plane a graph file keeps under `plane.name`; `None` when its axes make no plane.
    pub fn from_named(plane: &NamedPlane) -> Option<CPlane> {
        CPlane::from_axes(plane.origin.into(), plane.u.into(), plane.v.into())
    }

    /// This plane as a graph file keeps it, called `name`.
    pub fn named(&self, name: &str) -> NamedPlane {
        NamedPlane {
            name: name.to_string(),
            origin: self.origin.to_array(),
            u: self.u.to_array(),
            v: self.v.to_array(),
        }
    }

    /// The two in-plane axes (right and up on screen in the plane's own view) and the normal.
    pub fn axes(&self) -> (DVec3, DVec3, DVec3) {
        (self.u, self.v, self.normal)
    }

    /// The unit normal.
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// The plane through `through` parallel to this one.
    pub fn through(&self, through: DVec3) -> WorldPlane {
        WorldPlane {
            origin: through,
            normal: self.normal,
        }
    }

    /// The plane itself (through its origin).
    pub fn world(&self) -> WorldPlane {
        self.through(self.origin)
    }

    /// The plane's coordinates of `p`: along `u`, along `v` and along the normal, from the origin.
    pub fn local(&self, p: DVec3) -> DVec3 {
        let d = p - self.origin;
        DVec3::new(d.dot(self.u), d.dot(self.v), d.dot(self.normal))
    }

    /// The world point at the plane's coordinates `(a, b, c)`.
    pub fn at(&self, a: f64, b: f64, c: f64) -> DVec3 {
        self.origin + self.u * a + self.v * b + self.normal * c
    }

    /// `p` with its two in-plane coordinates (around the origin) rounded to multiples of `step`
    /// (the coordinate along the normal kept). On a world plane the other world coordinate is
    /// kept bit for bit.
    pub fn snap(&self, p: DVec3, step: f64) -> DVec3 {
        let l = self.local(p);
        let round = |x: f64| snap(x, 0.0, step);
        let q = self.at(round(l.x), round(l.y), l.z);
        if self.is_world() {
            // The world coordinate along the normal exactly as it was.
            let keep =
                |axis: f64, before: f64, after: f64| if axis != 0.0 { before } else { after };
            let n = self.normal;
            DVec3::new(
                keep(n.x, p.x, q.x),
                keep(n.y, p.y, q.y),
                keep(n.z, p.z, q.z),
            )
        } else {
            q
        }
    }

    /// `p` with its coordinate along the normal (from the origin) rounded to a multiple of
    /// `step`, the in-plane ones kept (the elevator drag's snap). On a world plane that is the
    /// world coordinate along the normal, the others kept bit for bit.
    pub fn snap_normal(&self, p: DVec3, step: f64) -> DVec3 {
        if self.is_world() {
            return snap_along(p, self.normal, step);
        }
        let c = (p - self.origin).dot(self.normal);
        p + self.normal * (snap(c, 0.0, step) - c)
    }
}

/// The eigenvalues and unit eigenvectors of a symmetric 3 × 3 matrix (cyclic Jacobi rotations).
fn symmetric_eigen(m: [[f64; 3]; 3]) -> ([f64; 3], [DVec3; 3]) {
    let mut a = m;
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..64 {
        let off = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
        let scale = a[0][0].powi(2) + a[1][1].powi(2) + a[2][2].powi(2);
        if off <= 1e-30 * scale.max(f64::MIN_POSITIVE) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A ← Jᵀ A J with J the rotation in the (p, q) plane.
            for row in &mut a {
                let (x, y) = (row[p], row[q]);
                row[p] = c * x - s * y;
                row[q] = s * x + c * y;
            }
            let (rp, rq) = (a[p], a[q]);
            a[p] = std::array::from_fn(|k| c * rp[k] - s * rq[k]);
            a[q] = std::array::from_fn(|k| s * rp[k] + c * rq[k]);
            for row in &mut v {
                let (x, y) = (row[p], row[q]);
                row[p] = c * x - s * y;
                row[q] = s * x + c * y;
            }
        }
    }
    let column = |k: usize| DVec3::new(v[0][k], v[1][k], v[2][k]).normalize();
    (
        [a[0][0], a[1][1], a[2][2]],
        [column(0), column(1), column(2)],
    )
}

/// `p` with its coordinate along the world axis `axis` (±X, ±Y or ±Z) rounded to a multiple of
/// `step`, as the shortest decimal ([`cnets_engine::numbers::snap`]).
pub fn snap_along(p: DVec3, axis: DVec3, step: f64) -> DVec3 {
    let round = |x: f64| snap(x, 0.0, step);
    let mut q = p;
    if axis.x != 0.0 {
        q.x = round(p.x);
    }
    if axis.y != 0.0 {
        q.y = round(p.y);
    }
    if axis.z != 0.0 {
        q.z = round(p.z);
    }
    q
}

#[cfg(test)]
mod tests {
    use super::super::screen::WorldRay;
    use super::*;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() <= 1e-12 * (1.0 + a.length().max(b.length()))
    }

    fn orthonormal(p: &CPlane) {
        for (x, y) in [(p.u, p.v), (p.u, p.normal), (p.v, p.normal)] {
            assert!(x.dot(y).abs() < 1e-12, "{p:?}");
        }
        for a in [p.u, p.v, p.normal] {
            assert!((a.length() - 1.0).abs() < 1e-12, "{p:?}");
        }
        assert!(close(p.u.cross(p.v), p.normal), "right-handed: {p:?}");
    }

    #[test]
    fn the_world_planes_are_presets_with_their_old_axes() {
        assert_eq!(CPlane::XY.axes(), (DVec3::X, DVec3::Y, DVec3::Z));
        assert_eq!(CPlane::XZ.axes(), (DVec3::X, DVec3::Z, DVec3::NEG_Y));
        assert_eq!(CPlane::YZ.axes(), (DVec3::Y, DVec3::Z, DVec3::X));
        for p in CPlane::ALL {
            orthonormal(&p);
            assert!(p.is_world());
            assert_eq!(
                CPlane::from_axes(p.origin, p.u, p.v),
                Some(p),
                "kept bit for bit"
            );
        }
        assert_eq!(CPlane::XZ.label(), "World XZ");
        let tilted = CPlane::from_axes(DVec3::ONE, DVec3::new(1.0, 2.0, 2.0), DVec3::Z).unwrap();
        let named = tilted.named("CPlane 1");
        assert_eq!(named.name, "CPlane 1");
        assert_eq!(
            CPlane::from_named(&named),
            Some(tilted),
            "a saved plane comes back exactly"
        );
        assert_eq!(CPlane::default(), CPlane::XY);
    }

    #[test]
    fn three_points_give_origin_u_and_normal() {
        let (a, b, c) = (
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(4.0, 2.0, 7.0),
            DVec3::new(1.0, 5.0, 3.0),
        );
        let p = CPlane::from_three_points(a, b, c).unwrap();
        orthonormal(&p);
        assert_eq!(p.origin, a);
        assert!(close(p.u, DVec3::new(0.6, 0.0, 0.8)));
        // c is on the positive v side; all three lie in the plane.
        assert!(p.local(c).y > 0.0);
        for q in [a, b, c] {
            assert!(p.local(q).z.abs() < 1e-12);
        }
        assert!(close(p.normal, (b - a).cross(c - a).normalize()));
        assert!(!p.is_world() && p.label() == "CPlane");
        let line = CPlane::from_three_points(a, b, a + (b - a) * 2.5);
        assert_eq!(line.unwrap_err(), CPlaneError::ThreeOnALine);
        assert!(CPlane::from_three_points(a, a, c).is_err());
    }

    #[test]
    fn a_fit_plane_goes_through_the_centroid_with_the_least_spread_as_normal() {
        // Points of a tilted plane with a little noise along its normal.
        let truth = CPlane::from_axes(
            DVec3::new(2.0, -1.0, 0.5),
            DVec3::new(1.0, 1.0, 0.3),
            DVec3::new(-0.2, 0.4, 1.0),
        )
        .unwrap();
        let mut points = Vec::new();
        for i in 0..7 {
            for j in 0..5 {
                let noise = if (i + j) % 2 == 0 { 1e-3 } else { -1e-3 };
                points.push(truth.at(i as f64 * 0.7 - 2.0, j as f64 * 0.4 - 1.0, noise));
            }
        }
        let fit = CPlane::fit(&points).unwrap();
        orthonormal(&fit);
        assert!(fit.normal.dot(truth.normal).abs() > 1.0 - 1e-9, "{fit:?}");
        let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
        assert!(close(fit.origin, centroid));
        // u along the longer spread (truth's u).
        assert!(fit.u.dot(truth.u).abs() > 0.99, "{fit:?}");
        // A planar polyline: every point on the fitted plane.
        let row: Vec<DVec3> = (0..6)
            .map(|k| truth.at(k as f64, (k as f64 * 0.9).sin(), 0.0))
            .collect();
        let fit = CPlane::fit(&row).unwrap();
        for p in &row {
            assert!(fit.local(*p).z.abs() < 1e-12, "{}", fit.local(*p).z);
        }
        let line: Vec<DVec3> = (0..5).map(|k| DVec3::splat(k as f64)).collect();
        assert_eq!(CPlane::fit(&line).unwrap_err(), CPlaneError::OnALine);
        assert!(CPlane::fit(&row[..2]).is_err());
    }

    #[test]
    fn a_tilted_plane_snaps_around_its_origin_and_rays_hit_it() {
        let plane = CPlane::from_three_points(
            DVec3::new(0.3, 0.1, 1.0),
            DVec3::new(3.3, 4.1, 1.0),
            DVec3::new(0.3, 0.1, 6.0),
        )
        .unwrap();
        orthonormal(&plane);
        let p = plane.at(1.26, -0.74, 0.2);
        let s = plane.snap(p, 0.5);
        let l = plane.local(s);
        assert!(
            (l.x - 1.5).abs() < 1e-12 && (l.y + 0.5).abs() < 1e-12,
            "{l:?}"
        );
        assert!((l.z - 0.2).abs() < 1e-12, "the normal coordinate kept");
        let e = plane.snap_normal(plane.at(1.0, 2.0, 0.37), 0.25);
        assert!((plane.local(e) - DVec3::new(1.0, 2.0, 0.25)).length() < 1e-12);
        let ray = WorldRay {
            origin: plane.at(0.5, 0.5, 10.0),
            direction: -plane.normal,
        };
        let hit = plane.world().hit(&ray).unwrap();
        assert!(close(hit, plane.at(0.5, 0.5, 0.0)));
        let along = WorldRay {
            origin: plane.at(0.0, 0.0, 1.0),
            direction: plane.u,
        };
        assert_eq!(plane.world().hit(&along), None, "parallel");
    }
}
