//! Mesh files: PLY and OBJ, read with well-kept crates and validated.
//!
//! [`parse_ply`] reads PLY (ASCII, binary little and big endian) with `ply-rs-bw`, [`parse_obj`]
//! reads Wavefront OBJ with `tobj`; both end in `finish`, the one place where a mesh is
//! checked (vertices present, finite attributes, indices in range) before it is handed out.
//! Winding is kept as the file has it.

mod obj;
mod ply;

use std::path::{Path, PathBuf};

use refrast::pipeline::Mesh;

pub use obj::parse_obj;
pub use ply::parse_ply;

/// A mesh read from a file, with which attributes the file carried.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Loaded {
    /// The mesh; absent attributes are filled in (see the `has_*` flags).
    pub mesh: Mesh,
    /// Whether the file gave normals; without them every normal is zero.
    pub has_normals: bool,
    /// Whether the file gave colours; without them every vertex is opaque white.
    pub has_colors: bool,
    /// Whether the file gave texture coordinates; without them every uv is zero.
    pub has_uvs: bool,
}

/// Why a mesh file could not be read: one line naming the problem, the place and the fix.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file could not be opened or read.
    #[error("cannot read {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The file's extension names no format this crate reads.
    #[error("{}: unknown mesh format; the supported extensions are .ply and .obj", path.display())]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// A readable file whose content is wrong.
    #[error("{}: {error}", path.display())]
    InFile {
        /// The file.
        path: PathBuf,
        /// What is wrong inside it.
        error: Box<LoadError>,
    },
    /// The PLY parser refused the file (syntax, a non-numeric value, an early end).
    #[error("PLY {}{message}", at_line(*line))]
    Ply {
        /// The 1-based line, where the parser knows it (ASCII files and headers).
        line: Option<usize>,
        /// The parser's message, on one line.
        message: String,
    },
    /// The OBJ parser refused the file.
    #[error("OBJ {}{message}", at_line(*line))]
    Obj {
        /// The 1-based line at which the file read so far first fails.
        line: Option<usize>,
        /// The parser's message with a hint.
        message: String,
    },
    /// The PLY header declares more elements than the bytes after it can hold.
    #[error(
        "PLY header declares {count} '{element}' elements, which need at least {needed} bytes, but only {available} bytes follow the header: the file is truncated or the count is wrong"
    )]
    CountExceedsData {
        /// The element's name.
        element: String,
        /// Its declared count.
        count: usize,
        /// The fewest bytes the declared elements (this one and those before it) take.
        needed: u128,
        /// The bytes after `end_header`.
        available: usize,
    },
    /// Bytes left over after every declared element was read.
    #[error(
        "PLY has {bytes} bytes after the last declared element: the header's counts are too small or the file has junk at its end"
    )]
    TrailingData {
        /// How many bytes are left (whitespace aside, for ASCII).
        bytes: usize,
    },
    /// The PLY header has no `element vertex`.
    #[error("PLY header has no 'element vertex': declare one with properties x, y and z")]
    NoVertexElement,
    /// An element lacks a property it needs.
    #[error("PLY element '{element}' lacks property '{property}': {fix}")]
    MissingProperty {
        /// The element.
        element: &'static str,
        /// The missing property.
        property: &'static str,
        /// What to declare.
        fix: &'static str,
    },
    /// A property has a type this loader cannot use.
    #[error("PLY property '{element}.{property}' is declared as {found}; expected {expected}")]
    PropertyType {
        /// The element.
        element: &'static str,
        /// The property.
        property: String,
        /// The declared type.
        found: String,
        /// The types accepted.
        expected: &'static str,
    },
    /// The mesh has no vertices.
    #[error("the mesh has no vertices: nothing to draw (a point cloud needs at least one vertex)")]
    NoVertices,
    /// More vertices than `u32` indices reach.
    #[error(
        "the mesh has {count} vertices, more than 32-bit indices can address ({})",
        u32::MAX
    )]
    TooManyVertices {
        /// The vertex count.
        count: usize,
    },
    /// A face with fewer than three corners.
    #[error("face {face} has {corners} vertices; a face needs at least 3")]
    ShortFace {
        /// The face's number, from 0.
        face: usize,
        /// Its corner count.
        corners: usize,
    },
    /// A face with a negative vertex index.
    #[error("face {face} has vertex index {index}; PLY indices count from 0 and cannot be negative")]
    NegativeIndex {
        /// The face's number, from 0.
        face: usize,
        /// The index.
        index: i64,
    },
    /// A face or triangle naming a vertex that does not exist.
    #[error(
        "face {face} refers to vertex {index}, but the mesh has {vertices} vertices (indices 0 to {})",
        vertices.saturating_sub(1)
    )]
    IndexOutOfRange {
        /// The face's number (a triangle's, for OBJ), from 0.
        face: usize,
        /// The index.
        index: u64,
        /// The vertex count.
        vertices: usize,
    },
    /// A vertex attribute that is NaN or infinite.
    #[error("vertex {vertex} has a non-finite {attribute} (NaN or infinite): fix its values in the file")]
    NotFinite {
        /// The vertex's number, from 0.
        vertex: usize,
        /// Which attribute: position, normal, colour or uv.
        attribute: &'static str,
    },
}

