//! The error type of the renderer.

use std::path::PathBuf;

/// Everything that can go wrong while building or rendering a scene.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No graphics adapter (GPU or software driver) could be found.
    #[error(
        "no graphics adapter available ({0}); install a Vulkan driver (e.g. `mesa-vulkan-drivers`) \
         or select a backend with WGPU_BACKEND"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("could not create a graphics device: {0}")]
    RequestDevice(String),
    /// An image or target size of zero, or larger than the device allows.
    #[error("invalid image size {width}×{height} (each side must be between 1 and {max})")]
    InvalidSize {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
        /// Largest side the device supports.
        max: u32,
    },
    /// The geometry handed to the scene is inconsistent (bad indices, wrong vertex count).
    #[error("invalid geometry: {0}")]
    Geometry(#[from] cnets_geometry::GeometryError),
    /// A per-face (per-vertex) colour list does not have one colour per face (vertex).
    #[error("{got} colours given for {expected} faces (or vertices, for per-vertex colours)")]
    ColorCount {
        /// Number of faces (vertices) of the mesh.
        expected: usize,
        /// Number of colours given.
        got: usize,
    },
    /// The GPU reported an error (validation, out of memory, internal).
    #[error("GPU error: {0}")]
    Gpu(String),
    /// Reading the rendered image back from the GPU failed.
    #[error("reading the image back from the GPU failed: {0}")]
    Readback(String),
    /// Writing or encoding a PNG failed.
    #[error("cannot write PNG {path}: {message}")]
    Png {
        /// The file that was being written.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}
