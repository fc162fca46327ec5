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
const ORDER: [&str; 20] = [
    "random",
    "union_find",
    "fnv",
    "le",
    "geometry",
    "clip",
    "mesh",
    "io",
    "solids",
    "bounds",
    "scene",
    "views",
    "grid",
    "sight",
    "queries",
    "hidden",
    "surfaces",
    "output",
    "error",
    "lab",
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
        .filter_map(|l| {
            let l = l.trim();
            l.strip_prefix("pub mod ")
                .or_else(|| l.strip_prefix("pub(crate) mod "))
        })
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

// ---------------------------------------------------------------------------------------------
// Cycles between sibling modules inside a layer.

/// Cycles between sibling modules allowed for a while, each as `folder: a, b, …` (the members
/// of one strongly connected component of the folder's sibling references, sorted): none
/// since issue 28 ended the last one (`geometry`: `exact` and `kernel`). The test fails on
/// any cycle not listed here.
const ALLOWED_CYCLES: &[&str] = &[];

/// A library file's module path: `src/a/b/x.rs` is `a::b::x`, `src/a/b/mod.rs` is `a::b`.
fn module_path(relative: &Path) -> Vec<String> {
    let mut parts: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().to_string())
        .collect();
    if let Some(last) = parts.pop()
        && last != "mod.rs"
    {
        parts.push(last.trim_end_matches(".rs").to_string());
    }
    parts
}

/// The paths a file's code names, as written after `crate::`, `super::` or `self::` (with the
/// prefix): use groups are expanded (`crate::a::{b, c::d}` names `crate::a::b` and
/// `crate::a::c::d`). Comments are left out.
fn named_paths(text: &str) -> Vec<Vec<String>> {
    let code: String = text.lines().map(|l| format!("{} ", code(l))).collect();
    let chars: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let is_ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut i = 0;
    while i < chars.len() {
        let starts_word = i == 0 || !(is_ident(chars[i - 1]) || chars[i - 1] == ':');
        let rest: String = chars[i..chars.len().min(i + 7)].iter().collect();
        if starts_word
            && (rest.starts_with("crate::")
                || rest.starts_with("super::")
                || rest.starts_with("self::"))
        {
            i = expand(&chars, i, Vec::new(), &mut out);
        } else {
            i += 1;
        }
    }
    out
}

/// Reads a use tree at `chars[i..]` (a path, possibly ending in a `{…}` group) under `prefix`
/// and returns the index after it.
fn expand(
    chars: &[char],
    mut i: usize,
    mut prefix: Vec<String>,
    out: &mut Vec<Vec<String>>,
) -> usize {
    let is_ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    loop {
        while i < chars.len() && chars[i].is_whitespace() {
            i += 1;
        }
        if i < chars.len() && chars[i] == '{' {
            i += 1;
            loop {
                while i < chars.len() && (chars[i].is_whitespace() || chars[i] == ',') {
                    i += 1;
                }
                if i >= chars.len() || chars[i] == '}' {
                    return i + 1;
                }
                let before = i;
                i = expand(chars, i, prefix.clone(), out);
                if i == before {
                    i += 1;
                }
            }
        }
        let start = i;
        while i < chars.len() && is_ident(chars[i]) {
            i += 1;
        }
        if i == start {
            if !prefix.is_empty() {
                out.push(prefix);
            }
            return i;
        }
        prefix.push(chars[start..i].iter().collect());
        if chars.get(i) == Some(&':') && chars.get(i + 1) == Some(&':') {
            i += 2;
        } else {
            out.push(prefix);
            return i;
        }
    }
}

/// Every reference from one sibling module to another inside the library's folders, as
/// `(folder, from, to, file)`: a file inside child `from` of `folder` names (by `crate::` or
/// `super::`) an item inside child `to` of the same folder.
fn sibling_references(src: &Path) -> Vec<(String, String, String, String)> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let modules: Vec<(Vec<String>, PathBuf)> = files
        .iter()
        .map(|p| {
            let relative = p.strip_prefix(src).unwrap_or(p).to_path_buf();
            (module_path(&relative), relative)
        })
        .filter(|(m, _)| !m.is_empty() && !matches!(m[0].as_str(), "lib" | "main" | "bin"))
        .collect();
    let known: std::collections::BTreeSet<&Vec<String>> = modules.iter().map(|(m, _)| m).collect();
    let mut out = Vec::new();
    for (own, relative) in &modules {
        let text = std::fs::read_to_string(src.join(relative)).unwrap_or_else(|e| panic!("{e}"));
        for path in named_paths(&text) {
            // Resolve to an absolute path below the crate.
            let mut absolute = own.clone();
            let mut segments = path.iter().peekable();
            match segments.next().map(String::as_str) {
                Some("crate") => absolute.clear(),
                Some("self") => {}
                Some("super") => {
                    absolute.pop();
                    while segments.peek().is_some_and(|s| *s == "super") {
                        segments.next();
                        absolute.pop();
                    }
                }
                _ => continue,
            }
            absolute.extend(segments.cloned());
            // The module named: the longest prefix that is a module of the library.
            let Some(target) = (1..=absolute.len())
                .rev()
                .map(|n| absolute[..n].to_vec())
                .find(|m| known.contains(m))
            else {
                continue;
            };
            let common = own.iter().zip(&target).take_while(|(a, b)| a == b).count();
            // A folder below the top level, with both modules strictly inside it.
            if common == 0 || common >= own.len() || common >= target.len() {
                continue;
            }
            out.push((
                own[..common].join("::"),
                own[common].clone(),
                target[common].clone(),
                relative.display().to_string(),
            ));
        }
    }
    out.sort();
    out.dedup();
    out
}

