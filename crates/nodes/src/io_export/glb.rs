//! Binary glTF 2.0 (.glb) built with `gltf-json`: meshes as triangles with positions, flat normals and
//! a colour per face (every face gets its own vertices, so colours and normals are flat), line sets as
//! `LINES` primitives, polylines as `LINE_STRIP` / `LINE_LOOP`. One buffer, one buffer view per
//! accessor, every view 4-byte aligned. The scene's root node turns the Z-up model into glTF's Y-up
//! frame (a −90° rotation about x); vertex data stay in model coordinates (f32).

use cnets_geometry::fabrication::polygon::newell;
use cnets_geometry::fabrication::triangulate;
use cnets_geometry::{DVec3, Line, PolygonMesh, Polyline};
use gltf_json as json;

use super::names::ItemNames;
use json::validation::Checked::Valid;
use json::validation::USize64;

/// What goes into one .glb file.
#[derive(Debug, Clone)]
pub struct GlbScene<'a> {
    /// Meshes with one RGB colour (components in [0, 1]) per face.
    pub meshes: Vec<(&'a PolygonMesh, Vec<DVec3>)>,
    /// Line sets (e.g. node axes).
    pub lines: Vec<&'a [Line]>,
    /// Polylines (open: line strip; closed: line loop).
    pub polylines: Vec<&'a Polyline>,
    /// The items' names (the file's nodes and meshes).
    pub names: ItemNames<'a>,
}

/// Accumulates the binary buffer and the document.
struct Builder {
    root: json::Root,
    bin: Vec<u8>,
}

impl Builder {
    /// Appends a buffer view holding `bytes` (4-byte aligned).
    fn view(
        &mut self,
        bytes: &[u8],
        target: json::buffer::Target,
    ) -> json::Index<json::buffer::View> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        })
    }

    /// A VEC3 float accessor (with min/max when `bounds`).
    fn vec3(&mut self, data: &[[f32; 3]], bounds: bool) -> json::Index<json::Accessor> {
        let bytes: Vec<u8> = data
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let view = self.view(&bytes, json::buffer::Target::ArrayBuffer);
        let (min, max) = if bounds {
            let mut lo = [f32::INFINITY; 3];
            let mut hi = [f32::NEG_INFINITY; 3];
            for p in data {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            (
                Some(json::Value::from(lo.to_vec())),
                Some(json::Value::from(hi.to_vec())),
            )
        } else {
            (None, None)
        };
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: Some(USize64(0)),
            count: USize64::from(data.len()),
            component_type: Valid(json::accessor::GenericComponentType(
                json::accessor::ComponentType::F32,
            )),
            extensions: None,
            extras: Default::default(),
            type_: Valid(json::accessor::Type::Vec3),
            min,
            max,
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    /// A SCALAR u32 index accessor.
    fn indices(&mut self, data: &[u32]) -> json::Index<json::Accessor> {
        let bytes: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, json::buffer::Target::ElementArrayBuffer);
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: Some(USize64(0)),
            count: USize64::from(data.len()),
            component_type: Valid(json::accessor::GenericComponentType(
                json::accessor::ComponentType::U32,
            )),
            extensions: None,
            extras: Default::default(),
            type_: Valid(json::accessor::Type::Scalar),
            min: None,
            max: None,
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    /// Writes faces `faces` of mesh `k` as one glTF node and mesh named `name`, with a material of
    /// its own named after it (`None` when no face has area).
    fn surface(
        &mut self,
        k: usize,
        name: String,
        mesh: &PolygonMesh,
        colours: &[DVec3],
        faces: &[usize],
    ) -> Result<Option<json::Index<json::Node>>, String> {
        // Each mesh has a material of its own, named after it: a mesh of one colour (a node's
        // preview colour) has it as the material's base colour; several colours stay per vertex.
        let uniform = uniform_colour(&faces.iter().map(|&f| colours[f]).collect::<Vec<_>>());
        let mut positions = Vec::new();
        let mut normals = Vec::new();
        let mut rgb = Vec::new();
        let mut indices = Vec::new();
        let mut corners = Vec::new();
        for &f in faces {
            let face = mesh.face(f);
            corners.clear();
            corners.extend(face.iter().map(|&v| mesh.vertices[v as usize]));
            if corners.iter().any(|p| !p.is_finite()) {
                return Err(format!("mesh {k}, face {f} has a non-finite vertex"));
            }
            let Some(n) = newell(&corners) else {
                continue; // no area: nothing to draw
            };
            let c = colours[f].clamp(DVec3::ZERO, DVec3::ONE);
            let base = positions.len() as u32;
            let tris: Vec<[usize; 3]> = triangulate(&corners)
                .into_iter()
                .filter(|t| {
                    let (a, b2, c2) = (corners[t[0]], corners[t[1]], corners[t[2]]);
                    (b2 - a).cross(c2 - a).length() > 0.0
                })
                .collect();
            if tris.is_empty() {
                continue;
            }
            for p in &corners {
                positions.push(f32x3(*p));
                normals.push(f32x3(n));
                rgb.push(f32x3(c));
            }
            for t in tris {
                indices.extend(t.map(|v| base + v as u32));
            }
        }
        if indices.is_empty() {
            return Ok(None);
        }
        let pos = self.vec3(&positions, true);
        let nor = self.vec3(&normals, false);
        let mut attributes = vec![
            (json::mesh::Semantic::Positions, pos),
            (json::mesh::Semantic::Normals, nor),
        ];
        if uniform.is_none() {
            attributes.push((json::mesh::Semantic::Colors(0), self.vec3(&rgb, false)));
        }
        let idx = self.indices(&indices);
        let material = self.root.push(surface_material(name.clone(), uniform));
        let prim = primitive(attributes, Some(idx), material, json::mesh::Mode::Triangles);
        Ok(Some(self.node(name, prim)))
    }

    /// A mesh with one primitive, and a node showing it.
    fn node(&mut self, name: String, primitive: json::mesh::Primitive) -> json::Index<json::Node> {
        let mesh = self.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name.clone()),
            primitives: vec![primitive],
            weights: None,
        });
        self.root.push(json::Node {
            mesh: Some(mesh),
            name: Some(name),
            ..Default::default()
        })
    }
}

