//! Importing reference meshes (`io.read_mesh`): OBJ, STL, PLY, glTF and GLB.
//!
//! One parser per format, each a pure function from the file's bytes to [`MeshObject`]s (errors
//! name the line or byte offset); the node reads the file through the context (tracked, so a
//! re-saved file re-runs it), welds when asked and joins the objects.

pub mod gltf;
pub mod obj;
pub mod ply;
pub mod stl;

use std::path::Path;

use super::ReadError;
use cnets_engine::prelude::*;
use cnets_geometry::mesh_weld::weld;

/// One object of a mesh file: an OBJ `o`/`g` group, a glTF primitive, or the whole STL/PLY file.
#[derive(Debug, Clone)]
pub struct MeshObject {
    /// Its name in the file (may be empty).
    pub name: String,
    /// Its mesh (only the vertices its faces use).
    pub mesh: PolygonMesh,
}

/// What a mesh file holds: everything joined, and each object on its own.
#[derive(Debug, Clone)]
pub struct MeshFile {
    /// Every face of the file in one mesh (objects that share vertices share them here too).
    pub joined: PolygonMesh,
    /// The objects, in file order.
    pub objects: Vec<MeshObject>,
}

impl MeshFile {
    /// A file whose objects share no vertices: the joined mesh is their concatenation.
    pub fn from_objects(objects: Vec<MeshObject>) -> Self {
        let mut joined = PolygonMesh::new();
        for object in &objects {
            joined.append(&object.mesh);
        }
        Self { joined, objects }
    }
}

/// The formats `io.read_mesh` reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ.
    Obj,
    /// STL, ascii or binary.
    Stl,
    /// PLY, ascii or binary.
    Ply,
    /// glTF 2.0, JSON (`.gltf`) or binary (`.glb`).
    Gltf,
}

impl MeshFormat {
    /// Parses a format name or, for `auto`, guesses it from the file extension.
    pub fn resolve(name: &str, path: &str) -> Result<Self, String> {
        let (name, key) = super::format_key(name, path);
        let auto = name.is_empty() || name == "auto";
        match key.as_str() {
            "obj" => Ok(Self::Obj),
            "stl" => Ok(Self::Stl),
            "ply" => Ok(Self::Ply),
            "gltf" | "glb" => Ok(Self::Gltf),
            _ if auto => Err(format!(
                "cannot tell the format of '{path}' from its extension: set format to obj, stl, ply, gltf or glb"
            )),
            _ => Err(format!(
                "unknown format '{name}': expected auto, obj, stl, ply, gltf or glb"
            )),
        }
    }
}

node! {
    /// Reads a mesh drawn elsewhere (a reference hull, a site model): OBJ (`v` and `f` records;
    /// `o`/`g` start objects), STL (ascii and binary), PLY (ascii and binary) or glTF 2.0 (`.gltf`
    /// with its buffers, or `.glb`; node transforms applied). Polygons stay polygons (an OBJ quad
    /// stays a quad). `mesh` is everything in the file joined, `meshes` one mesh per object or glTF
    /// primitive, in file order. `weld` merges vertices closer than it (STL stores every triangle's
    /// corners apart: give a weld to get a connected mesh). A relative path is resolved against the
    /// graph file's folder (reads are allowed there and in `--allow-read` folders); a file rewritten
    /// later is read again. A malformed file is an error
    /// naming the line (text formats) or byte offset (binary ones).
    #[node(id = "io.read_mesh", category = "Import", flags(Import))]
    pub fn read_mesh[ctx](
        /// The file (relative to the graph file's folder, or absolute).
        #[ui(widget = FilePath)]
        path: k::Text,
        /// auto (from the extension), obj, stl, ply, gltf or glb.
        format: k::Choice<crate::choices::MeshFormat> = "auto",
        /// Merge vertices closer than this (optional; ≥ 0).
        weld: Option<k::Number>,
    ) -> (
        /// Everything in the file, joined.
        mesh: k::Mesh,
        /// One mesh per object (OBJ group, glTF primitive), in file order.
        meshes: k::List<k::Mesh>,
    ) {
        if path.trim().is_empty() {
            return Err("no file given: set path".into());
        }
        let format = MeshFormat::resolve(format, &path)?;
        if let Some(w) = weld
            && !(w.is_finite() && w >= 0.0)
        {
            return Err(format!("weld must be a finite number ≥ 0, got {w}").into());
        }
        // Permission, file kind, size limit and memory budget are checked by the context.
        let (file, bytes) = ctx.read_file(&path)?;
        // The reader's place (line, column) becomes fields of the error.
        let named = |e: ReadError| e.in_file(&file.display().to_string());
        let mut guard = ctx.guard(format!("reading '{}'", cnets_engine::files::excerpt(&path, 60)));
        let file_mesh = match format {
            MeshFormat::Obj => {
                let text = std::str::from_utf8(&bytes).map_err(|e| {
                    named(
                        format!("not UTF-8 text (invalid byte at offset {})", e.valid_up_to())
                            .into(),
                    )
                })?;
                obj::parse_within(text, &mut guard).map_err(named)?
            }
            MeshFormat::Stl => MeshFile::from_objects(stl::parse(&bytes).map_err(named)?),
            MeshFormat::Ply => MeshFile::from_objects(ply::parse_within(&bytes, &mut guard).map_err(named)?),
            MeshFormat::Gltf => {
                let folder = Path::new(&path).parent().unwrap_or(Path::new(""));
                let external = |uri: &str| {
                    let relative = folder.join(uri);
                    ctx.read_file(&relative.to_string_lossy())
                        .map(|(_, bytes)| bytes)
                        .map_err(|e| e.to_string())
                };
                let (objects, warnings) =
                    gltf::parse_within(&bytes, &external, &mut guard).map_err(named)?;
                for w in warnings {
                    ctx.warn(format!("{}: {w}", file.display()));
                }
                MeshFile::from_objects(objects)
            }
        };
        let MeshFile { joined, objects } = file_mesh;
        if objects.is_empty() {
            return Err(format!("{}: no faces found", file.display()).into());
        }
        let (joined, meshes) = match weld {
            Some(w) => (
                weld_mesh(&joined, w)?,
                objects
                    .iter()
                    .map(|o| weld_mesh(&o.mesh, w))
                    .collect::<Result<Vec<_>, _>>()?,
            ),
            None => (joined, objects.into_iter().map(|o| o.mesh).collect()),
        };
        Ok((joined, meshes))
    }
}

fn weld_mesh(mesh: &PolygonMesh, tolerance: f64) -> Result<PolygonMesh, NodeError> {
    Ok(weld(mesh, tolerance)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_resolve_from_names_and_extensions() {
        assert_eq!(
            MeshFormat::resolve("auto", "hull.GLB").unwrap(),
            MeshFormat::Gltf
        );
        assert_eq!(MeshFormat::resolve("", "a/b.stl").unwrap(), MeshFormat::Stl);
        assert_eq!(
            MeshFormat::resolve("PLY", "x.dat").unwrap(),
            MeshFormat::Ply
        );
        assert!(
            MeshFormat::resolve("auto", "x.dat")
                .unwrap_err()
                .contains("extension")
        );
        assert!(
            MeshFormat::resolve("fbx", "x.fbx")
                .unwrap_err()
                .contains("unknown format")
        );
    }
}
