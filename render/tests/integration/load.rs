//! Mesh files: the fixtures read as they should, and every malformed file is refused with a
//! one-line message naming the problem and the place.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3, Vec4};
use refrast_render::load::{LoadError, load, parse_obj, parse_ply};

/// A fixture under `tests/data/`.
fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// The error of a file that must be refused, checked to be one line.
fn refused(result: Result<refrast_render::load::Loaded, LoadError>) -> (LoadError, String) {
    let error = result.expect_err("a malformed file must be refused");
    let message = error.to_string();
    assert!(!message.contains('\n'), "not one line: {message:?}");
    (error, message)
}

/// An ASCII PLY with `vertices` lines after a header of x, y, z and `faces` after a face list.
fn ascii_ply(vertex_count: &str, vertices: &str, face_count: &str, faces: &str) -> Vec<u8> {
    format!(
        "ply\nformat ascii 1.0\nelement vertex {vertex_count}\nproperty float x\nproperty float y\n\
         property float z\nelement face {face_count}\nproperty list uchar int vertex_indices\n\
         end_header\n{vertices}{faces}"
    )
    .into_bytes()
}

const TRIANGLE: &str = "0 0 0\n1 0 0\n0 1 0\n";

#[test]
fn ascii_cube_with_colours() {
    let loaded = load(&data("cube.ply")).expect("the cube reads");
    assert_eq!(loaded.mesh.vertices.len(), 8);
    assert_eq!(
        loaded.mesh.triangles.len(),
        12,
        "six quads fan into twelve triangles"
    );
    assert!(loaded.has_colors && !loaded.has_normals && !loaded.has_uvs);
    assert_eq!(loaded.mesh.vertices[0].color, Vec4::new(1.0, 0.0, 0.0, 1.0));
    assert_eq!(loaded.mesh.vertices[7].color, Vec4::new(0.0, 0.0, 0.0, 1.0));
    assert_eq!(loaded.mesh.vertices[6].position, Vec3::ONE);
    assert_eq!(loaded.mesh.triangles[0], [0, 1, 2]);
    assert_eq!(loaded.mesh.triangles[1], [0, 2, 3]);
    assert!(loaded.mesh.vertices.iter().all(|v| v.normal == Vec3::ZERO));
}

#[test]
fn binary_little_endian_tetrahedron() {
    let loaded = load(&data("tetra_le.ply")).expect("the tetrahedron reads");
    assert_eq!(loaded.mesh.vertices.len(), 4);
    assert_eq!(
        loaded.mesh.triangles,
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    );
    assert!(loaded.has_normals && loaded.has_colors && !loaded.has_uvs);
    let v = loaded.mesh.vertices[3];
    assert_eq!(v.position, Vec3::Z);
    assert!((v.normal.length() - 1.0).abs() < 1e-6);
    assert_eq!(v.color, Vec4::new(1.0, 0.0, 0.5, 1.0));
}

/// The binary fixture in big-endian order, written here: same mesh, other byte order.
#[test]
fn binary_big_endian_reads_like_little_endian() {
    let little = std::fs::read(data("tetra_le.ply")).expect("fixture");
    let split = little
        .windows(11)
        .position(|w| w == b"end_header\n")
        .expect("header end")
        + 11;
    let header = String::from_utf8(little[..split].to_vec())
        .expect("ascii header")
        .replace("binary_little_endian", "binary_big_endian");
    let mut big = header.into_bytes();
    let body = &little[split..];
    big.extend(body[..4 * 9 * 4].chunks(4).flat_map(|c| [c[3], c[2], c[1], c[0]]));
    for face in body[4 * 9 * 4..].chunks(13) {
        big.push(face[0]);
        big.extend(face[1..].chunks(4).flat_map(|c| [c[3], c[2], c[1], c[0]]));
    }
    let expected = load(&data("tetra_le.ply")).expect("little endian");
    assert_eq!(parse_ply(&big).expect("big endian"), expected);
}

#[test]
fn obj_with_normals_and_uv_merges_its_objects() {
    let loaded = load(&data("quad.obj")).expect("the OBJ reads, its .mtl missing");
    assert!(loaded.has_normals && loaded.has_uvs && !loaded.has_colors);
    assert_eq!(loaded.mesh.triangles.len(), 4, "two quads, two objects, one mesh");
    let n = loaded.mesh.vertices.len() as u32;
    assert!(loaded.mesh.triangles.iter().flatten().all(|&i| i < n));
    assert!(loaded.mesh.vertices.iter().all(|v| v.normal == Vec3::NEG_Z));
    assert!(loaded.mesh.vertices.iter().all(|v| v.color == Vec4::ONE));
    let right = loaded
        .mesh
        .vertices
        .iter()
        .find(|v| v.position == Vec3::new(1.0, 1.0, 0.0));
    assert_eq!(right.expect("the second object's corner").uv, Vec2::new(1.0, 1.0));
}