/// `"line N: "` or nothing: the place prefix of the parser errors.
fn at_line(line: Option<usize>) -> String {
    line.map_or_else(String::new, |n| format!("line {n}: "))
}

/// Reads a mesh file, choosing the format by extension (`.ply` or `.obj`, any case).
pub fn load(path: &Path) -> Result<Loaded, LoadError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let parse = match extension.as_deref() {
        Some("ply") => parse_ply,
        Some("obj") => parse_obj,
        _ => {
            return Err(LoadError::UnknownFormat {
                path: path.to_path_buf(),
            });
        }
    };
    let bytes = std::fs::read(path).map_err(|source| LoadError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse(&bytes).map_err(|error| LoadError::InFile {
        path: path.to_path_buf(),
        error: Box::new(error),
    })
}

/// The one check every loaded mesh passes: vertices present and addressable by `u32`, every
/// attribute finite, every index in range; colours are clamped to `[0, 1]` (exporters write
/// 1.0000001).
fn finish(mut loaded: Loaded) -> Result<Loaded, LoadError> {
    let vertices = &mut loaded.mesh.vertices;
    if vertices.is_empty() {
        return Err(LoadError::NoVertices);
    }
    if u32::try_from(vertices.len()).is_err() {
        return Err(LoadError::TooManyVertices {
            count: vertices.len(),
        });
    }
    for (vertex, v) in vertices.iter_mut().enumerate() {
        let attributes = [
            ("position", v.position.is_finite()),
            ("normal", v.normal.is_finite()),
            ("colour", v.color.is_finite()),
            ("uv", v.uv.is_finite()),
        ];
        if let Some((attribute, _)) = attributes.into_iter().find(|(_, finite)| !finite) {
            return Err(LoadError::NotFinite { vertex, attribute });
        }
        v.color = v.color.clamp(glam::Vec4::ZERO, glam::Vec4::ONE);
    }
    let count = vertices.len();
    for (face, triangle) in loaded.mesh.triangles.iter().enumerate() {
        if let Some(&index) = triangle.iter().find(|&&i| i as usize >= count) {
            return Err(LoadError::IndexOutOfRange {
                face,
                index: u64::from(index),
                vertices: count,
            });
        }
    }
    Ok(loaded)
}

/// Both parsers on arbitrary bytes, checking what every caller relies on: an `Ok` mesh has
/// vertices, indices below their count, finite positions. The `mesh_load` fuzz target and the
/// replay of its corpus run this; a panic inside is the other failure they look for.
pub fn check_any_bytes(bytes: &[u8]) -> Result<(), String> {
    for (format, result) in [("PLY", parse_ply(bytes)), ("OBJ", parse_obj(bytes))] {
        let Ok(loaded) = result else { continue };
        let mesh = &loaded.mesh;
        let count = mesh.vertices.len();
        if count == 0 {
            return Err(format!("{format}: accepted a mesh without vertices"));
        }
        if let Some(t) = mesh
            .triangles
            .iter()
            .find(|t| t.iter().any(|&i| i as usize >= count))
        {
            return Err(format!("{format}: triangle {t:?} indexes past {count} vertices"));
        }
        if let Some(v) = mesh.vertices.iter().position(|v| !v.position.is_finite()) {
            return Err(format!("{format}: vertex {v} has a non-finite position"));
        }
    }
    Ok(())
}
