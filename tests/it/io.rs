//! The mesh-file readers: OBJ, STL (ASCII and binary), OFF, PLY (ASCII and binary), and
//! `read_mesh`.

use kepler::geometry::Point3;
use kepler::io::FileError;
use kepler::io::{obj, off, ply, read_mesh, stl};
use kepler::mesh::{Mesh, Validation};
use std::path::{Path, PathBuf};

/// The unit cube's corners, index `x + 2y + 4z`.
fn cube_vertices() -> Vec<Point3> {
    (0..8)
        .map(|i| Point3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)))
        .collect()
}

/// The unit cube's faces (0-based), counter-clockwise seen from outside.
const CUBE_FACES: [[u32; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

/// The cube's 12 triangles, each quad `a b c d` split into `a b c` and `a c d`.
fn cube_triangles() -> Vec<[Point3; 3]> {
    let v = cube_vertices();
    let p = |i: u32| v[i as usize];
    CUBE_FACES
        .iter()
        .flat_map(|&[a, b, c, d]| [[p(a), p(b), p(c)], [p(a), p(c), p(d)]])
        .collect()
}

/// Checks the unit cube: exact corners, 8 vertices, `faces` faces, closed, volume 1.
fn assert_unit_cube(mesh: &Mesh, faces: usize) {
    assert_eq!(mesh.vertices().len(), 8);
    for p in cube_vertices() {
        assert!(mesh.vertices().contains(&p), "missing corner {p}");
    }
    assert_eq!(mesh.faces().len(), faces);
    assert_eq!(mesh.triangles().len(), 12);
    assert!(mesh.topology().closed);
    assert!(mesh.is_solid());
    assert_eq!(mesh.volume(), 1.0);
}

/// The message of an error, which must be about the input: bad text, or a mesh the text
/// describes that is not valid (`FileError::Input` or `FileError::Mesh`).
fn input_error(result: Result<Mesh, FileError>) -> String {
    match result {
        Err(e @ (FileError::Input { .. } | FileError::Mesh { .. })) => e.to_string(),
        Err(e) => panic!("expected an input error, got {e:?}"),
        Ok(_) => panic!("expected an error, got a mesh"),
    }
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// A file in the temporary directory, removed when dropped.
struct TempFile(PathBuf);

impl TempFile {
    fn new(name: &str, bytes: &[u8]) -> TempFile {
        let path = std::env::temp_dir().join(format!("kepler-io-{}-{name}", std::process::id()));
        std::fs::write(&path, bytes).unwrap();
        TempFile(path)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

// ---------------------------------------------------------------------------------------
// OBJ

/// The cube as OBJ, with `corner` writing the 1-based vertex index `i` of face corner `k`
/// (0..4) of face `f` (0..6), after the 8 vertex lines.
fn cube_obj(corner: impl Fn(u32, usize, usize) -> String) -> String {
    let mut text = String::new();
    for p in cube_vertices() {
        text += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    text += "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    text += "vn 0 0 1\n";
    for (f, face) in CUBE_FACES.iter().enumerate() {
        let corners: Vec<String> = face
            .iter()
            .enumerate()
            .map(|(k, &i)| corner(i + 1, f, k))
            .collect();
        text += &format!("f {}\n", corners.join(" "));
    }
    text
}

#[test]
fn obj_cube_keeps_quads_and_exact_coordinates() {
    let mesh = obj::parse(&cube_obj(|i, _, _| i.to_string()), "cube.obj").unwrap();
    assert_unit_cube(&mesh, 6);
    assert_eq!(mesh.vertices(), &cube_vertices()[..]);
    for (f, face) in mesh.faces().iter().enumerate() {
        assert_eq!(
            face.vertices(),
            &CUBE_FACES[f][..],
            "face {f} stays the same quad"
        );
    }
}

#[test]
fn obj_negative_indices_and_slash_forms_give_the_same_mesh() {
    let plain = obj::parse(&cube_obj(|i, _, _| i.to_string()), "a.obj").unwrap();
    // 8 vertices precede every face: vertex i is -(9 - i).
    let negative = cube_obj(|i, _, _| format!("-{}", 9 - i));
    assert_eq!(obj::parse(&negative, "b.obj").unwrap(), plain);
    let full = cube_obj(|i, _, k| format!("{i}/{}/1", k + 1));
    assert_eq!(obj::parse(&full, "c.obj").unwrap(), plain);
    let mixed = cube_obj(|i, f, k| match (f + k) % 4 {
        0 => format!("{i}/{}", k + 1),
        1 => format!("{i}//1"),
        2 => format!("-{}/-{}/-1", 9 - i, 4 - k),
        _ => i.to_string(),
    });
    assert_eq!(obj::parse(&mixed, "d.obj").unwrap(), plain);
}

#[test]
fn obj_accepts_grouping_comments_continuations_and_w_1() {
    let text = "\u{feff}# header\nmtllib a.mtl\no thing\ng a b\ns 1\nusemtl red\n\
                v 0 0 0 1\nv 1 0 0 # comment\nv \\\n  0 1 0\n\n   \nvn 0 0 1\nf 1 2 \\\n 3\n";
    let mesh = obj::parse(text, "t.obj").unwrap();
    assert_eq!(mesh.vertices().len(), 3);
    assert_eq!(mesh.faces()[0].vertices(), &[0, 1, 2]);
}

#[test]
fn obj_coordinates_are_correctly_rounded_f64() {
    let text = "v 0.1 0.30000000000000004 -2.5e-300\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let mesh = obj::parse(text, "t.obj").unwrap();
    let p = mesh.vertices()[0];
    assert_eq!((p.x, p.y, p.z), (0.1, 0.1 + 0.2, -2.5e-300));
    assert_ne!(p.x, f64::from(0.1f32));
}

/// The error of an OBJ text, read strictly (degenerate and non-planar faces refused).
fn obj_error(text: &str) -> String {
    input_error(obj::parse_with(text, "t.obj", Validation::Strict))
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn obj_malformed_number() {
    assert_eq!(
        obj_error("v 0 0 0\nv 1 0x1 0\n"),
        "t.obj:2: y coordinate '0x1' is not a number"
    );
    assert_eq!(
        obj_error("v 1,5 0 0\n"),
        "t.obj:1: x coordinate '1,5' is not a number"
    );
}

#[test]
fn obj_missing_and_extra_coordinates() {
    assert_eq!(
        obj_error("v 0 0 0\n\nv 1 2\n"),
        "t.obj:3: missing coordinate: expected x y z, found 2 values"
    );
    assert_eq!(
        obj_error("v 1 2 3 1 0.5 0.5\n"),
        "t.obj:1: too many values: expected x y z and optionally w = 1, found 6 values \
         (vertex colours are not supported)"
    );
}

#[test]
fn obj_nan_and_inf_are_not_finite() {
    assert_eq!(
        obj_error("v nan 0 0\n"),
        "t.obj:1: x coordinate 'nan' is not a finite number"
    );
    assert_eq!(
        obj_error("# c\nv 0 0 -inf\n"),
        "t.obj:2: z coordinate '-inf' is not a finite number"
    );
    assert_eq!(
        obj_error("v 0 NaN 0\n"),
        "t.obj:1: y coordinate 'NaN' is not a finite number"
    );
    assert_eq!(
        obj_error("v 0 1e400 0\n"),
        "t.obj:1: y coordinate '1e400' is not a finite number: it is too large for f64"
    );
}

#[test]
fn obj_every_finite_coordinate_is_accepted() {
    for x in ["2e100", "1.7976931348623157e308", "5e-324"] {
        let mesh = obj::parse(&format!("v 0 0 0\nv {x} 0 0\nv 0 1 0\nf 1 2 3\n"), "t.obj");
        assert_eq!(mesh.unwrap().faces().len(), 1, "{x}");
    }
}

#[test]
fn obj_face_with_two_vertices() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2 3\nf 1 2\n")),
        "t.obj:5: face 2 has 2 vertices; a face needs at least 3"
    );
}

#[test]
fn obj_index_out_of_range() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2 4\n")),
        "t.obj:4: vertex index 4 is out of range: 3 vertices are defined before this line"
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f -1 -2 -4\n")),
        "t.obj:4: vertex index -4 is out of range: 3 vertices are defined before this line"
    );
    // A vertex defined after the face does not count.
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2 4\nv 1 1 0\n")),
        "t.obj:4: vertex index 4 is out of range: 3 vertices are defined before this line"
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}vt 0 0\nf 1/1 2/2 3/1\n")),
        "t.obj:5: texture coordinate index 2 is out of range: \
         1 texture coordinates are defined before this line"
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1//1 2//1 3//1\n")),
        "t.obj:4: normal index 1 is out of range: 0 normals are defined before this line"
    );
}

#[test]
fn obj_index_zero() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 0 1 2\n")),
        "t.obj:4: vertex index 0 is invalid: OBJ indices count from 1 (or back from -1)"
    );
}

