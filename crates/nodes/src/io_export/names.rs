//! The names of exported items (a GLB's nodes and meshes, an OBJ's objects): given names in item
//! order — meshes, then line sets, then polylines —, the rest named by kind and index (`mesh 0`,
//! `lines 1`, `polyline 2`), as before names could be given.

/// Names for the items of one export.
#[derive(Debug, Clone, Copy)]
pub struct ItemNames<'a> {
    given: &'a [String],
    meshes: usize,
    line_sets: usize,
}

impl<'a> ItemNames<'a> {
    /// Names from `given` for `meshes` meshes and `line_sets` line sets, then the polylines.
    pub fn new(given: &'a [String], meshes: usize, line_sets: usize) -> Self {
        Self {
            given,
            meshes,
            line_sets,
        }
    }

    fn at(&self, k: usize, kind: &str, index: usize) -> String {
        match self.given.get(k).map(|s| s.trim()) {
            Some(name) if !name.is_empty() => name.to_string(),
            _ => format!("{kind} {index}"),
        }
    }

    /// The name of mesh `k`.
    pub fn mesh(&self, k: usize) -> String {
        self.at(k, "mesh", k)
    }

    /// The name of line set `k`.
    pub fn lines(&self, k: usize) -> String {
        self.at(self.meshes + k, "lines", k)
    }

    /// The name of polyline `k`.
    pub fn polyline(&self, k: usize) -> String {
        self.at(self.meshes + self.line_sets + k, "polyline", k)
    }
}

/// A name as one OBJ token: white space and control characters become `_` (an `o` line ends at
/// the line's end, and some readers split it at spaces).
pub fn obj_token(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_whitespace() || c.is_control() {
                '_'
            } else {
                c
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn given_names_run_over_meshes_then_lines_then_polylines() {
        let given = vec!["roof".to_string(), " ".to_string(), "axes".to_string()];
        let names = ItemNames::new(&given, 2, 1);
        assert_eq!(names.mesh(0), "roof");
        assert_eq!(names.mesh(1), "mesh 1", "a blank name falls back");
        assert_eq!(names.lines(0), "axes");
        assert_eq!(names.polyline(0), "polyline 0");
        assert_eq!(obj_token("wing a\tb\u{1b}"), "wing_a_b_");
    }
}
