//! Shared helpers of the geometry integration tests: random valid designs and independent checks.
#![allow(dead_code)]

use cnets_geometry::conenet::{
    ConstructInputs, CoplanarInputs, CtubeInputs, construct, construct_coplanar, construct_ctube,
};
use cnets_geometry::{DVec3, Polyline, QuadGrid};
use proptest::prelude::*;

/// A random but well-posed design: a gently turning directrix, a generatrix around X_0, apex values
/// near 1 and ratios near ½.
#[derive(Debug, Clone)]
pub struct Design {
    pub directrix: Polyline,
    pub generatrix: Polyline,
    /// M − 1 apex values.
    pub apex: Vec<f64>,
    /// N lists of M − 1 ratios.
    pub ratios: Vec<Vec<f64>>,
    /// M − 1 per-column ratios (for the coplanar construction).
    pub rho: Vec<f64>,
    pub tau: Vec<f64>,
    /// N lists of M − 1 perturbations added to the Monge normals.
    pub normal_noise: Vec<Vec<DVec3>>,
}

fn vec3(range: std::ops::RangeInclusive<f64>) -> impl Strategy<Value = DVec3> {
    (range.clone(), range.clone(), range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// Directrix with `m` points (open), edges of length 0.5 … 1.5 turning by at most ~35°.
pub fn directrix(m: usize) -> impl Strategy<Value = Polyline> {
    (
        vec3(-1.0..=1.0),
        prop::collection::vec((0.5..1.5f64, vec3(-0.35..=0.35)), m - 1),
    )
        .prop_map(|(d0, steps)| {
            let mut dir = (DVec3::X + d0 * 0.5).normalize();
            let mut p = DVec3::ZERO;
            let mut points = vec![p];
            for (len, turn) in steps {
                p += dir * len;
                points.push(p);
                dir = (dir + turn).normalize();
            }
            Polyline::open(points)
        })
}

/// A generatrix of `n` points around the first directrix point, in a plane roughly perpendicular to
/// the first edge, at distance 0.5 … 2 from X_0.
pub fn generatrix_for(directrix: &Polyline, n: usize) -> impl Strategy<Value = Polyline> + use<> {
    let e = (directrix.points[1] - directrix.points[0]).normalize();
    let x0 = directrix.points[0];
    let u = e.any_orthonormal_vector();
    let v = e.cross(u);
    (
        prop::collection::vec((0.5..2.0f64, 0.15..0.5f64, -0.2..0.2f64), n),
        0.0..std::f64::consts::TAU,
    )
        .prop_map(move |(pts, phi0)| {
            let mut phi = phi0;
            let points = pts
                .into_iter()
                .map(|(r, dphi, along)| {
                    phi += dphi;
                    x0 + (u * phi.cos() + v * phi.sin()) * r + e * along
                })
                .collect();
            Polyline::open(points)
        })
}

/// A random design with N ∈ 2..=`max_n` rows and M ∈ 2..=`max_m` columns.
pub fn design(max_n: usize, max_m: usize) -> impl Strategy<Value = Design> {
    (2..=max_n, 2..=max_m).prop_flat_map(|(n, m)| {
        directrix(m).prop_flat_map(move |d| {
            let g = generatrix_for(&d, n);
            let apex = prop::collection::vec(prop_oneof![Just(1.0), 0.75..1.3f64], m - 1);
            let ratios = prop::collection::vec(prop::collection::vec(0.3..0.7f64, m - 1), n);
            let rho = prop::collection::vec(0.3..0.7f64, m - 1);
            let tau = prop::collection::vec(0.3..0.7f64, m - 1);
            let noise = prop::collection::vec(prop::collection::vec(vec3(-0.3..=0.3), m - 1), n);
            (Just(d), g, apex, ratios, rho, tau, noise).prop_map(
                |(directrix, generatrix, apex, ratios, rho, tau, normal_noise)| Design {
                    directrix,
                    generatrix,
                    apex,
                    ratios,
                    rho,
                    tau,
                    normal_noise,
                },
            )
        })
    })
}

/// How far a quad is from planar, measured robustly (absolute): the distance of one vertex from the
/// plane through the other three, using the three that span the largest triangle. The distance
/// between the diagonal lines (the libigl measure) is ill-conditioned when the diagonals are nearly
/// parallel (folded quads): rounding of the coordinates alone then shows up amplified by 1/sin of
/// their angle, which random designs do produce.
pub fn plane_distance(q: [DVec3; 4]) -> f64 {
    (0..4)
        .map(|k| {
            let t: Vec<DVec3> = (0..4).filter(|&m| m != k).map(|m| q[m]).collect();
            let n = (t[1] - t[0]).cross(t[2] - t[0]);
            (n.length(), q[k] - t[0], n)
        })
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map_or(0.0, |(area, d, n)| {
            if area > 0.0 {
                d.dot(n).abs() / area
            } else {
                0.0
            }
        })
}

/// The plane of a (nearly planar) quad: through the largest of its four vertex triangles, the
/// well-conditioned choice (the diagonals' cross product is not, on folded quads). Returns a point
/// and the unit normal, or `None` for a quad with no area.
pub fn face_plane(q: [DVec3; 4]) -> Option<(DVec3, DVec3)> {
    let (area, point, n) = (0..4)
        .map(|k| {
            let t: Vec<DVec3> = (0..4).filter(|&m| m != k).map(|m| q[m]).collect();
            let n = (t[1] - t[0]).cross(t[2] - t[0]);
            (n.length(), t[0], n)
        })
        .max_by(|a, b| a.0.total_cmp(&b.0))?;
    (area > 0.0).then(|| (point, n / area))
}

/// The largest [`plane_distance`] over all quads.
pub fn max_plane_distance(mesh: &QuadGrid) -> f64 {
    mesh.quads()
        .map(|(_, q)| plane_distance(q))
        .fold(0.0, f64::max)
}

/// Largest vertex distance between two meshes of the same shape.
pub fn max_vertex_distance(a: &QuadGrid, b: &QuadGrid) -> f64 {
    assert_eq!((a.rows, a.cols), (b.rows, b.cols));
    a.vertices
        .iter()
        .zip(&b.vertices)
        .map(|(p, q)| p.distance(*q))
        .fold(0.0, f64::max)
}

/// Sine of the angle between two vectors (0 when either vanishes).
pub fn sin_angle(a: DVec3, b: DVec3) -> f64 {
    let d = a.length() * b.length();
    if d == 0.0 {
        0.0
    } else {
        a.cross(b).length() / d
    }
}

/// Every construction of `d` (results and errors alike) as text: `{:?}` prints each f64 as its
/// shortest round-trip form, so equal texts mean equal bits.
pub fn all_constructions(d: &Design) -> Vec<String> {
    let wide_ratios: Vec<Vec<f64>> = d
        .ratios
        .iter()
        .map(|row| row.iter().map(|r| 0.5 + (r - 0.5) * 2.2).collect())
        .collect();
    let ratios = ConstructInputs::new(d.directrix.clone(), d.generatrix.clone())
        .apex(d.apex.clone())
        .ratios(wide_ratios);
    let coplanar = CoplanarInputs::new(d.directrix.clone(), d.generatrix.clone())
        .apex(d.apex.clone())
        .ruling_ratios(d.rho.clone())
        .plane_ratios(d.tau.clone());
    let ctube = CtubeInputs::new(d.directrix.clone(), d.generatrix.clone()).apex(d.apex.clone());
    let mut out = vec![format!("{:?}", construct_ctube(&ctube))];
    for alpha in [-1.0, 0.0, 0.5, 1.0] {
        out.push(format!(
            "{:?}",
            construct(&ratios.clone().assistance(alpha))
        ));
        out.push(format!(
            "{:?}",
            construct_coplanar(&coplanar.clone().assistance(alpha))
        ));
    }
    out
}
