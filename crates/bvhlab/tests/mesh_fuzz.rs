//! `Mesh::from_obj` never panics: random bytes, and random edits of a small valid OBJ file
//! (the edits a truncated download, a bad exporter or a hand edit make). Whatever loads must
//! be a well-formed mesh.

use bvhlab::mesh::Mesh;
use bvhlab::prelude::*;
use proptest::collection::vec;
use proptest::prelude::*;

const VALID: &str = "# cube corner\nmtllib cube.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
                     v 0 0 1\nvt 0 0\nvn 0 0 1\ng side\nf 1/1/1 2/1/1 3/1/1 4/1/1\n\
                     f -1 -4 -3\nf 1//1 5//1 2//1\nl 1 5\n";

/// Pieces that make edits interesting for an OBJ reader.
const PIECES: [&str; 24] = [
    " ",
    "\n",
    "\r\n",
    "\t",
    "/",
    "//",
    "-",
    "0",
    "1",
    "-1",
    "9",
    "f",
    "v",
    "f 1 2",
    "v 1 2",
    "nan",
    "inf",
    "1e39",
    "#",
    "99999999999999999999",
    "-9223372036854775808",
    "é",
    "\0",
    "f 1 2 3 4 5 6 7 8",
];

#[derive(Debug, Clone)]
enum Edit {
    Insert(usize, usize),
    Delete(usize, usize),
    Replace(usize, u8),
    Truncate(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), 0..PIECES.len()).prop_map(|(at, p)| Edit::Insert(at, p)),
        (any::<usize>(), 1usize..12).prop_map(|(at, n)| Edit::Delete(at, n)),
        (any::<usize>(), any::<u8>()).prop_map(|(at, b)| Edit::Replace(at, b)),
        any::<usize>().prop_map(Edit::Truncate),
    ]
}

fn apply(bytes: &mut Vec<u8>, edit: &Edit) {
    let at = |i: usize, len: usize| if len == 0 { 0 } else { i % (len + 1) };
    match *edit {
        Edit::Insert(i, p) => {
            let i = at(i, bytes.len());
            bytes.splice(i..i, PIECES[p].bytes());
        }
        Edit::Delete(i, n) => {
            let i = at(i, bytes.len());
            bytes.drain(i..(i + n).min(bytes.len()));
        }
        Edit::Replace(i, b) => {
            if !bytes.is_empty() {
                let i = i % bytes.len();
                bytes[i] = b;
            }
        }
        Edit::Truncate(i) => bytes.truncate(at(i, bytes.len())),
    }
}

/// What any successfully loaded mesh must satisfy.
fn assert_well_formed(mesh: &Mesh) {
    let n = mesh.positions().len();
    assert!(mesh.positions().iter().all(|p| p.is_finite()));
    assert_eq!(mesh.indices().len(), mesh.triangles().len());
    for (t, corners) in mesh.triangles().iter().zip(mesh.indices()) {
        assert!(corners.iter().all(|&i| (i as usize) < n));
        let p = |k: usize| mesh.positions()[corners[k] as usize];
        assert_eq!(*t, Triangle3::new(p(0), p(1), p(2)));
    }
    let stats = mesh.summary();
    assert!(stats.degenerate_triangles <= stats.triangles);
    assert!(stats.triangles >= stats.faces);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn random_bytes_never_panic(bytes in vec(any::<u8>(), 0..2048)) {
        if let Ok(mesh) = Mesh::from_obj(&bytes) {
            assert_well_formed(&mesh);
        }
    }

    #[test]
    fn random_text_never_panics(text in "[vf0-9 /\\-.#\n]{0,400}") {
        if let Ok(mesh) = Mesh::from_obj(text.as_bytes()) {
            assert_well_formed(&mesh);
        }
    }

    #[test]
    fn edited_obj_files_never_panic(edits in vec(edit(), 1..8)) {
        let mut bytes = VALID.as_bytes().to_vec();
        for e in &edits {
            apply(&mut bytes, e);
        }
        match Mesh::from_obj(&bytes) {
            Ok(mesh) => assert_well_formed(&mesh),
            Err(e) => prop_assert!(e.to_string().starts_with("line "), "{}", e),
        }
    }
}

#[test]
fn the_unedited_file_loads() {
    let mesh = Mesh::from_obj(VALID.as_bytes()).expect("valid");
    assert_eq!((mesh.len(), mesh.summary().faces), (4, 3));
    assert_well_formed(&mesh);
}