fn f32x3(p: DVec3) -> [f32; 3] {
    [p.x as f32, p.y as f32, p.z as f32]
}

fn primitive(
    attributes: Vec<(json::mesh::Semantic, json::Index<json::Accessor>)>,
    indices: Option<json::Index<json::Accessor>>,
    material: json::Index<json::Material>,
    mode: json::mesh::Mode,
) -> json::mesh::Primitive {
    json::mesh::Primitive {
        attributes: attributes.into_iter().map(|(s, a)| (Valid(s), a)).collect(),
        extensions: None,
        extras: Default::default(),
        indices,
        material: Some(material),
        mode: Valid(mode),
        targets: None,
    }
}

/// The one colour of every face of a mesh (components clamped to [0, 1]), if they share one.
fn uniform_colour(colours: &[DVec3]) -> Option<DVec3> {
    let first = colours.first()?.clamp(DVec3::ZERO, DVec3::ONE);
    colours
        .iter()
        .all(|c| c.clamp(DVec3::ZERO, DVec3::ONE) == first)
        .then_some(first)
}

/// A mesh's material: named after the mesh, double-sided, matte; its base colour the mesh's one
/// colour, else white (the vertex colours then carry the faces' colours).
fn surface_material(name: String, colour: Option<DVec3>) -> json::Material {
    let c = colour.unwrap_or(DVec3::ONE);
    json::Material {
        name: Some(name),
        double_sided: true,
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor([
                c.x as f32, c.y as f32, c.z as f32, 1.0,
            ]),
            metallic_factor: json::material::StrengthFactor(0.0),
            roughness_factor: json::material::StrengthFactor(0.8),
            ..Default::default()
        },
        ..Default::default()
    }
}

