//! Closest points on a polygon mesh, accelerated by a bounding-volume hierarchy.
//!
//! The mesh's polygons are fanned into triangles and handed to `parry3d-f64`'s `TriMesh`, a
//! maintained BVH with exact point-to-triangle projection; every answer is mapped back to the
//! polygon the triangle came from. Building costs O(F log F), each query about O(log F).

use glam::DVec3;
use parry3d_f64::math::Vector as ParryVector;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{CompositeShapeRef, TriMesh};
use rayon::prelude::*;

use crate::{GeometryError, PolygonMesh};

fn to_parry(p: DVec3) -> ParryVector {
    ParryVector::new(p.x, p.y, p.z)
}

fn from_parry(p: ParryVector) -> DVec3 {
    DVec3::new(p.x, p.y, p.z)
}

/// The closest point of a mesh to a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosestPoint {
    /// The point on the mesh.
    pub point: DVec3,
    /// Its distance from the query point.
    pub distance: f64,
    /// The polygon it lies on (index into the mesh's faces).
    pub face: usize,
}

/// A mesh prepared for closest-point queries.
pub struct MeshQuery {
    triangles: TriMesh,
    /// The polygon of each triangle.
    face_of_triangle: Vec<u32>,
}

impl std::fmt::Debug for MeshQuery {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MeshQuery")
            .field("triangles", &self.face_of_triangle.len())
            .finish()
    }
}

impl MeshQuery {
    /// Prepares a mesh: validates it (finite vertices, valid faces, at least one face) and builds
    /// the hierarchy.
    pub fn new(mesh: &PolygonMesh) -> Result<Self, GeometryError> {
        mesh.validate()?;
        crate::error::check_finite_points("mesh", &mesh.vertices)?;
        if mesh.face_count() == 0 {
            return Err(GeometryError::Degenerate("the mesh has no faces".into()));
        }
        let mut indices = Vec::with_capacity(mesh.indices.len());
        let mut face_of_triangle = Vec::with_capacity(mesh.indices.len());
        for (k, face) in mesh.faces().enumerate() {
            for c in 1..face.len() - 1 {
                indices.push([face[0], face[c], face[c + 1]]);
                face_of_triangle.push(k as u32);
            }
        }
        let vertices = mesh.vertices.iter().map(|&p| to_parry(p)).collect();
        let triangles = TriMesh::new(vertices, indices)
            .map_err(|e| GeometryError::Degenerate(format!("the mesh cannot be indexed: {e}")))?;
        Ok(Self {
            triangles,
            face_of_triangle,
        })
    }

    /// The closest point of the mesh to `p` (`p` must be finite).
    pub fn closest(&self, p: DVec3) -> Result<ClosestPoint, GeometryError> {
        crate::curves::check_finite_vec("point", p)?;
        let query = to_parry(p);
        let (triangle, projection) = CompositeShapeRef(&self.triangles)
            .project_local_point(query, f64::MAX, false)
            .ok_or_else(|| GeometryError::Degenerate("no closest point found".into()))?;
        let point = from_parry(projection.point);
        Ok(ClosestPoint {
            point,
            distance: point.distance(p),
            face: self.face_of_triangle[triangle as usize] as usize,
        })
    }

    /// The closest point of the mesh to `p` and the triangle of the polygons' fans it lies on
    /// (its three vertex indices: a polygon `[v0, v1, …]` is fanned into `[v0, v_c, v_{c+1}]`).
    pub fn closest_triangle(&self, p: DVec3) -> Result<(ClosestPoint, [u32; 3]), GeometryError> {
        crate::curves::check_finite_vec("point", p)?;
        let (triangle, projection) = CompositeShapeRef(&self.triangles)
            .project_local_point(to_parry(p), f64::MAX, false)
            .ok_or_else(|| GeometryError::Degenerate("no closest point found".into()))?;
        let point = from_parry(projection.point);
        let hit = ClosestPoint {
            point,
            distance: point.distance(p),
            face: self.face_of_triangle[triangle as usize] as usize,
        };
        Ok((hit, self.triangles.indices()[triangle as usize]))
    }

    /// [`MeshQuery::closest_triangle`] of many query points, in order (on all threads).
    pub fn closest_triangles(
        &self,
        points: &[DVec3],
    ) -> Result<Vec<(ClosestPoint, [u32; 3])>, GeometryError> {
        crate::error::check_finite_points("points", points)?;
        points
            .par_iter()
            .map(|&p| self.closest_triangle(p))
            .collect()
    }

    /// The closest points of many query points, in order (on all threads).
    pub fn closest_all(&self, points: &[DVec3]) -> Result<Vec<ClosestPoint>, GeometryError> {
        crate::error::check_finite_points("points", points)?;
        points.par_iter().map(|&p| self.closest(p)).collect()
    }

    /// The distance from `p` to the mesh (the same as [`MeshQuery::closest`]'s).
    pub fn distance(&self, p: DVec3) -> f64 {
        self.triangles.distance_to_local_point(to_parry(p), false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::closest_point_on_triangle;

    fn grid_mesh(n: usize) -> PolygonMesh {
        let mut vertices = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
                vertices.push(DVec3::new(x, y, (3.0 * x).sin() * (2.0 * y).cos() * 0.3));
            }
        }
        let id = |i: usize, j: usize| (i * (n + 1) + j) as u32;
        let faces: Vec<Vec<u32>> = (0..n)
            .flat_map(|i| {
                (0..n).map(move |j| vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
            })
            .collect();
        PolygonMesh::from_faces(vertices, &faces).unwrap()
    }

    #[test]
    fn matches_a_brute_force_search_over_every_triangle() {
        let mesh = grid_mesh(12);
        let query = MeshQuery::new(&mesh).unwrap();
        let v = &mesh.vertices;
        let mut seed = 12345u64;
        for _ in 0..300 {
            let mut r = || {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 0.5
            };
            let p = DVec3::new(r(), r(), r());
            let brute = mesh
                .faces()
                .flat_map(|f| (1..f.len() - 1).map(move |c| [f[0], f[c], f[c + 1]]))
                .map(|t| {
                    closest_point_on_triangle(
                        p,
                        v[t[0] as usize],
                        v[t[1] as usize],
                        v[t[2] as usize],
                    )
                    .distance(p)
                })
                .fold(f64::INFINITY, f64::min);
            let hit = query.closest(p).unwrap();
            assert!(
                (hit.distance - brute).abs() <= 1e-12,
                "{} vs {brute}",
                hit.distance
            );
            // The reported face really holds the point.
            let f = mesh.face(hit.face);
            let on_face = (1..f.len() - 1)
                .map(|c| {
                    closest_point_on_triangle(
                        hit.point,
                        v[f[0] as usize],
                        v[f[c] as usize],
                        v[f[c + 1] as usize],
                    )
                    .distance(hit.point)
                })
                .fold(f64::INFINITY, f64::min);
            assert!(on_face < 1e-12, "face {} is {on_face} away", hit.face);
            assert!((query.distance(p) - hit.distance).abs() < 1e-12);
        }
    }

    #[test]
    fn bad_meshes_and_points_are_errors() {
        assert!(MeshQuery::new(&PolygonMesh::new()).is_err());
        let mesh = grid_mesh(2);
        let q = MeshQuery::new(&mesh).unwrap();
        assert!(q.closest(DVec3::new(f64::NAN, 0.0, 0.0)).is_err());
        let mut bad = mesh.clone();
        bad.vertices[0].x = f64::INFINITY;
        assert!(MeshQuery::new(&bad).is_err());
    }
}