#[test]
fn obj_non_integer_and_malformed_corners() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2.0 3\n")),
        "t.obj:4: vertex index '2.0' is not an integer"
    );
    for corner in ["1/", "1//", "/1", "1/1/1/1", "1/x"] {
        let message = obj_error(&format!("{TRIANGLE}vt 0 0\nvn 0 0 1\nf 2 3 {corner}\n"));
        assert!(
            message.starts_with("t.obj:6: ")
                && (message.contains("malformed face corner")
                    || message.contains("not an integer")),
            "{corner}: {message}"
        );
    }
}

#[test]
fn obj_zero_area_face() {
    assert_eq!(
        obj_error("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 4\nf 1 2 3\n"),
        "t.obj:6: face 2 has zero area"
    );
}

#[test]
fn obj_non_planar_face() {
    let message = obj_error("v 0 0 0\nv 1 0 0\nv 1 1 0.01\nv 0 1 0\n# quad\nf 1 2 3 4\n");
    assert!(
        message.starts_with("t.obj:6: face 1 is not planar"),
        "{message}"
    );
}

#[test]
fn obj_repeated_vertex() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2 3 2\n")),
        "t.obj:4: face 1 visits the point (1, 0, 0) twice"
    );
}

#[test]
fn obj_unknown_keyword() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}vc 1 0 0 1\n")),
        "t.obj:4: unknown keyword 'vc'"
    );
    assert_eq!(obj_error("V 0 0 0\n"), "t.obj:1: unknown keyword 'V'");
}

