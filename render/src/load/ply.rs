//! PLY (ASCII, binary little and big endian) through `ply-rs-bw`, into a [`Loaded`] mesh.
//!
//! The header is read first and checked before any payload: the vertex and face properties
//! this loader needs, their types, and that the declared counts fit in the bytes present, so
//! that an absurd count (`element vertex 99999999999`) is refused before anything is allocated.

use glam::{Vec2, Vec3, Vec4};
use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult, PropertyType, ScalarType,
};
use refrast::pipeline::{Mesh, Vertex};

use super::{LoadError, Loaded, finish};

/// The vertex attributes read, one slot each: position, normal, colour, uv.
const SLOTS: usize = 12;

/// The slot a vertex property fills, by the names exporters use (Blender, MeshLab, the Stanford
/// scans): `s, t`, `u, v` and `texture_u, texture_v` are all texture coordinates.
fn slot(name: &str) -> Option<usize> {
    Some(match name {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        "nx" => 3,
        "ny" => 4,
        "nz" => 5,
        "red" => 6,
        "green" => 7,
        "blue" => 8,
        "alpha" => 9,
        "s" | "u" | "texture_u" | "texture_s" => 10,
        "t" | "v" | "texture_v" | "texture_t" => 11,
        _ => return None,
    })
}

/// Whether a slot holds a colour channel.
fn is_color(slot: usize) -> bool {
    (6..10).contains(&slot)
}

/// One `vertex` element: its attribute slots, as read.
#[derive(Clone, Copy, Debug)]
struct PlyVertex([f32; SLOTS]);

impl PropertyAccess for PlyVertex {
    /// Absent colour channels read as 1 (opaque white), every other absent slot as 0.
    fn new() -> Self {
        Self([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0])
    }

    /// A `uchar` colour channel is 0..255 and scaled to `[0, 1]`; any other number is taken as it is.
    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let Some(i) = slot(name) else {
            return PropertyAccessResult::Ignored;
        };
        let value = match property {
            Property::UChar(c) if is_color(i) => f32::from(c) / 255.0,
            other => match other.to_f32_lossy() {
                Some(v) => v,
                None => return PropertyAccessResult::UnsupportedType,
            },
        };
        self.0[i] = value;
        PropertyAccessResult::Set
    }
}

/// One `face` element: its vertex indices, widened so that negative ones can be named.
#[derive(Clone, Debug)]
struct PlyFace(Vec<i64>);

impl PropertyAccess for PlyFace {
    fn new() -> Self {
        Self(Vec::new())
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        if !matches!(name, "vertex_indices" | "vertex_index") {
            return PropertyAccessResult::Ignored;
        }
        self.0 = match property {
            Property::ListChar(l) => l.into_iter().map(i64::from).collect(),
            Property::ListUChar(l) => l.into_iter().map(i64::from).collect(),
            Property::ListShort(l) => l.into_iter().map(i64::from).collect(),
            Property::ListUShort(l) => l.into_iter().map(i64::from).collect(),
            Property::ListInt(l) => l.into_iter().map(i64::from).collect(),
            Property::ListUInt(l) => l.into_iter().map(i64::from).collect(),
            _ => return PropertyAccessResult::UnsupportedType,
        };
        PropertyAccessResult::Set
    }
}

/// Any other element: read past, kept nowhere.
#[derive(Clone, Copy, Debug)]
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Self
    }
}

/// Which vertex attributes the header declares.
#[derive(Clone, Copy, Debug)]
struct Layout {
    normals: bool,
    colors: bool,
    uvs: bool,
}

/// The PLY name of a scalar type, for messages.
fn scalar_name(t: &ScalarType) -> &'static str {
    match t {
        ScalarType::Char => "char",
        ScalarType::UChar => "uchar",
        ScalarType::Short => "short",
        ScalarType::UShort => "ushort",
        ScalarType::Int => "int",
        ScalarType::UInt => "uint",
        ScalarType::Float => "float",
        ScalarType::Double => "double",
    }
}

