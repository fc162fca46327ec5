//! The layering of the crate, kept true: every top-level module of the library imports only
//! the modules of the layers before it, and the engine never imports the lab.
//!
//! The layers, in order (the crate documentation draws them): the exact kernel (`geometry`,
//! with polygon clipping in `clip`), meshes and their files (`mesh`, `io`, `solids`), the
//! bounds of one object (`bounds`), the scene graph and its views (`scene`, `views`), the
//! grid and the point queries (`grid`, `queries`), lines and surfaces (`hidden`,
//! `surfaces`), output (`output`), the error that wraps every layer's (`error`), and the
//! lab of paper experiments (`lab`), which may use all of the engine.
//!
//! A module's references are read from its source text: every `crate::name` path outside
//! comments, including those inside `use crate::{...}` groups, and every `super::` path that
//! would climb out of the module. The test fails with the file and line of each reference to
//! a later module.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The top-level modules of the library, each allowed to import only those before it.
const ORDER: [&str; 15] = [
    "geometry", "clip", "mesh", "io", "solids", "bounds", "scene", "views", "grid", "queries",
    "hidden", "surfaces", "output", "error", "lab",
];

/// Every `.rs` file below `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    entries.sort();
    for path in entries {
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The code of a line: the text before a `//` comment (doc comments included). String
/// literals in the library do not contain `crate::` paths or `//`, so this is enough here.
fn code(line: &str) -> &str {
    line.split_once("//").map_or(line, |(before, _)| before)
}

/// The top-level modules a line of code names with `crate::`: plain paths and the first
/// segment of every item of a `crate::{...}` group (which may span lines: `group` carries an
/// open group from one line to the next).
fn crate_references(line: &str, group: &mut bool) -> Vec<String> {
    let mut found = Vec::new();
    let segment = |s: &str| {
        s.trim_start()
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect::<String>()
    };
    let mut rest = line;
    if *group {
        let (inside, after) = rest
            .split_once('}')
            .map_or((rest, None), |(a, b)| (a, Some(b)));
        found.extend(inside.split(',').map(segment).filter(|s| !s.is_empty()));
        match after {
            Some(after) => {
                *group = false;
                rest = after;
            }
            None => return found,
        }
    }
    while let Some(at) = rest.find("crate::") {
        rest = &rest[at + "crate::".len()..];
        if let Some(inner) = rest.strip_prefix('{') {
            let (inside, after) = inner
                .split_once('}')
                .map_or((inner, None), |(a, b)| (a, Some(b)));
            found.extend(inside.split(',').map(segment).filter(|s| !s.is_empty()));
            match after {
                Some(after) => rest = after,
                None => {
                    *group = true;
                    return found;
                }
            }
        } else {
            found.push(segment(rest));
        }
    }
    found
}

/// How deep a file sits below its top-level module's folder: `src/queries/visp.rs` is 1 (one
/// `super::` reaches `queries`), `src/queries/mod.rs` and `src/clip.rs` are 0.
fn depth_in_module(relative: &Path) -> usize {
    let parts: Vec<_> = relative.components().collect();
    let last_is_mod = relative.file_name().is_some_and(|f| f == "mod.rs");
    parts.len().saturating_sub(if last_is_mod { 2 } else { 1 })
}

/// Every reference of a library module to a module that is not before it, as
/// `file:line: module -> other`.
fn violations(src: &Path) -> Vec<String> {
    let rank: BTreeMap<&str, usize> = ORDER.iter().enumerate().map(|(i, m)| (*m, i)).collect();
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut out = Vec::new();
    for path in files {
        let relative = path.strip_prefix(src).unwrap_or(&path).to_path_buf();
        let first = relative
            .components()
            .next()
            .map(|c| {
                c.as_os_str()
                    .to_string_lossy()
                    .trim_end_matches(".rs")
                    .to_string()
            })
            .unwrap_or_default();
        if first == "lib" || first == "main" || first == "bin" {
            continue;
        }
        let Some(&own) = rank.get(first.as_str()) else {
            out.push(format!(
                "{}: module `{first}` is in no layer of ORDER",
                path.display()
            ));
            continue;
        };
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
        let depth = depth_in_module(&relative);
        let mut group = false;
        for (n, line) in text.lines().enumerate() {
            let line_code = code(line);
            for name in crate_references(line_code, &mut group) {
                let allowed = rank.get(name.as_str()).is_none_or(|&r| r <= own);
                let is_module = rank.contains_key(name.as_str());
                if is_module && !allowed {
                    out.push(format!("{}:{}: {first} -> {name}", path.display(), n + 1));
                }
                if !is_module && !matches!(name.as_str(), "Error" | "Result") {
                    out.push(format!(
                        "{}:{}: `crate::{name}` is no module of ORDER",
                        path.display(),
                        n + 1
                    ));
                }
                if matches!(name.as_str(), "Error" | "Result") && own < rank["error"] {
                    out.push(format!(
                        "{}:{}: {first} -> error (crate::{name})",
                        path.display(),
                        n + 1
                    ));
                }
            }
            let climbs = line_code.matches("super::").count();
            if climbs > 0 && line_code.contains(&"super::".repeat(depth + 1)) {
                out.push(format!(
                    "{}:{}: `super::` climbs out of `{first}`",
                    path.display(),
                    n + 1
                ));
            }
        }
    }
    out
}

#[test]
fn every_module_imports_only_earlier_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let found = violations(&src);
    assert!(
        found.is_empty(),
        "imports against the layering:\n{}",
        found.join("\n")
    );
}