/// The cycles among siblings: for each folder, each strongly connected component of more
/// than one child, as `folder: a, b, …`, with the references that close it (`file: a -> b`).
fn sibling_cycles(src: &Path) -> Vec<(String, Vec<String>)> {
    let references = sibling_references(src);
    let mut graphs: BTreeMap<String, BTreeMap<String, std::collections::BTreeSet<String>>> =
        BTreeMap::new();
    for (folder, from, to, _) in &references {
        graphs
            .entry(folder.clone())
            .or_default()
            .entry(from.clone())
            .or_default()
            .insert(to.clone());
    }
    let mut cycles = Vec::new();
    for (folder, graph) in &graphs {
        // Reachability by search from every node (the graphs are small).
        let reach = |from: &String| {
            let mut seen = std::collections::BTreeSet::new();
            let mut stack = vec![from.clone()];
            while let Some(n) = stack.pop() {
                for m in graph.get(&n).into_iter().flatten() {
                    if seen.insert(m.clone()) {
                        stack.push(m.clone());
                    }
                }
            }
            seen
        };
        let reaches: BTreeMap<&String, _> = graph.keys().map(|n| (n, reach(n))).collect();
        let mut done = std::collections::BTreeSet::new();
        for n in graph.keys() {
            if done.contains(n) || !reaches[n].contains(n) {
                continue;
            }
            let members: Vec<String> = reaches[n]
                .iter()
                .filter(|m| reaches.get(m).is_some_and(|r| r.contains(n)))
                .cloned()
                .collect();
            done.extend(members.iter().cloned());
            let edges = references
                .iter()
                .filter(|(f, a, b, _)| f == folder && members.contains(a) && members.contains(b))
                .map(|(_, a, b, file)| format!("{file}: {a} -> {b}"))
                .collect();
            cycles.push((format!("{folder}: {}", members.join(", ")), edges));
        }
    }
    cycles
}

#[test]
fn sibling_modules_form_no_new_cycle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let cycles = sibling_cycles(&src);
    let new: Vec<String> = cycles
        .iter()
        .filter(|(c, _)| !ALLOWED_CYCLES.contains(&c.as_str()))
        .map(|(c, edges)| format!("{c}\n    {}", edges.join("\n    ")))
        .collect();
    assert!(
        new.is_empty(),
        "cycles between sibling modules:\n{}",
        new.join("\n")
    );
    for allowed in ALLOWED_CYCLES {
        if !cycles.iter().any(|(c, _)| c == allowed) {
            eprintln!("ALLOWED_CYCLES: `{allowed}` is gone: remove it from the list");
        }
    }
}

/// The cycle checker itself: references by `super::`, by `crate::` paths and groups, from a
/// nested folder, close a cycle; a parent naming its children and a child naming its parent
/// do not.
#[test]
fn the_checker_sees_sibling_cycles() {
    let dir = std::env::temp_dir().join(format!("kepler-cycles-{}", std::process::id()));
    let write = |rel: &str, text: &str| {
        let path = dir.join(rel);
        std::fs::create_dir_all(path.parent().unwrap_or(&dir)).unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(path, text).unwrap_or_else(|e| panic!("{e}"));
    };
    write("lib.rs", "pub mod geometry;\n");
    write(
        "geometry/mod.rs",
        "pub mod a;\npub use a::f;\nuse self::b::g;\n",
    );
    write("geometry/a.rs", "use super::b::g; // use super::c::h;\n");
    write(
        "geometry/b.rs",
        "use crate::{\n    geometry::{c::h, mod_item},\n};\n",
    );
    write("geometry/c/mod.rs", "use super::super::geometry::Item;\n");
    write(
        "geometry/c/deep.rs",
        "fn f() { crate::geometry::a::f(); }\n",
    );
    write("geometry/d.rs", "use super::a::f;\n");
    let cycles = sibling_cycles(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(cycles.len(), 1, "{cycles:#?}");
    assert_eq!(cycles[0].0, "geometry: a, b, c");
    assert_eq!(
        cycles[0].1,
        [
            "geometry/a.rs: a -> b",
            "geometry/b.rs: b -> c",
            "geometry/c/deep.rs: c -> a"
        ]
    );
}