#[test]
fn obj_elements_that_cannot_be_represented() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}l 1 2\n")),
        "t.obj:4: 'l' (line) elements cannot be represented: only polygon faces ('f') are read"
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}p 1\n")),
        "t.obj:4: 'p' (point) elements cannot be represented: only polygon faces ('f') are read"
    );
    for keyword in [
        "vp 0.5",
        "cstype bspline",
        "curv 0 1 1 2",
        "surf 0 1 0 1 1 2 3",
    ] {
        let message = obj_error(&format!("{TRIANGLE}{keyword}\n"));
        assert!(
            message.starts_with("t.obj:4: free-form curve and surface statement"),
            "{message}"
        );
    }
}

#[test]
fn obj_w_other_than_1() {
    assert_eq!(
        obj_error("v 0 0 0 1\nv 2 0 0 2\n"),
        "t.obj:2: w coordinate '2' is not 1: kepler does not rescale coordinates by w"
    );
}

#[test]
fn obj_error_in_continued_statement_is_at_its_first_line() {
    assert_eq!(
        obj_error("v 0 0 \\\n0\nv 1 \\\n x \\\n 0\n"),
        "t.obj:3: y coordinate 'x' is not a number"
    );
}

// ---------------------------------------------------------------------------------------
// STL

/// An ASCII STL of the triangles, each coordinate written so that it parses to the same
/// `f64`; normals are written as given.
fn ascii_stl(triangles: &[[Point3; 3]], normal: &str) -> String {
    let mut text = String::from("solid test\n");
    for t in triangles {
        text += &format!("  facet normal {normal}\n    outer loop\n");
        for p in t {
            text += &format!("      vertex {:e} {:e} {:e}\n", p.x, p.y, p.z);
        }
        text += "    endloop\n  endfacet\n";
    }
    text + "endsolid test\n"
}

/// A binary STL of the triangles of `f32` corners, with a header that starts with `solid`.
fn binary_stl(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut bytes = b"solid this header must not make the file ASCII".to_vec();
    bytes.resize(80, b' ');
    bytes.extend(u32::try_from(triangles.len()).unwrap().to_le_bytes());
    for t in triangles {
        for x in [0.0f32; 3].iter().chain(t.iter().flatten()) {
            bytes.extend(x.to_le_bytes());
        }
        bytes.extend(0xbeefu16.to_le_bytes());
    }
    bytes
}

fn to_f64(t: &[[f32; 3]; 3]) -> [Point3; 3] {
    t.map(|[x, y, z]| Point3::new(x.into(), y.into(), z.into()))
}

fn cube_f32() -> Vec<[[f32; 3]; 3]> {
    cube_triangles()
        .iter()
        .map(|t| t.map(|p| [p.x as f32, p.y as f32, p.z as f32]))
        .collect()
}

#[test]
fn stl_ascii_cube() {
    let mesh = stl::parse(ascii_stl(&cube_triangles(), "0 0 0").as_bytes(), "cube.stl").unwrap();
    assert_unit_cube(&mesh, 12);
    assert_eq!(mesh.merged_vertices(), 36 - 8);
}

#[test]
fn stl_binary_cube_agrees_with_ascii() {
    let binary = stl::parse(&binary_stl(&cube_f32()), "cube.stl").unwrap();
    assert_unit_cube(&binary, 12);
    let ascii = stl::parse(ascii_stl(&cube_triangles(), "0 0 0").as_bytes(), "c.stl").unwrap();
    assert_eq!(binary, ascii);
}

#[test]
fn stl_binary_round_trips_f32_exactly() {
    let triangles = [
        [[0.1f32, 0.2, 0.3], [1.1, 0.2, 0.3], [0.1, 1.2, 0.3]],
        [[0.1f32, 0.2, 0.3], [0.1, 1.2, 0.3], [1e-30, 7.0e-45, 1.0e5]],
    ];
    let mesh = stl::parse(&binary_stl(&triangles), "t.stl").unwrap();
    let expected: Vec<Point3> = [0, 1, 2, 5]
        .map(|k| to_f64(&triangles[k / 3])[k % 3])
        .to_vec();
    assert_eq!(mesh.vertices(), &expected[..]);
    assert_eq!(mesh.vertices()[0].x, f64::from(0.1f32));
    assert_ne!(mesh.vertices()[0].x, 0.1);
    let ascii: Vec<[Point3; 3]> = triangles.iter().map(to_f64).collect();
    let from_ascii = stl::parse(ascii_stl(&ascii, "0 0 1").as_bytes(), "t.stl").unwrap();
    assert_eq!(from_ascii, mesh);
}

#[test]
fn stl_ascii_keywords_in_any_case_and_any_whitespace() {
    let text = "SOLID my part\r\n\tFacet Normal 0 0 1 OUTER\r\n loop VERTEX 0 0 0 vertex 1 0 0\n\
                vertex\n0\n1\n0 ENDLOOP endfacet\nEndSolid my part\n\n";
    let mesh = stl::parse(text.as_bytes(), "t.stl").unwrap();
    assert_eq!(mesh.faces().len(), 1);
    assert_eq!(mesh.faces()[0].vertices(), &[0, 1, 2]);
    let empty = stl::parse(b"solid\nendsolid\n", "t.stl").unwrap();
    assert!(empty.faces().is_empty());
}

