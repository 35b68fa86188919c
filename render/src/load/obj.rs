//! Wavefront OBJ through `tobj`: triangulated, one index per vertex, every model in one mesh.
//!
//! Material libraries are not read (`mtllib` names a file beside the OBJ, and a mesh loader
//! reading from a buffer has no directory): a missing `.mtl` is no error.

use glam::{Vec2, Vec3};
use refrast::pipeline::{Mesh, Vertex};

use super::{LoadError, Loaded, finish};

/// How the OBJ is read: polygons fanned into triangles, positions, normals and uvs under one
/// index (vertices are split where a face combines them differently).
fn options() -> tobj::LoadOptions {
    tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..tobj::LoadOptions::default()
    }
}

/// The models in `bytes`, materials ignored.
fn models(bytes: &[u8]) -> Result<Vec<tobj::Model>, tobj::LoadError> {
    let mut reader = bytes;
    tobj::load_obj_buf(&mut reader, &options(), |_| Err(tobj::LoadError::OpenFileFailed))
        .map(|(models, _materials)| models)
}

/// The 1-based line at which the file read so far first fails: `tobj` names no line, so the
/// shortest failing prefix is found by bisection over the line ends.
fn failing_line(bytes: &[u8]) -> Option<usize> {
    let ends: Vec<usize> = bytes
        .iter()
        .enumerate()
        .filter(|&(_, b)| *b == b'\n')
        .map(|(i, _)| i + 1)
        .chain((bytes.last() != Some(&b'\n')).then_some(bytes.len()))
        .collect();
    // Invariant: the first `lo` lines read, the first `hi` lines fail.
    let (mut lo, mut hi) = (0, ends.len());
    if hi == 0 || models(&bytes[..ends[hi - 1]]).is_ok() {
        return None;
    }
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if models(&bytes[..ends[mid - 1]]).is_ok() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(hi)
}

/// Refuses the face indices that `tobj` 4.0.5 overflows on, before it sees them: an index of 0,
/// a relative (negative) one reaching before the first element, or one larger than the file has
/// lines. `tobj` turns those into huge `usize`s and multiplies them (`vt * 2 + 1`,
/// `vn * 3 + 2` in its `add_vertex`), which panics under overflow checks and reads the wrong
/// element without; found by the `mesh_load` fuzz target (reproducers in
/// `fuzz/regressions/mesh_load/`). Lines are split and tokenised as `tobj` does.
fn check_face_indices(bytes: &[u8]) -> Result<(), LoadError> {
    let text = String::from_utf8_lossy(bytes);
    let lines = text.lines().count();
    // Positions, texture coordinates and normals defined so far.
    let mut defined = [0usize; 3];
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => defined[0] += 1,
            Some("vt") => defined[1] += 1,
            Some("vn") => defined[2] += 1,
            Some("f" | "l") => {
                for word in words {
                    let parts = word.split('/').enumerate().take(3);
                    for (kind, part) in parts.filter(|(_, p)| !p.is_empty()) {
                        let Ok(index) = part.parse::<isize>() else {
                            continue;
                        };
                        let reach = index.unsigned_abs();
                        let fits = match index.signum() {
                            0 => false,
                            -1 => reach <= defined[kind],
                            _ => reach <= lines,
                        };
                        if !fits {
                            let name = ["v", "vt", "vn"][kind];
                            let message = if index > 0 {
                                format!(
                                    "face index {index} is beyond any '{name}' a file of {lines} lines can define"
                                )
                            } else {
                                format!(
                                    "face index {index} names no '{name}' ({} defined so far): indices count from 1, negative ones back from the last",
                                    defined[kind]
                                )
                            };
                            return Err(LoadError::Obj {
                                line: Some(n + 1),
                                message,
                            });
                        }
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// What to fix for each of `tobj`'s errors.
fn hint(e: &tobj::LoadError) -> &'static str {
    use tobj::LoadError as E;
    match e {
        E::PositionParseError => "a 'v' line needs three numbers (x y z, optionally w or r g b)",
        E::NormalParseError => "a 'vn' line needs three numbers",
        E::TexcoordParseError => "a 'vt' line needs two numbers",
        E::FaceParseError | E::InvalidPolygon => {
            "an 'f' line needs at least three vertex references like 1, 1/2 or 1/2/3"
        }
        E::FaceVertexOutOfBounds | E::FaceTexCoordOutOfBounds | E::FaceNormalOutOfBounds => {
            "a face refers to a 'v', 'vt' or 'vn' that is not defined"
        }
        E::FaceColorOutOfBounds => "give vertex colours (v x y z r g b) on every 'v' line or on none",
        E::ReadError => "the file is not UTF-8 text",
        _ => "check the line's syntax",
    }
}

/// Reads an OBJ file into one mesh (every object and group merged).
pub fn parse_obj(bytes: &[u8]) -> Result<Loaded, LoadError> {
    check_face_indices(bytes)?;
    let models = models(bytes).map_err(|e| LoadError::Obj {
        line: failing_line(bytes),
        message: format!("{e}: {}", hint(&e)),
    })?;
    let every = |f: fn(&tobj::Mesh) -> bool| models.iter().all(|m| f(&m.mesh));
    let mut loaded = Loaded {
        mesh: Mesh::default(),
        has_normals: every(|m| !m.normals.is_empty()),
        has_colors: every(|m| !m.vertex_color.is_empty()),
        has_uvs: every(|m| !m.texcoords.is_empty()),
    };
    for tobj::Model { mesh: m, .. } in &models {
        let base = loaded.mesh.vertices.len();
        let offset = u32::try_from(base).map_err(|_| LoadError::TooManyVertices { count: base })?;
        let get3 = |a: &[f32], i: usize, or: Vec3| a.get(3 * i..3 * i + 3).map_or(or, Vec3::from_slice);
        loaded.mesh.vertices.extend((0..m.positions.len() / 3).map(|i| {
            Vertex {
                position: get3(&m.positions, i, Vec3::ZERO),
                normal: get3(&m.normals, i, Vec3::ZERO),
                color: get3(&m.vertex_color, i, Vec3::ONE).extend(1.0),
                uv: m
                    .texcoords
                    .get(2 * i..2 * i + 2)
                    .map_or(Vec2::ZERO, Vec2::from_slice),
            }
        }));
        for t in m.indices.chunks_exact(3) {
            let shifted = [t[0], t[1], t[2]].map(|i| i.checked_add(offset));
            let [Some(a), Some(b), Some(c)] = shifted else {
                return Err(LoadError::TooManyVertices {
                    count: base + m.positions.len() / 3,
                });
            };
            loaded.mesh.triangles.push([a, b, c]);
        }
    }
    finish(loaded)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failing_line_is_the_first_bad_line() {
        let obj = b"v 0 0 0\nv 1 0 0\nv x 1 0\nv 0 0 1\n";
        assert_eq!(failing_line(obj), Some(3));
    }

    #[test]
    fn failing_line_is_none_for_a_good_file() {
        assert_eq!(failing_line(b"v 0 0 0\n"), None);
    }
}