/// The PLY spelling of a property type, for messages.
fn type_name(t: &PropertyType) -> String {
    match t {
        PropertyType::Scalar(s) => scalar_name(s).to_owned(),
        PropertyType::List(n, s) => format!("list {} {}", scalar_name(n), scalar_name(s)),
    }
}

/// Checks the header's `vertex` and `face` elements and says which attributes it gives.
fn layout(header: &Header) -> Result<Layout, LoadError> {
    let vertex = header.elements.get("vertex").ok_or(LoadError::NoVertexElement)?;
    let has = |name: &str| vertex.properties.contains_key(name);
    for axis in ["x", "y", "z"] {
        if !has(axis) {
            return Err(LoadError::MissingProperty {
                element: "vertex",
                property: axis,
                fix: "declare x, y and z",
            });
        }
    }
    let normals = ["nx", "ny", "nz"].map(has);
    if let Some(i) = normals
        .iter()
        .position(|n| !n)
        .filter(|_| normals.contains(&true))
    {
        return Err(LoadError::MissingProperty {
            element: "vertex",
            property: ["nx", "ny", "nz"][i],
            fix: "declare all of nx, ny and nz, or none",
        });
    }
    for (name, property) in &vertex.properties {
        let Some(i) = slot(name) else { continue };
        let (ok, expected) = match &property.data_type {
            PropertyType::Scalar(ScalarType::UChar | ScalarType::Float | ScalarType::Double) => (true, ""),
            PropertyType::Scalar(_) if !is_color(i) => (true, ""),
            _ if is_color(i) => (false, "uchar (0 to 255), float or double (0 to 1)"),
            _ => (false, "a number, not a list"),
        };
        if !ok {
            return Err(LoadError::PropertyType {
                element: "vertex",
                property: name.clone(),
                found: type_name(&property.data_type),
                expected,
            });
        }
    }
    if let Some(face) = header.elements.get("face") {
        let indices = ["vertex_indices", "vertex_index"]
            .iter()
            .find_map(|n| face.properties.get(*n))
            .ok_or(LoadError::MissingProperty {
                element: "face",
                property: "vertex_indices",
                fix: "declare 'property list uchar int vertex_indices'",
            })?;
        if !matches!(&indices.data_type, PropertyType::List(_, s) if !matches!(s, ScalarType::Float | ScalarType::Double))
        {
            return Err(LoadError::PropertyType {
                element: "face",
                property: indices.name.clone(),
                found: type_name(&indices.data_type),
                expected: "a list of integers (list uchar int)",
            });
        }
    }
    Ok(Layout {
        normals: normals[0],
        colors: ["red", "green", "blue"].iter().any(|n| has(n)),
        uvs: vertex.properties.keys().any(|n| slot(n).is_some_and(|i| i >= 10)),
    })
}

/// The fewest bytes one element of `def` takes: a character per value in ASCII (and at
/// least its line's end), the scalars and list counts in binary; never less than one, so that
/// even an element without properties cannot be declared more often than there are bytes.
fn min_element_bytes(def: &ElementDef, encoding: Encoding) -> u128 {
    let size = |s: &ScalarType| match s {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    };
    let bytes: u128 = match encoding {
        Encoding::Ascii => def.properties.len() as u128,
        Encoding::BinaryBigEndian | Encoding::BinaryLittleEndian => def
            .properties
            .values()
            .map(|p| match &p.data_type {
                PropertyType::Scalar(s) | PropertyType::List(s, _) => size(s),
            })
            .sum(),
    };
    bytes.max(1)
}

/// Refuses a header whose counts cannot fit in the `available` bytes after it, before any
/// allocation; and a vertex count beyond `u32` indices.
fn check_counts(header: &Header, available: usize) -> Result<(), LoadError> {
    let mut needed: u128 = 0;
    for def in header.elements.values() {
        needed = needed
            .saturating_add((def.count as u128).saturating_mul(min_element_bytes(def, header.encoding)));
        if needed > available as u128 {
            return Err(LoadError::CountExceedsData {
                element: def.name.clone(),
                count: def.count,
                needed,
                available,
            });
        }
    }
    match header.elements.get("vertex") {
        Some(v) if v.count == 0 => Err(LoadError::NoVertices),
        Some(v) if u32::try_from(v.count).is_err() => Err(LoadError::TooManyVertices { count: v.count }),
        _ => Ok(()),
    }
}