#[test]
fn extension_is_case_insensitive_and_unknown_ones_are_named() {
    let dir = std::env::temp_dir().join(format!("refrast-load-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let upper = dir.join("CUBE.PLY");
    std::fs::copy(data("cube.ply"), &upper).expect("copy");
    assert!(load(&upper).is_ok());
    let (_, message) = refused(load(&dir.join("cube.stl")));
    assert!(
        message.contains("cube.stl") && message.contains(".ply and .obj"),
        "{message}"
    );
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn missing_file_names_path_and_reason() {
    let path = data("no-such-mesh.ply");
    let (error, message) = refused(load(&path));
    assert!(matches!(error, LoadError::Io { .. }));
    assert!(
        message.contains("no-such-mesh.ply") && message.contains("No such file"),
        "{message}"
    );
}

#[test]
fn a_content_error_names_the_file() {
    let dir = std::env::temp_dir().join(format!("refrast-load-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("bad.obj");
    std::fs::write(&path, "v 0 0 0\nf 1 2 3\n").expect("write");
    let (_, message) = refused(load(&path));
    assert!(
        message.contains("bad.obj") && message.contains("OBJ line 2: face index 3"),
        "{message}"
    );
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn point_cloud_without_faces_is_allowed() {
    let loaded = parse_ply(&ascii_ply("3", TRIANGLE, "0", "")).expect("a point cloud reads");
    assert_eq!(loaded.mesh.vertices.len(), 3);
    assert!(loaded.mesh.triangles.is_empty());
}

#[test]
fn ply_truncated_vertices_are_refused_with_the_line() {
    let (error, message) = refused(parse_ply(&ascii_ply("5", TRIANGLE, "0", "")));
    assert!(matches!(error, LoadError::Ply { line: Some(_), .. }), "{message}");
    assert!(message.contains("expected 5, got 3"), "{message}");
}

#[test]
fn ply_truncated_binary_is_refused_before_reading() {
    let mut bytes = std::fs::read(data("tetra_le.ply")).expect("fixture");
    let header = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .expect("header end")
        + 11;
    bytes.truncate(header + 100);
    let (error, message) = refused(parse_ply(&bytes));
    assert!(
        matches!(
            error,
            LoadError::CountExceedsData {
                count: 4,
                needed: 144,
                available: 100,
                ..
            }
        ),
        "{message}"
    );
    assert!(
        message.contains("4 'vertex'") && message.contains("truncated"),
        "{message}"
    );
}

#[test]
fn ply_truncated_inside_a_face_list() {
    // The counts fit (a face's least is its list count), the lists do not.
    let mut bytes = std::fs::read(data("tetra_le.ply")).expect("fixture");
    bytes.truncate(bytes.len() - 20);
    let (error, message) = refused(parse_ply(&bytes));
    assert!(matches!(error, LoadError::Ply { .. }), "{message}");
    assert!(message.contains("'face' (expected 4, got 2)"), "{message}");
}

#[test]
fn ply_with_absurd_vertex_count_is_refused() {
    let (error, message) = refused(parse_ply(&ascii_ply("99999999999", TRIANGLE, "0", "")));
    assert!(matches!(
        error,
        LoadError::CountExceedsData {
            count: 99_999_999_999,
            ..
        }
    ));
    assert!(message.contains("99999999999 'vertex'"), "{message}");
}

#[test]
fn ply_with_absurd_count_of_an_empty_binary_element_is_refused() {
    // An element without properties takes no bytes: without a floor its count would spin.
    let bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n\
        property float y\nproperty float z\nelement nothing 18446744073709551615\nend_header\n\
        \0\0\0\0\0\0\0\0\0\0\0\0";
    let (error, message) = refused(parse_ply(bytes));
    assert!(matches!(error, LoadError::CountExceedsData { .. }), "{message}");
}

#[test]
fn ply_with_more_data_than_declared_is_refused() {
    let (error, message) = refused(parse_ply(&ascii_ply("2", TRIANGLE, "0", "")));
    assert!(matches!(error, LoadError::TrailingData { bytes: 3 }), "{message}");
    let mut bytes = std::fs::read(data("tetra_le.ply")).expect("fixture");
    bytes.extend([0; 7]);
    assert!(matches!(
        refused(parse_ply(&bytes)).0,
        LoadError::TrailingData { bytes: 7 }
    ));
}

#[test]
fn ply_non_numeric_value_names_the_line() {
    let (error, message) = refused(parse_ply(&ascii_ply("3", "0 0 0\n1 abc 0\n0 1 0\n", "0", "")));
    assert!(
        matches!(error, LoadError::Ply { line: Some(11), .. }),
        "{message}"
    );
    assert!(
        message.starts_with("PLY line 11: ") && message.contains("abc"),
        "{message}"
    );
}

#[test]
fn ply_face_index_out_of_range_names_face_index_and_count() {
    let (error, message) = refused(parse_ply(&ascii_ply("3", TRIANGLE, "2", "3 0 1 2\n3 0 1 7\n")));
    assert!(matches!(
        error,
        LoadError::IndexOutOfRange {
            face: 1,
            index: 7,
            vertices: 3
        }
    ));
    assert_eq!(
        message,
        "face 1 refers to vertex 7, but the mesh has 3 vertices (indices 0 to 2)"
    );
}

#[test]
fn ply_negative_index_is_refused() {
    let (error, message) = refused(parse_ply(&ascii_ply("3", TRIANGLE, "1", "3 0 -1 2\n")));
    assert!(
        matches!(error, LoadError::NegativeIndex { face: 0, index: -1 }),
        "{message}"
    );
}

#[test]
fn ply_face_with_two_vertices_is_refused() {
    let (error, message) = refused(parse_ply(&ascii_ply("3", TRIANGLE, "2", "3 0 1 2\n2 0 1\n")));
    assert!(
        matches!(error, LoadError::ShortFace { face: 1, corners: 2 }),
        "{message}"
    );
}

#[test]
fn ply_polygon_is_fan_triangulated() {
    let square = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
    let loaded = parse_ply(&ascii_ply("4", square, "1", "4 0 1 2 3\n")).expect("a quad reads");
    assert_eq!(loaded.mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
}

#[test]
fn ply_nan_and_infinite_coordinates_name_the_vertex() {
    // ASCII has no spelling for NaN; a number beyond f32 becomes infinite.
    let vertices = "0 0 0\n1 0 0\n0 -1e39 0\n";
    let (error, message) = refused(parse_ply(&ascii_ply("3", vertices, "0", "")));
    assert!(
        matches!(
            error,
            LoadError::NotFinite {
                vertex: 2,
                attribute: "position"
            }
        ),
        "{message}"
    );
    assert_eq!(
        message,
        "vertex 2 has a non-finite position (NaN or infinite): fix its values in the file"
    );
    for bad in [f32::NAN, f32::INFINITY] {
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n\
            property float y\nproperty float z\nend_header\n"
            .to_vec();
        bytes.extend(
            [0.0, 0.0, 0.0, 1.0, bad, 0.0]
                .iter()
                .flat_map(|f: &f32| f.to_le_bytes()),
        );
        let (error, message) = refused(parse_ply(&bytes));
        assert!(
            matches!(
                error,
                LoadError::NotFinite {
                    vertex: 1,
                    attribute: "position"
                }
            ),
            "{message}"
        );
    }
}

#[test]
fn ply_missing_coordinate_is_named() {
    let bytes =
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float z\nend_header\n0 0\n";
    let (error, message) = refused(parse_ply(bytes));
    assert!(
        matches!(error, LoadError::MissingProperty { property: "y", .. }),
        "{message}"
    );
}

#[test]
fn ply_partial_normals_are_refused() {
    let bytes = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
        property float z\nproperty float nx\nend_header\n0 0 0 1\n";
    let (error, message) = refused(parse_ply(bytes));
    assert!(
        matches!(error, LoadError::MissingProperty { property: "ny", .. }),
        "{message}"
    );
}

#[test]
fn ply_without_vertex_element_or_vertices_is_refused() {
    let bytes = b"ply\nformat ascii 1.0\nelement point 1\nproperty float x\nend_header\n0\n";
    assert!(matches!(refused(parse_ply(bytes)).0, LoadError::NoVertexElement));
    assert!(matches!(
        refused(parse_ply(&ascii_ply("0", "", "0", ""))).0,
        LoadError::NoVertices
    ));
}

#[test]
fn ply_colour_of_a_wrong_type_is_refused() {
    let bytes = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
        property float z\nproperty int red\nend_header\n0 0 0 9\n";
    let (error, message) = refused(parse_ply(bytes));
    assert!(matches!(error, LoadError::PropertyType { .. }), "{message}");
    assert!(
        message.contains("vertex.red") && message.contains("int"),
        "{message}"
    );
}

#[test]
fn ply_float_face_indices_are_refused() {
    let bytes = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
        property float z\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n\
        0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let (error, message) = refused(parse_ply(bytes));
    assert!(
        matches!(error, LoadError::PropertyType { element: "face", .. }),
        "{message}"
    );
}

#[test]
fn ply_uv_alpha_and_other_elements() {
    let bytes = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty short y\n\
        property float z\nproperty float s\nproperty float t\nproperty uchar alpha\n\
        element edge 1\nproperty int vertex1\nproperty int vertex2\n\
        element face 1\nproperty list uchar uint vertex_index\nend_header\n\
        0 0 0 0 0 255\n1 0 0 1 0 0\n0 1 0 0 1 51\n0 1\n3 0 1 2\n";
    let loaded = parse_ply(bytes).expect("reads");
    assert!(loaded.has_uvs && !loaded.has_colors);
    assert_eq!(loaded.mesh.vertices[1].uv, Vec2::new(1.0, 0.0));
    assert_eq!(loaded.mesh.vertices[2].color, Vec4::new(1.0, 1.0, 1.0, 0.2));
    assert_eq!(loaded.mesh.triangles, vec![[0, 1, 2]]);
}

#[test]
fn ply_garbage_is_refused() {
    for bytes in [&b""[..], b"ply", b"ply\n", b"solid cube\n", b"\xff\xfe\x00"] {
        let (error, message) = refused(parse_ply(bytes));
        assert!(matches!(error, LoadError::Ply { .. }), "{message}");
    }
}

#[test]
fn obj_parse_error_names_the_line() {
    let (error, message) = refused(parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n"));
    assert!(matches!(error, LoadError::Obj { line: Some(3), .. }), "{message}");
    assert!(
        message.starts_with("OBJ line 3: position parse error"),
        "{message}"
    );
}

#[test]
fn obj_face_out_of_range_names_the_line() {
    let (error, message) = refused(parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n"));
    assert!(matches!(error, LoadError::Obj { line: Some(5), .. }), "{message}");
}

#[test]
fn obj_without_vertices_is_refused() {
    assert!(matches!(
        refused(parse_obj(b"# nothing\n")).0,
        LoadError::NoVertices
    ));
}

#[test]
fn obj_nan_vertex_is_named() {
    let (error, message) = refused(parse_obj(b"v 0 0 0\nv 1 NaN 0\nv 0 1 0\nf 1 2 3\n"));
    assert!(
        matches!(error, LoadError::NotFinite { vertex: 1, .. }),
        "{message}"
    );
}

#[test]
fn obj_negative_indices_are_relative() {
    let loaded = parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n").expect("relative indices");
    assert_eq!(loaded.mesh.triangles, vec![[0, 1, 2]]);
}

#[test]
fn obj_vertex_colours_are_read() {
    let loaded = parse_obj(b"v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n").expect("reads");
    assert!(loaded.has_colors);
    assert_eq!(loaded.mesh.vertices[1].color, Vec4::new(0.0, 1.0, 0.0, 1.0));
}

#[test]
fn obj_colours_on_some_vertices_only_say_so() {
    let (error, message) = refused(parse_obj(b"v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    assert!(matches!(error, LoadError::Obj { line: Some(4), .. }), "{message}");
    assert!(message.contains("on every 'v' line or on none"), "{message}");
}

/// `tobj` 4.0.5 multiplies unchecked face indices: these panicked under overflow checks
/// (found by the `mesh_load` fuzz target; the files are in `fuzz/regressions/mesh_load/`).
#[test]
fn obj_relative_texcoord_index_before_the_first_is_refused() {
    let (error, message) = refused(parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-6 2/1 3/1\n"));
    assert!(matches!(error, LoadError::Obj { line: Some(5), .. }), "{message}");
    assert!(
        message.contains("face index -6 names no 'vt' (1 defined so far)"),
        "{message}"
    );
}

#[test]
fn obj_huge_normal_index_is_refused() {
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//7000000000000000000 2//1 3//1\n";
    let (error, message) = refused(parse_obj(obj));
    assert!(matches!(error, LoadError::Obj { line: Some(5), .. }), "{message}");
}

#[test]
fn obj_index_zero_is_refused() {
    let (error, message) = refused(parse_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/0 2 3\n"));
    assert!(matches!(error, LoadError::Obj { line: Some(5), .. }), "{message}");
    assert!(message.contains("count from 1"), "{message}");
}
