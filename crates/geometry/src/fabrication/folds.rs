//! Fold lines and fold angles of unrolled strips (issue 43): what a brake press needs.
//!
//! Consecutive panels k − 1 and k of a strip share a rung; in the flat layout that rung is the fold
//! line (its two placed ends). The fold angle is the angle between the two panels' unit normals,
//! signed by the side the fold goes to. **Sign convention:** each panel's normal is its Newell normal
//! in the mesh's corner order, turned over when the unrolling turned the panel over (a mesh not
//! consistently oriented), so that every panel's normal points to +z in the flat layout: the flat
//! layout is the strip seen from its normal side. A fold is a **mountain** (positive angle) when the
//! next panel bends away from that side (its centroid is on the −normal side of the previous
//! panel's plane: the crease points at the viewer), a **valley** (negative) when it bends towards it.
//! A flat continuation has angle 0. `|angle|` is `atan2(|n₀ × n₁|, n₀ · n₁)` ∈ [0, π], which equals
//! the dihedral angle of the 3D net between the two panels (π minus their interior angle).

use glam::{DVec2, DVec3};

use super::panels::{StripPanels, shared_edge};
use super::polygon::newell_vector;

/// One fold of an unrolled strip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fold {
    /// The strip (index into the list of strips or pieces).
    pub strip: usize,
    /// The fold is between panel `panel − 1` and panel `panel` of the strip.
    pub panel: usize,
    /// The fold line in the flat layout (z = 0).
    pub line: [DVec3; 2],
    /// The signed fold angle in radians: mountain positive (see the module docs).
    pub angle: f64,
}

/// The normal of a panel oriented to +z in the flat layout: its 3D Newell normal, negated when the
/// flat corners run clockwise (the panel was turned over). `None` for a panel without area.
fn oriented_normal(corners: &[DVec3], flat: &[DVec3]) -> Option<DVec3> {
    let n = newell_vector(corners).try_normalize()?;
    let f: Vec<DVec2> = flat.iter().map(|p| p.truncate()).collect();
    let area2: f64 = (0..f.len())
        .map(|i| f[i].perp_dot(f[(i + 1) % f.len()]))
        .sum();
    Some(if area2 < 0.0 { -n } else { n })
}

/// The signed fold angle between two 3D panels (corners and placed corners), the second sharing the
/// edge from `p` to `q` with the first.
pub fn fold_angle(
    a: (&[DVec3], &[DVec3]),
    b: (&[DVec3], &[DVec3]),
    p: DVec3,
    q: DVec3,
) -> Option<f64> {
    let na = oriented_normal(a.0, a.1)?;
    let nb = oriented_normal(b.0, b.1)?;
    let magnitude = na.cross(nb).length().atan2(na.dot(nb));
    // How far the second panel's centroid is off the first panel's plane, measured from the fold.
    let centroid = b.0.iter().sum::<DVec3>() / b.0.len() as f64;
    let t = (q - p).normalize_or_zero();
    let mut d = centroid - p;
    d -= t * d.dot(t);
    // `0.0 - m`, not `-m`: a flat fold is +0, not −0 (written `+0.00`).
    Some(if d.dot(na) < 0.0 {
        magnitude
    } else {
        0.0 - magnitude
    })
}

/// Every fold of every strip: between each pair of consecutive panels, in strip order.
pub fn folds(strips: &[StripPanels]) -> Vec<Fold> {
    let mut out = Vec::new();
    for (s, strip) in strips.iter().enumerate() {
        for k in 1..strip.panels.len() {
            let (a, b) = (&strip.panels[k - 1], &strip.panels[k]);
            let Some(([ia, ja], _)) = shared_edge(a, b) else {
                continue;
            };
            let angle = fold_angle(
                (&a.corners, &a.flat),
                (&b.corners, &b.flat),
                a.corners[ia],
                a.corners[ja],
            )
            .unwrap_or(0.0);
            out.push(Fold {
                strip: s,
                panel: k,
                line: [a.flat[ia], a.flat[ja]],
                angle,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two unit squares along the x axis, the second turned by `angle` about the shared edge x = 1,
    /// its far edge going down (−z) for a positive angle.
    fn pair(angle: f64) -> (Vec<DVec3>, Vec<DVec3>) {
        let a = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let (s, c) = angle.sin_cos();
        let far = DVec3::new(1.0 + c, 0.0, -s);
        let b = vec![
            DVec3::new(1.0, 0.0, 0.0),
            far,
            far + DVec3::Y,
            DVec3::new(1.0, 1.0, 0.0),
        ];
        (a, b)
    }

    #[test]
    fn bending_away_from_the_normal_is_a_mountain() {
        for angle in [0.3, -0.7, 1.2] {
            let (a, b) = pair(angle);
            // Counter-clockwise seen from +z: the flat layout is the 3D panel itself for `a`.
            let fa = a.clone();
            let fb: Vec<DVec3> = [1.0, 2.0, 2.0, 1.0]
                .iter()
                .zip([0.0, 0.0, 1.0, 1.0])
                .map(|(&x, y)| DVec3::new(x, y, 0.0))
                .collect();
            let got = fold_angle((&a, &fa), (&b, &fb), a[1], a[2]).unwrap();
            assert!((got - angle).abs() < 1e-12, "{got} vs {angle}");
        }
    }
}
