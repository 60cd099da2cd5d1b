//! PLACEHOLDER: triangle meshes from OBJ files (issue 3).