/// The error of an STL file, read strictly.
fn stl_error(bytes: &[u8]) -> String {
    input_error(stl::parse_with(bytes, "t.stl", Validation::Strict))
}

#[test]
fn stl_truncated_binary() {
    let mut bytes = binary_stl(&cube_f32());
    bytes.truncate(bytes.len() - 10);
    assert_eq!(
        stl_error(&bytes),
        "t.stl:header: neither a binary STL (the triangle count in its header, 12, needs 684 \
         bytes, but it has 674) nor an ASCII STL (it contains binary data)"
    );
    let mut bytes = binary_stl(&cube_f32());
    bytes.push(b'\n');
    assert_eq!(
        stl_error(&bytes),
        "t.stl:header: neither a binary STL (the triangle count in its header, 12, needs 684 \
         bytes, but it has 685) nor an ASCII STL (it contains binary data)"
    );
    assert_eq!(
        stl_error(&[0u8; 40]),
        "t.stl:header: neither a binary STL (it has 40 bytes, fewer than the 84 of a binary \
         header) nor an ASCII STL (it does not start with 'solid')"
    );
}

#[test]
fn stl_ascii_missing_endloop() {
    let text = ascii_stl(&cube_triangles(), "0 0 0").replacen("    endloop\n", "", 1);
    // The first facet's endfacet moves up to line 7.
    assert_eq!(
        stl_error(text.as_bytes()),
        "t.stl:7: expected 'endloop', found 'endfacet'"
    );
    let cut = "solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n";
    assert_eq!(
        stl_error(cut.as_bytes()),
        "t.stl:6: unexpected end of file: expected 'endloop'"
    );
}

#[test]
fn stl_ascii_bad_numbers_and_structure() {
    let one = |normal: &str, c: &str| {
        format!(
            "solid\nfacet normal {normal}\nouter loop\nvertex 0 0 0\nvertex 1 {c} 0\n\
             vertex 0 1 0\nendloop\nendfacet\nendsolid\n"
        )
    };
    assert_eq!(
        stl_error(one("0 0 1", "nan").as_bytes()),
        "t.stl:5: y coordinate 'nan' is not a finite number"
    );
    assert_eq!(
        stl_error(one("0 0 1", "0.0.0").as_bytes()),
        "t.stl:5: y coordinate '0.0.0' is not a number"
    );
    assert_eq!(
        stl_error(one("0 inf 1", "0").as_bytes()),
        "t.stl:2: normal y 'inf' is not a finite number"
    );
    assert_eq!(
        stl_error(one("0 1", "0").as_bytes()),
        "t.stl:3: normal z 'outer' is not a number"
    );
    assert_eq!(
        stl_error(format!("{}solid again\n", one("0 0 1", "0")).as_bytes()),
        "t.stl:10: unexpected 'solid' after 'endsolid'"
    );
    assert_eq!(
        stl_error(b"solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\n"),
        "t.stl:7: expected 'endloop', found 'vertex'"
    );
    assert_eq!(
        stl_error(b"solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1\n"),
        "t.stl:5: unexpected end of file: expected y coordinate"
    );
    assert_eq!(
        stl_error(b"hello\n"),
        "t.stl:header: neither a binary STL (it has 6 bytes, fewer than the 84 of a binary \
         header) nor an ASCII STL (it does not start with 'solid')"
    );
    assert_eq!(
        stl_error(
            one("0 0 1", "0")
                .replace("1 0 0", "2 0 0")
                .replace("vertex 0 1 0", "vertex 4 0 0")
                .as_bytes()
        ),
        "t.stl:2: face 1 has zero area"
    );
}