#[test]
fn every_top_level_module_has_a_layer() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let lib = std::fs::read_to_string(src.join("lib.rs")).unwrap_or_else(|e| panic!("{e}"));
    let declared: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.trim().strip_prefix("pub mod "))
        .map(|m| m.trim_end_matches(';'))
        .collect();
    let mut sorted_order = ORDER.to_vec();
    sorted_order.sort_unstable();
    let mut sorted = declared.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, sorted_order, "lib.rs declares {declared:?}");
}

/// The checker itself finds what it must: a reference to a later layer in a plain path, in a
/// `use` group over several lines, in a climb with `super::`, and not in comments.
#[test]
fn the_checker_sees_forbidden_imports() {
    let dir = std::env::temp_dir().join(format!("kepler-layering-{}", std::process::id()));
    let write = |rel: &str, text: &str| {
        let path = dir.join(rel);
        std::fs::create_dir_all(path.parent().unwrap_or(&dir)).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(path, text).unwrap_or_else(|e| panic!("{e}"));
    };
    write("lib.rs", "pub mod geometry;\n");
    write(
        "geometry/mod.rs",
        "use crate::mesh::Mesh;\n// use crate::lab::x;\n",
    );
    write(
        "geometry/ray.rs",
        "use crate::{\n    clip,\n    views::View,\n};\n",
    );
    write(
        "geometry/deep/a.rs",
        "use super::super::super::scene::Scene;\n",
    );
    write(
        "mesh/mod.rs",
        "use crate::geometry::Point3;\nuse super::x;\n",
    );
    write("scene.rs", "fn f() -> crate::Result<()> { Ok(()) }\n");
    let found = violations(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    let expect = [
        "geometry/mod.rs:1: geometry -> mesh",
        "geometry/ray.rs:2: geometry -> clip",
        "geometry/ray.rs:3: geometry -> views",
        "geometry/deep/a.rs:1: `super::` climbs out of `geometry`",
        "mesh/mod.rs:2: `super::` climbs out of `mesh`",
        "scene.rs:1: scene -> error (crate::Result)",
    ];
    for e in expect {
        assert!(
            found.iter().any(|f| f.ends_with(e)),
            "missing {e} in {found:#?}"
        );
    }
    assert_eq!(found.len(), expect.len(), "{found:#?}");
}
