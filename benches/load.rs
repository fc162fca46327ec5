//! Reading mesh files (issue 16's `load` group): the same mesh of 69,600 triangles (a torus,
//! coordinates with full 17-digit mantissas) as OBJ, OFF, ASCII and binary STL, ASCII and
//! binary PLY, parsed from memory into a validated [`Mesh`]. Throughput is in bytes of the
//! file. Two references run in the same group: copying the binary STL's bytes out of the
//! page cache (`std::fs::read`, the floor any reader of a file has) and building the mesh from
//! vertices and faces already in memory (`Mesh::from_polygons`: what every reader ends with).
//!
//!   cargo bench --bench load

use std::fmt::Write as _;
use std::hint::black_box;

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use kepler::io::{obj, off, ply, stl};
use kepler::mesh::Mesh;

/// The torus's vertices and triangles.
fn mesh() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let torus = kepler::solids::torus(3.0, 1.0, 240, 145).expect("valid torus");
    let vertices = torus.vertices().iter().map(|p| [p.x, p.y, p.z]).collect();
    (vertices, torus.triangles().to_vec())
}

fn obj_text(v: &[[f64; 3]], t: &[[u32; 3]]) -> Vec<u8> {
    let mut s = String::new();
    for p in v {
        let _ = writeln!(s, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    for f in t {
        let _ = writeln!(s, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    s.into_bytes()
}

/// The body OFF and ASCII PLY share: a line per vertex, then `3 i j k` per triangle.
fn counted_lines(mut s: String, v: &[[f64; 3]], t: &[[u32; 3]]) -> Vec<u8> {
    for p in v {
        let _ = writeln!(s, "{:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    for f in t {
        let _ = writeln!(s, "3 {} {} {}", f[0], f[1], f[2]);
    }
    s.into_bytes()
}

fn off_text(v: &[[f64; 3]], t: &[[u32; 3]]) -> Vec<u8> {
    counted_lines(format!("OFF\n{} {} 0\n", v.len(), t.len()), v, t)
}

fn stl_ascii(v: &[[f64; 3]], t: &[[u32; 3]]) -> Vec<u8> {
    let mut s = "solid torus\n".to_owned();
    for f in t {
        s += "facet normal 0 0 0\nouter loop\n";
        for &i in f {
            let p = v[i as usize];
            let _ = writeln!(s, "vertex {:?} {:?} {:?}", p[0], p[1], p[2]);
        }
        s += "endloop\nendfacet\n";
    }
    s += "endsolid torus\n";
    s.into_bytes()
}

fn stl_binary(v: &[[f64; 3]], t: &[[u32; 3]]) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b.extend_from_slice(&(t.len() as u32).to_le_bytes());
    for f in t {
        b.extend_from_slice(&[0u8; 12]);
        for &i in f {
            for c in v[i as usize] {
                b.extend_from_slice(&(c as f32).to_le_bytes());
            }
        }
        b.extend_from_slice(&[0u8; 2]);
    }
    b
}

fn ply_header(format: &str, v: usize, t: usize) -> String {
    format!(
        "ply\nformat {format} 1.0\nelement vertex {v}\nproperty double x\nproperty double y\n\
         property double z\nelement face {t}\nproperty list uchar int vertex_indices\nend_header\n"
    )
}

fn ply_ascii(v: &[[f64; 3]], t: &[[u32; 3]]) -> Vec<u8> {
    counted_lines(ply_header("ascii", v.len(), t.len()), v, t)
}

fn ply_binary(v: &[[f64; 3]], t: &[[u32; 3]]) -> Vec<u8> {
    let mut b = ply_header("binary_little_endian", v.len(), t.len()).into_bytes();
    for p in v {
        for c in p {
            b.extend_from_slice(&c.to_le_bytes());
        }
    }
    for f in t {
        b.push(3);
        for &i in f {
            b.extend_from_slice(&(i as i32).to_le_bytes());
        }
    }
    b
}

fn load(c: &mut Criterion) {
    let (v, t) = mesh();
    let files: [(&str, Vec<u8>); 6] = [
        ("obj", obj_text(&v, &t)),
        ("off", off_text(&v, &t)),
        ("stl ascii", stl_ascii(&v, &t)),
        ("stl binary", stl_binary(&v, &t)),
        ("ply ascii", ply_ascii(&v, &t)),
        ("ply binary", ply_binary(&v, &t)),
    ];
    let parse = |name: &str, bytes: &[u8]| -> Mesh {
        let text = || std::str::from_utf8(bytes).expect("generated text is UTF-8");
        match name {
            "obj" => obj::parse(text(), "t.obj"),
            "off" => off::parse(text(), "t.off"),
            "ply ascii" | "ply binary" => ply::parse(bytes, "t.ply"),
            _ => stl::parse(bytes, "t.stl"),
        }
        .expect("generated file is valid")
    };
    // Every format reads the same triangles (STL's are rounded to f32, so only counted).
    for (name, bytes) in &files {
        assert_eq!(parse(name, bytes).triangles().len(), t.len(), "{name}");
    }
    let mut g = c.benchmark_group(format!("load {} triangles", t.len()));
    for (name, bytes) in &files {
        g.throughput(Throughput::Bytes(bytes.len() as u64));
        g.bench_function(*name, |b| b.iter(|| parse(name, black_box(bytes))));
    }
    let path = std::env::temp_dir().join(format!("kepler-load-bench-{}.stl", std::process::id()));
    std::fs::write(&path, &files[3].1).expect("temporary file");
    g.throughput(Throughput::Bytes(files[3].1.len() as u64));
    g.bench_function("reference: fs::read of the binary STL", |b| {
        b.iter(|| std::fs::read(black_box(&path)).expect("temporary file"))
    });
    let _ = std::fs::remove_file(&path);
    let points: Vec<kepler::geometry::Point3> = v
        .iter()
        .map(|p| kepler::geometry::Point3::new(p[0], p[1], p[2]))
        .collect();
    let faces: Vec<Vec<u32>> = t.iter().map(|f| f.to_vec()).collect();
    g.throughput(Throughput::Elements(t.len() as u64));
    g.bench_function("reference: Mesh::from_polygons (no text)", |b| {
        b.iter_batched(
            || (points.clone(), faces.clone()),
            |(points, faces)| Mesh::from_polygons(points, faces).expect("valid"),
            BatchSize::LargeInput,
        )
    });
    g.finish();
}

criterion_group!(benches, load);
criterion_main!(benches);