#[test]
fn stl_binary_errors_name_the_triangle() {
    let mut triangles = cube_f32();
    triangles[1][2][0] = f32::NAN;
    assert_eq!(
        stl_error(&binary_stl(&triangles)),
        "t.stl:triangle 2: vertex 3 (NaN, 0, 0) has a coordinate that is not a finite number"
    );
    let mut triangles = cube_f32();
    triangles[4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
    match stl::parse_with(&binary_stl(&triangles), "t.stl", Validation::Strict) {
        Err(FileError::Mesh { path, at, source }) => {
            assert_eq!((path.as_str(), at.as_str()), ("t.stl", "triangle 5"));
            assert_eq!(source, kepler::mesh::MeshError::ZeroArea { face: 4 });
        }
        other => panic!("expected an input error, got {other:?}"),
    }
    let mut bytes = binary_stl(&cube_f32());
    bytes[84 + 50 + 4..84 + 50 + 8].copy_from_slice(&f32::INFINITY.to_le_bytes());
    assert_eq!(
        stl_error(&bytes),
        "t.stl:triangle 2: the normal (0, inf, 0) is not 3 finite numbers"
    );
}

// ---------------------------------------------------------------------------------------
// OFF

/// The cube as OFF with the given header lines (before the vertices).
fn cube_off(header: &str) -> String {
    let mut text = String::from(header);
    for p in cube_vertices() {
        text += &format!("{} {} {}\n", p.x, p.y, p.z);
    }
    for f in CUBE_FACES {
        text += &format!("4 {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    text
}

#[test]
fn off_cube() {
    let mesh = off::parse(&cube_off("OFF\n8 6 12\n"), "cube.off").unwrap();
    assert_unit_cube(&mesh, 6);
    assert_eq!(mesh.vertices(), &cube_vertices()[..]);
    for (f, face) in mesh.faces().iter().enumerate() {
        assert_eq!(face.vertices(), &CUBE_FACES[f][..]);
    }
    for header in [
        "OFF 8 6 12\n",
        "8 6 0\n",
        "# c\n\nOFF # cube\n\n# counts\n  8 6 12 \n",
    ] {
        assert_eq!(
            off::parse(&cube_off(header), "cube.off").unwrap(),
            mesh,
            "{header}"
        );
    }
}

#[test]
fn off_colours_and_normals_are_not_geometry() {
    let plain = off::parse(&cube_off("OFF\n8 6 12\n"), "cube.off").unwrap();
    let with_face_colours = cube_off("OFF\n8 6 12\n")
        .lines()
        .enumerate()
        .map(|(i, l)| match i {
            10 => format!("{l} 3\n"),
            11 => format!("{l} 255 0 0\n"),
            12 => format!("{l} 0.5 0.5 0.5 1\n"),
            _ => format!("{l}\n"),
        })
        .collect::<String>();
    assert_eq!(off::parse(&with_face_colours, "c.off").unwrap(), plain);
    let with_vertex_values = |header: &str, extra: &str| {
        cube_off(&format!("{header}\n8 6 12\n"))
            .lines()
            .enumerate()
            .map(|(i, l)| match i {
                2..=9 => format!("{l} {extra}\n"),
                _ => format!("{l}\n"),
            })
            .collect::<String>()
    };
    for (header, extra) in [
        ("COFF", "255 255 255"),
        ("COFF", "1 1 1 0.5"),
        ("NOFF", "0 0 1"),
        ("CNOFF", "0 0 1 1 1 1"),
        ("CNOFF", "0 0 1 1 1 1 1"),
    ] {
        let text = with_vertex_values(header, extra);
        assert_eq!(
            off::parse(&text, "c.off").unwrap(),
            plain,
            "{header} {extra}"
        );
    }
    assert_eq!(
        input_error(off::parse(&with_vertex_values("COFF", "1 1"), "c.off")),
        "c.off:3: expected 3 coordinates x y z and a colour of 3 or 4 values, found 5 values \
         (vertex 1 of the 8 announced on line 2)"
    );
    assert_eq!(
        input_error(off::parse(&with_vertex_values("NOFF", "0 0 x"), "c.off")),
        "c.off:3: normal or colour value 'x' is not a number (vertex 1 of the 8 announced on line 2)"
    );
}

/// The error of an OFF text, read strictly.
fn off_error(text: &str) -> String {
    input_error(off::parse_with(text, "t.off", Validation::Strict))
}

#[test]
fn off_count_mismatch() {
    let cube = cube_off("OFF\n8 6 12\n");
    // One face fewer than announced: the file ends early.
    let short = cube.replace("4 1 3 7 5\n", "");
    assert_eq!(
        off_error(&short),
        "t.off:15: unexpected end of file: line 2 announces 6 faces, found 5"
    );
    // One record more than announced.
    assert_eq!(
        off_error(&format!("{cube}\n# trailing\n3 0 1 2\n")),
        "t.off:19: unexpected data after the 8 vertices and 6 faces announced on line 2"
    );
    // A vertex fewer than announced: the first face is read as a vertex.
    assert_eq!(
        off_error(&cube_off("OFF\n9 6 12\n")),
        "t.off:11: expected 3 coordinates x y z, found 5 values (vertex 9 of the 9 announced on line 2)"
    );
    assert_eq!(
        off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n"),
        "t.off:4: unexpected end of file: line 2 announces 3 vertices, found 2"
    );
    assert_eq!(
        off_error("OFF\n# nothing else\n"),
        "t.off:2: unexpected end of file: expected the counts"
    );
    assert_eq!(
        off_error(""),
        "t.off:1: empty file: expected the header 'OFF' or the counts"
    );
}

#[test]
fn off_bad_header_and_counts() {
    assert_eq!(
        off_error("STOFF\n3 1 0\n"),
        "t.off:1: unsupported OFF variant 'STOFF': only OFF, COFF, NOFF and CNOFF are read"
    );
    assert_eq!(
        off_error("OFF BINARY\n"),
        "t.off:1: binary OFF is not supported"
    );
    assert_eq!(
        off_error("PLY\n"),
        "t.off:1: expected the header 'OFF' or the counts 'vertices faces edges', found 'PLY'"
    );
    assert_eq!(
        off_error("OFF\n3 1\n"),
        "t.off:2: expected the counts 'vertices faces edges', found '3 1'"
    );
    assert_eq!(
        off_error("OFF\n3 -1 0\n"),
        "t.off:2: the counts '3 -1 0' are not 3 non-negative integers"
    );
}

const OFF_TRIANGLE: &str = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";

#[test]
fn off_bad_numbers() {
    assert_eq!(
        off_error("OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"),
        "t.off:4: y coordinate 'zero' is not a number (vertex 2 of the 3 announced on line 2)"
    );
    assert_eq!(
        off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 inf\n3 0 1 2\n"),
        "t.off:5: z coordinate 'inf' is not a finite number (vertex 3 of the 3 announced on line 2)"
    );
    assert_eq!(
        off_error("OFF\n3 1 0\nNaN 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
        "t.off:3: x coordinate 'NaN' is not a finite number (vertex 1 of the 3 announced on line 2)"
    );
    assert_eq!(
        off_error("OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
        "t.off:3: expected 3 coordinates x y z, found 2 values (vertex 1 of the 3 announced on line 2)"
    );
}

#[test]
fn off_bad_faces() {
    assert_eq!(
        off_error(&format!("{OFF_TRIANGLE}3 0 1 3\n")),
        "t.off:6: vertex index 3 is out of range: the file has 3 vertices, numbered from 0"
    );
    assert_eq!(
        off_error(&format!("{OFF_TRIANGLE}3 0 -1 2\n")),
        "t.off:6: vertex index '-1' is not a non-negative integer"
    );
    assert_eq!(
        off_error(&format!("{OFF_TRIANGLE}4 0 1 2\n")),
        "t.off:6: the face announces 4 vertices but lists 3"
    );
    assert_eq!(
        off_error(&format!("{OFF_TRIANGLE}3 0 1 2 1 1\n")),
        "t.off:6: expected a colour of 1, 3 or 4 values (or none) after the 3 vertex indices, \
         found 2 values"
    );
    assert_eq!(
        off_error(&format!("{OFF_TRIANGLE}2 0 1\n")),
        "t.off:6: face 1 has 2 vertices; a face needs at least 3"
    );
    assert_eq!(
        off_error("OFF\n4 2 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n3 0 1 3\n# collinear\n3 0 1 2\n"),
        "t.off:9: face 2 has zero area"
    );
    let message = off_error("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 1\n0 1 0\n4 0 1 2 3\n");
    assert!(
        message.starts_with("t.off:7: face 1 is not planar"),
        "{message}"
    );
}

// ---------------------------------------------------------------------------------------
// read_mesh

#[test]
fn read_mesh_fixtures() {
    let obj = read_mesh(&data("cube.obj")).unwrap();
    assert_unit_cube(&obj, 6);
    let off = read_mesh(&data("cube.off")).unwrap();
    assert_unit_cube(&off, 6);
    assert_eq!(obj, off);
    let stl = read_mesh(&data("cube_ascii.stl")).unwrap();
    assert_unit_cube(&stl, 12);
    assert!(stl.faces().iter().all(|f| f.vertices().len() == 3));
}

#[test]
fn read_mesh_binary_stl_and_any_letter_case() {
    let file = TempFile::new("cube.STL", &binary_stl(&cube_f32()));
    let binary = read_mesh(&file.0).unwrap();
    assert_eq!(binary, read_mesh(&data("cube_ascii.stl")).unwrap());
    let text = std::fs::read(data("cube.obj")).unwrap();
    let file = TempFile::new("cube.Obj", &text);
    assert_unit_cube(&read_mesh(&file.0).unwrap(), 6);
}

#[test]
fn read_mesh_reports_errors_with_the_path() {
    let file = TempFile::new("bad.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n");
    let message = read_mesh(&file.0).unwrap_err().to_string();
    assert_eq!(
        message,
        format!(
            "{}:6: vertex index 5 is out of range: the file has 3 vertices, numbered from 0",
            file.0.display()
        )
    );
}

#[test]
fn read_mesh_unknown_extension() {
    for name in ["scene.3ds", "cube", "cube.obj.gz"] {
        let message = read_mesh(Path::new(name)).unwrap_err().to_string();
        assert_eq!(
            message,
            format!("{name}: unknown mesh format: the extension must be .obj, .stl, .off or .ply")
        );
    }
}

#[test]
fn read_mesh_missing_file() {
    let path = data("missing.obj");
    match read_mesh(&path) {
        Err(e @ FileError::Io { .. }) => {
            let message = e.to_string();
            assert!(
                message.starts_with(&format!("{}: ", path.display())),
                "{message}"
            );
        }
        other => panic!("expected an I/O error, got {other:?}"),
    }
}

#[test]
fn a_mesh_file_without_faces_is_an_error() {
    let path = std::env::temp_dir().join(format!("kepler-empty-{}.obj", std::process::id()));
    std::fs::write(&path, "# nothing here\nv 0 0 0\n").unwrap();
    let e = kepler::io::read_mesh(&path).unwrap_err().to_string();
    std::fs::remove_file(&path).unwrap();
    assert!(e.ends_with(":1: the file has no faces"), "{e}");
}

// ---------------------------------------------------------------------------------------------
// PLY.

/// A PLY header for `vertices` vertices with `x y z` of type `coordinate` (and a normal and a
/// colour around them, which are ignored), `faces` faces whose list has count type `count`
/// and index type `index`, and an `edge` element of one record.
fn ply_header(
    format: &str,
    vertices: usize,
    coordinate: &str,
    faces: usize,
    count: &str,
    index: &str,
) -> String {
    format!(
        "ply\nformat {format} 1.0\ncomment made by kepler's tests\nelement vertex {vertices}\n\
         property float nx\nproperty {coordinate} x\nproperty {coordinate} y\n\
         property {coordinate} z\nproperty uchar red\nelement face {faces}\n\
         property list {count} {index} vertex_indices\nproperty int flags\n\
         element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
    )
}

/// Scalars of PLY's types, written in one byte order.
#[derive(Clone, Copy)]
enum Scalar {
    Float(f32),
    Double(f64),
    UChar(u8),
    UShort(u16),
    Int(i32),
    UInt(u32),
}

fn put(bytes: &mut Vec<u8>, x: Scalar, big: bool) {
    macro_rules! order {
        ($v:expr) => {
            if big {
                bytes.extend($v.to_be_bytes())
            } else {
                bytes.extend($v.to_le_bytes())
            }
        };
    }
    match x {
        Scalar::Float(v) => order!(v),
        Scalar::Double(v) => order!(v),
        Scalar::UChar(v) => bytes.push(v),
        Scalar::UShort(v) => order!(v),
        Scalar::Int(v) => order!(v),
        Scalar::UInt(v) => order!(v),
    }
}

/// The unit cube as a binary PLY in either byte order, with coordinates as `float` or
/// `double`, list counts as `uchar` and indices as `ushort`, `int` or `uint`.
fn binary_cube(big: bool, double: bool, index: &str) -> Vec<u8> {
    let format = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let coordinate = if double { "double" } else { "float" };
    let mut bytes = ply_header(format, 8, coordinate, 6, "uchar", index).into_bytes();
    for p in cube_vertices() {
        put(&mut bytes, Scalar::Float(0.5), big);
        for c in p.iter() {
            let c = if double {
                Scalar::Double(*c)
            } else {
                Scalar::Float(*c as f32)
            };
            put(&mut bytes, c, big);
        }
        put(&mut bytes, Scalar::UChar(200), big);
    }
    for face in CUBE_FACES {
        put(&mut bytes, Scalar::UChar(4), big);
        for i in face {
            let i = match index {
                "ushort" => Scalar::UShort(i as u16),
                "int" => Scalar::Int(i as i32),
                _ => Scalar::UInt(i),
            };
            put(&mut bytes, i, big);
        }
        put(&mut bytes, Scalar::Int(-1), big);
    }
    put(&mut bytes, Scalar::Int(0), big);
    put(&mut bytes, Scalar::Int(1), big);
    bytes
}

/// The unit cube as an ASCII PLY.
fn ascii_cube() -> String {
    let mut text = ply_header("ascii", 8, "double", 6, "uchar", "int");
    for p in cube_vertices() {
        text += &format!("0.5 {} {} {} 200\n", p.x, p.y, p.z);
    }
    for f in CUBE_FACES {
        text += &format!("4 {} {} {} {} -1\n", f[0], f[1], f[2], f[3]);
    }
    text + "0 1\n"
}

#[test]
fn ply_ascii_and_binary_read_the_same_cube() {
    let ascii = ply::parse(ascii_cube().as_bytes(), "c.ply").unwrap();
    assert_unit_cube(&ascii, 6);
    let faces: Vec<Vec<u32>> = CUBE_FACES.iter().map(|f| f.to_vec()).collect();
    assert_eq!(ascii.polygons(), faces);
    assert_eq!(ascii.vertices(), cube_vertices().as_slice());
    for big in [false, true] {
        for double in [false, true] {
            for index in ["ushort", "int", "uint"] {
                let m = ply::parse(&binary_cube(big, double, index), "c.ply").unwrap();
                assert_eq!(m, ascii, "big endian {big}, double {double}, {index}");
            }
        }
    }
}

#[test]
fn ply_coordinates_keep_their_declared_precision() {
    // A float is widened exactly, a double read correctly rounded.
    let tri = |coordinate: &str, x: &str| {
        let mut text = ply_header("ascii", 3, coordinate, 1, "uchar", "uint");
        text += &format!("0 {x} 0 0 0\n0 1 1 0 0\n0 0 1 0 0\n3 0 1 2 0\n0 1\n");
        ply::parse(text.as_bytes(), "t.ply").unwrap().vertices()[0].x
    };
    assert_eq!(tri("double", "0.1"), 0.1);
    assert_eq!(tri("float", "0.1"), f64::from(0.1f32));
    let mut exact = ply_header("binary_little_endian", 3, "double", 1, "uchar", "int").into_bytes();
    for p in [[0.1, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
        put(&mut exact, Scalar::Float(0.0), false);
        for c in p {
            put(&mut exact, Scalar::Double(c), false);
        }
        put(&mut exact, Scalar::UChar(0), false);
    }
    exact.push(3);
    for i in [0, 1, 2, 0, 0, 1] {
        put(&mut exact, Scalar::Int(i), false);
    }
    let m = ply::parse(&exact, "t.ply").unwrap();
    assert_eq!(m.vertices()[0], Point3::new(0.1, 0.0, 0.0));
    // A binary NaN is read, and refused as a coordinate, naming the element.
    // The last vertex's x: after its float nx, before the edge (8 bytes), the face (17) and
    // the rest of the vertex (29).
    let at = exact.len() - 8 - 17 - 29 + 4;
    exact[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    assert_eq!(
        input_error(ply::parse(&exact, "t.ply")),
        "t.ply:vertex 3: vertex 3 has a coordinate that is not a finite number"
    );
}

#[test]
fn ply_errors_name_the_line_or_the_element() {
    let text = ascii_cube().replace("4 1 3 7 5 -1\n", "4 1 3 7 8 -1\n");
    assert_eq!(
        input_error(ply::parse(text.as_bytes(), "c.ply")),
        "c.ply:30: face 6: vertex index 8 is out of range: the file has 8 vertices, numbered \
         from 0"
    );
    let text = ascii_cube().replace("0.5 1 1 1 200\n", "0.5 1 nan 1 200\n");
    assert_eq!(
        input_error(ply::parse(text.as_bytes(), "c.ply")),
        "c.ply:24: vertex 8: '0.5 1 nan 1 200' are not the numbers the header declares"
    );
    let text = ascii_cube().replace("element face", "elemnt face");
    assert_eq!(
        input_error(ply::parse(text.as_bytes(), "c.ply")),
        "c.ply:10: 'elemnt face 6' is not a header line (ply, format, comment, obj_info, \
         element, property or end_header)"
    );
    // A binary file: the element. Truncated: the end of file.
    let mut bytes = binary_cube(true, false, "int");
    // The last face's last index: before it the edge (8 bytes), the face's flags (4) and that
    // index (4).
    let at = bytes.len() - 8 - 4 - 4;
    bytes[at..at + 4].copy_from_slice(&9i32.to_be_bytes());
    assert_eq!(
        input_error(ply::parse(&bytes, "c.ply")),
        "c.ply:face 6: vertex index 9 is out of range: the file has 8 vertices, numbered from 0"
    );
    let bytes = binary_cube(false, true, "int");
    let cut = &bytes[..bytes.len() - 30];
    assert_eq!(
        input_error(ply::parse(cut, "c.ply")),
        "c.ply:face 5: unexpected end of file: the header announces 6 face elements"
    );
    let no_z = ascii_cube().replace("property double z\n", "");
    assert_eq!(
        input_error(ply::parse(no_z.as_bytes(), "c.ply")),
        "c.ply:header: the vertex element has no property 'z'"
    );
}

#[test]
fn ply_polygons_not_exactly_planar_are_split_or_refused() {
    let text = ascii_cube().replace("0.5 1 1 1 200\n", "0.5 1 1 1.0000000000000002 200\n");
    let m = ply::parse(text.as_bytes(), "c.ply").unwrap();
    // Vertex 7 moved along z leaves the faces x = 1 and y = 1 planar, and bends z = 1.
    assert_eq!(
        (m.split_polygons(), m.faces().len(), m.polygons().len()),
        (1, 7, 6)
    );
    assert!(m.is_solid());
    let e = input_error(ply::parse_with(
        text.as_bytes(),
        "c.ply",
        Validation::Strict,
    ));
    assert!(e.starts_with("c.ply:26: face 2 is not planar"), "{e}");
}

/// Input echoed in an error is cut to a readable length, whatever the reader.
#[test]
fn a_huge_token_is_not_echoed_whole() {
    let huge = "k".repeat(1 << 20);
    let errors = [
        input_error(obj::parse(&format!("v 0 0 0\n{huge} 1 2\n"), "t.obj")),
        input_error(obj::parse(&format!("v 0 0 {huge}\n"), "t.obj")),
        input_error(off::parse(&format!("OFF\n3 1 0\n0 0 {huge}\n"), "t.off")),
        input_error(off::parse(&format!("{huge}OFF\n"), "t.off")),
        input_error(stl::parse(format!("solid t\n{huge}\n").as_bytes(), "t.stl")),
        input_error(ply::parse(
            format!("ply\nformat ascii 1.0\n{huge}\nend_header\n").as_bytes(),
            "t.ply",
        )),
        input_error(ply::parse(
            ascii_cube()
                .replace("0.5 1 1 1 200\n", &format!("0.5 1 {huge} 1 200\n"))
                .as_bytes(),
            "t.ply",
        )),
    ];
    for e in errors {
        assert!(
            e.len() < 400 && e.contains("kkkkkkkkkk"),
            "{} bytes: {}",
            e.len(),
            &e[..e.len().min(400)]
        );
        assert!(e.contains("(1048"), "{e}");
    }
}

/// A mesh file whose faces all have zero area once its coordinates are rounded to doubles (a
/// 1e-6 box placed at 1e15) is a valid, empty object: it loads with its degenerate faces
/// counted and draws nothing. A file with no face at all is still an error.
#[test]
fn a_file_of_degenerate_faces_only_is_an_empty_object() {
    let dir = std::env::temp_dir().join(format!("kepler-degenerate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("far.obj");
    let mut obj = String::new();
    for x in [1e15, 1e15 + 1e-6] {
        for y in [1e15, 1e15 + 1e-6] {
            for z in [1e15, 1e15 + 1e-6] {
                obj.push_str(&format!("v {x} {y} {z}\n"));
            }
        }
    }
    obj.push_str("f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n");
    std::fs::write(&path, obj).unwrap();
    let mesh = kepler::io::read_mesh(&path).unwrap();
    assert!(mesh.faces().is_empty());
    assert_eq!(mesh.degenerate_faces(), 6);
    let empty = dir.join("empty.obj");
    std::fs::write(&empty, "v 0 0 0\nv 1 0 0\n").unwrap();
    let e = kepler::io::read_mesh(&empty).unwrap_err();
    assert!(e.to_string().contains("the file has no faces"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}