/// Encodes the scene as a binary glTF file. Fails when there is nothing to export or a coordinate
/// is not finite.
pub fn encode_glb(scene: &GlbScene<'_>) -> Result<Vec<u8>, String> {
    let mut b = Builder {
        root: json::Root {
            asset: json::Asset {
                generator: Some(format!("cnets {}", env!("CARGO_PKG_VERSION"))),
                copyright: None,
                ..Default::default()
            },
            ..Default::default()
        },
        bin: Vec::new(),
    };
    let ink = b.root.push(json::Material {
        name: Some("lines".into()),
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor([0.05, 0.05, 0.05, 1.0]),
            metallic_factor: json::material::StrengthFactor(0.0),
            ..Default::default()
        },
        ..Default::default()
    });
    let mut children = Vec::new();
    for (k, (mesh, colours)) in scene.meshes.iter().enumerate() {
        if colours.len() != mesh.face_count() {
            return Err(format!(
                "mesh {k} has {} faces but {} colours",
                mesh.face_count(),
                colours.len()
            ));
        }
        // A joined structure is written as one glTF mesh a part (`structure: wall`), so a viewer
        // lists the nets it was joined from.
        let name = scene.names.mesh(k);
        let groups: Vec<(String, Vec<usize>)> = if mesh.parts.is_empty() {
            vec![(name, (0..mesh.face_count()).collect())]
        } else {
            mesh.parts
                .names
                .iter()
                .zip(mesh.parts.faces_of_each())
                .map(|(part, faces)| (format!("{name}: {part}"), faces))
                .collect()
        };
        for (name, faces) in groups {
            if let Some(child) = b.surface(k, name, mesh, colours, &faces)? {
                children.push(child);
            }
        }
    }
    for (k, lines) in scene.lines.iter().enumerate() {
        if lines.is_empty() {
            continue;
        }
        let mut positions = Vec::with_capacity(2 * lines.len());
        for (s, l) in lines.iter().enumerate() {
            if !(l.start.is_finite() && l.end.is_finite()) {
                return Err(format!("line set {k}, segment {s} is not finite"));
            }
            positions.push(f32x3(l.start));
            positions.push(f32x3(l.end));
        }
        let pos = b.vec3(&positions, true);
        let prim = primitive(
            vec![(json::mesh::Semantic::Positions, pos)],
            None,
            ink,
            json::mesh::Mode::Lines,
        );
        children.push(b.node(scene.names.lines(k), prim));
    }
    for (k, p) in scene.polylines.iter().enumerate() {
        if p.points.len() < 2 {
            continue;
        }
        if p.points.iter().any(|q| !q.is_finite()) {
            return Err(format!("polyline {k} has a non-finite point"));
        }
        let positions: Vec<[f32; 3]> = p.points.iter().map(|q| f32x3(*q)).collect();
        let pos = b.vec3(&positions, true);
        let mode = if p.closed && p.points.len() > 2 {
            json::mesh::Mode::LineLoop
        } else {
            json::mesh::Mode::LineStrip
        };
        let prim = primitive(
            vec![(json::mesh::Semantic::Positions, pos)],
            None,
            ink,
            mode,
        );
        children.push(b.node(scene.names.polyline(k), prim));
    }
    if children.is_empty() {
        return Err("nothing to export: no mesh face, line or polyline".into());
    }
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let root_node = b.root.push(json::Node {
        children: Some(children),
        name: Some("cnets (Z up)".into()),
        rotation: Some(json::scene::UnitQuaternion([-h, 0.0, 0.0, h])),
        ..Default::default()
    });
    let scene_index = b.root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: Some("cnets".into()),
        nodes: vec![root_node],
    });
    b.root.scene = Some(scene_index);
    b.root.push(json::Buffer {
        byte_length: USize64::from(b.bin.len()),
        name: None,
        uri: None,
        extensions: None,
        extras: Default::default(),
    });
    let mut text = b.root.to_vec().map_err(|e| e.to_string())?;
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let mut bin = b.bin;
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let total = u32::try_from(total).map_err(|_| "the glTF file would exceed 4 GiB".to_string())?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    Ok(out)
}
