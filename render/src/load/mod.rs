//! Mesh files: PLY and OBJ, read with well-kept crates and validated.