/// The crate's error on one line (its messages span several, with tabs).
fn parse_error(e: &ParseError) -> LoadError {
    let text = e.to_string();
    let text = text
        .strip_prefix(&format!("Line {}: ", e.line().unwrap_or(0)))
        .unwrap_or(&text);
    let mut message = text.split_whitespace().collect::<Vec<_>>().join(" ");
    if message.len() > 240 {
        let cut = (0..=240)
            .rev()
            .find(|&i| message.is_char_boundary(i))
            .unwrap_or(0);
        message.truncate(cut);
        message.push('…');
    }
    LoadError::Ply {
        line: e.line(),
        message,
    }
}

/// Reads a PLY file (ASCII or binary) into a mesh; polygons are fan-triangulated.
pub fn parse_ply(bytes: &[u8]) -> Result<Loaded, LoadError> {
    let mut reader = Reader::new(bytes);
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| parse_error(&e))?;
    let layout = layout(&header)?;
    check_counts(&header, reader.get_ref().len())?;
    let (mut vertices, mut faces) = (Vec::new(), Vec::new());
    for (name, def) in &header.elements {
        let read = match name.as_str() {
            "vertex" => Parser::<PlyVertex>::new()
                .read_payload_for_element(&mut reader, def, &header)
                .map(|v| vertices = v),
            "face" => Parser::<PlyFace>::new()
                .read_payload_for_element(&mut reader, def, &header)
                .map(|f| faces = f),
            _ => Parser::<Skip>::new()
                .read_payload_for_element(&mut reader, def, &header)
                .map(drop),
        };
        read.map_err(|e| parse_error(&e))?;
    }
    let rest = reader.get_ref();
    let left = match header.encoding {
        Encoding::Ascii => rest.iter().filter(|b| !b.is_ascii_whitespace()).count(),
        Encoding::BinaryBigEndian | Encoding::BinaryLittleEndian => rest.len(),
    };
    if left > 0 {
        return Err(LoadError::TrailingData { bytes: left });
    }
    let mesh = Mesh {
        vertices: vertices.iter().map(vertex).collect(),
        triangles: triangulate(&faces, vertices.len())?,
    };
    finish(Loaded {
        mesh,
        has_normals: layout.normals,
        has_colors: layout.colors,
        has_uvs: layout.uvs,
    })
}

/// A read vertex as refrast's (absent attributes are filled in by [`PlyVertex::new`]).
fn vertex(v: &PlyVertex) -> Vertex {
    let s = v.0;
    Vertex {
        position: Vec3::new(s[0], s[1], s[2]),
        normal: Vec3::new(s[3], s[4], s[5]),
        color: Vec4::new(s[6], s[7], s[8], s[9]),
        uv: Vec2::new(s[10], s[11]),
    }
}

/// Faces to triangles, fanning each polygon from its first corner, indices checked.
fn triangulate(faces: &[PlyFace], vertices: usize) -> Result<Vec<[u32; 3]>, LoadError> {
    let mut triangles = Vec::with_capacity(faces.len());
    for (face, PlyFace(corners)) in faces.iter().enumerate() {
        if corners.len() < 3 {
            return Err(LoadError::ShortFace {
                face,
                corners: corners.len(),
            });
        }
        let mut index = Vec::with_capacity(corners.len());
        for &i in corners {
            if i < 0 {
                return Err(LoadError::NegativeIndex { face, index: i });
            }
            match u32::try_from(i) {
                Ok(i) if (i as usize) < vertices => index.push(i),
                _ => {
                    return Err(LoadError::IndexOutOfRange {
                        face,
                        index: i.unsigned_abs(),
                        vertices,
                    });
                }
            }
        }
        triangles.extend((1..index.len() - 1).map(|k| [index[0], index[k], index[k + 1]]));
    }
    Ok(triangles)
}
