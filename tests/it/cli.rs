//! The `kepler` command line, run as a separate process: `kepler bounds SCENE [--json]`, its
//! table and JSON output, and its errors.

use serde_json::{Value, json};
use std::process::{Command, Output};

/// Runs the built binary in the crate's directory (so `scenes/...` resolves).
pub(super) fn kepler(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_kepler"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the kepler binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).expect("UTF-8 output")
}

pub(super) fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).expect("UTF-8 output")
}

/// Runs successfully and returns the standard output.
pub(super) fn ok(args: &[&str]) -> String {
    let o = kepler(args);
    assert!(
        o.status.success(),
        "kepler {args:?} failed ({:?}): {}",
        o.status,
        stderr(&o)
    );
    assert_eq!(stderr(&o), "", "kepler {args:?} wrote to stderr");
    stdout(&o)
}

/// Fails cleanly (exit code 1, nothing on stdout, one `error: ` line, no panic) and returns
/// the error message after `error: `.
pub(super) fn fails(args: &[&str]) -> String {
    let o = kepler(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "kepler {args:?}: {err}");
    assert!(!err.contains("panicked"), "kepler {args:?} panicked: {err}");
    assert_eq!(stdout(&o), "", "kepler {args:?} wrote to stdout");
    assert!(err.starts_with("error: "), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    err["error: ".len()..].trim_end().to_string()
}

fn json_of(args: &[&str]) -> Value {
    let out = ok(args);
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("not JSON ({e}):\n{out}"))
}

fn object<'a>(report: &'a Value, name: &str) -> &'a Value {
    report["objects"]
        .as_array()
        .expect("an `objects` array")
        .iter()
        .find(|o| o["name"] == name)
        .unwrap_or_else(|| panic!("no object {name}"))
}

// ---------------------------------------------------------------------------------------------
// The table.

#[test]
fn bounds_table_for_the_cube() {
    let out = ok(&["bounds", "scenes/cube.toml"]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    let header: Vec<&str> = lines[0].split_whitespace().collect();
    assert_eq!(
        &header[..6],
        ["object", "faces", "vertices", "solid", "cbox", "inbox"]
    );
    let row: Vec<&str> = lines[1].split_whitespace().collect();
    assert_eq!(&row[..4], ["cube", "6", "8", "yes"]);
    assert!(
        lines[1].contains("[-0.5 -0.5 -0.5]..[0.5 0.5 0.5]"),
        "{}",
        lines[1]
    );
}

#[test]
fn bounds_table_marks_open_and_inside_out_objects() {
    let out = ok(&["bounds", "scenes/meshes.toml"]);
    let row = |name: &str| -> Vec<String> {
        out.lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("no line for {name}:\n{out}"))
            .split_whitespace()
            .map(String::from)
            .collect()
    };
    assert_eq!(&row("house")[..4], ["house", "7", "10", "yes"]);
    assert_eq!(&row("tent")[..4], ["tent", "4", "5", "open"]);
    assert_eq!(
        &row("inside-out")[..4],
        ["inside-out", "6", "8", "inside-out"]
    );
    // The tent has no inbox.
    assert!(row("tent").contains(&"empty".to_string()), "{out}");
}

#[test]
fn bounds_table_indents_subobjects_by_depth() {
    let out = ok(&["bounds", "scenes/city.toml"]);
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines.iter().any(|l| l.starts_with("block ")));
    assert!(lines.iter().any(|l| l.starts_with("  tower-west ")));
    assert!(lines.iter().any(|l| l.starts_with("    body ")));
    let block: Vec<&str> = lines
        .iter()
        .find(|l| l.starts_with("block "))
        .unwrap()
        .split_whitespace()
        .collect();
    assert_eq!(block[1], "1962");
}

#[test]
fn bounds_of_a_mesh_file() {
    let out = ok(&["bounds", "tests/data/cube.obj"]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    let row: Vec<&str> = lines[1].split_whitespace().collect();
    assert_eq!(&row[..4], ["cube", "6", "8", "yes"]);
}

// ---------------------------------------------------------------------------------------------
// JSON.

#[test]
fn bounds_json_for_the_cube() {
    let report = json_of(&["bounds", "scenes/cube.toml", "--json"]);
    let objects = report["objects"].as_array().expect("an `objects` array");
    assert_eq!(objects.len(), 1);
    let c = &objects[0];
    assert_eq!(c["name"], "cube");
    assert_eq!(c["path"], "cube");
    assert_eq!(c["depth"], 0);
    assert_eq!(c["faces"], 6);
    assert_eq!(c["vertices"], 8);
    assert_eq!(c["closed"], true);
    assert_eq!(c["inside_out"], false);
    assert_eq!(c["volume"], 1.0);
    assert_eq!(c["surface_area"], 6.0);
    let unit = json!({"min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5], "volume": 1.0, "surface_area": 6.0});
    assert_eq!(c["cbox"], unit);
    assert_eq!(c["inbox"], unit);
    // Min then max per direction: x, y, z, x+y, x+z, y+z, x−z, y−x, z−y.
    assert_eq!(
        c["tribox"]["bounds"],
        json!([
            -0.5, 0.5, -0.5, 0.5, -0.5, 0.5, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0,
            -1.0, 1.0
        ])
    );
    assert_eq!(c["tribox"]["faces"], 6);
    assert_eq!(c["tribox"]["volume"], 1.0);
    assert_eq!(c["cbox_ratio"], 1.0);
}

#[test]
fn bounds_json_shape() {
    let report = json_of(&["bounds", "scenes/meshes.toml", "--json"]);
    assert_eq!(report.as_object().unwrap().len(), 1, "only `objects`");
    let objects = report["objects"].as_array().unwrap();
    assert_eq!(objects.len(), 3);
    let is_triple = |v: &Value| {
        v.as_array()
            .is_some_and(|a| a.len() == 3 && a.iter().all(Value::is_f64))
    };
    for o in objects {
        assert!(o["name"].is_string());
        assert!(o["faces"].is_u64() && o["vertices"].is_u64());
        assert!(o["closed"].is_boolean() && o["inside_out"].is_boolean());
        assert!(o["volume"].is_f64() || o["volume"].is_null());
        assert!(is_triple(&o["cbox"]["min"]) && is_triple(&o["cbox"]["max"]));
        assert!(
            o["inbox"].is_null()
                || (is_triple(&o["inbox"]["min"]) && is_triple(&o["inbox"]["max"]))
        );
        let b = o["tribox"]["bounds"].as_array().unwrap();
        assert_eq!(b.len(), 18);
        assert!(b.iter().all(Value::is_f64));
        assert!(o["tribox"]["faces"].is_u64());
        assert!(o["tribox"]["volume"].is_f64());
    }
}

#[test]
fn bounds_json_for_the_mesh_scene() {
    let report = json_of(&["bounds", "scenes/meshes.toml", "--json"]);

    let house = object(&report, "house");
    assert_eq!(house["closed"], true);
    assert_eq!(house["inside_out"], false);
    assert_eq!(house["volume"], 30.0);
    assert_eq!(house["faces"], 7);
    assert_eq!(
        house["cbox"],
        json!({"min": [0.0, 0.0, 0.0], "max": [4.0, 3.0, 3.0], "volume": 36.0, "surface_area": 66.0})
    );
    // Its vertices (0|4, 0|3, 0|2) and the ridge (0|4, 1.5, 3), by hand.
    assert_eq!(
        house["tribox"]["bounds"],
        json!([
            0.0, 4.0, 0.0, 3.0, 0.0, 3.0, 0.0, 7.0, 0.0, 7.0, 0.0, 5.0, -3.0, 4.0, -4.0, 3.0, -3.0,
            2.0
        ])
    );

    let tent = object(&report, "tent");
    assert_eq!(tent["closed"], false);
    assert_eq!(tent["inside_out"], false);
    assert_eq!(tent["inbox"], Value::Null);
    assert_eq!(tent["volume"], Value::Null);
    assert_eq!(
        (tent["faces"].as_u64(), tent["vertices"].as_u64()),
        (Some(4), Some(5))
    );
    // Scaled by (1.5, 1.5, 1) and moved by (7, 1.5, 0).
    assert_eq!(
        tent["cbox"],
        json!({"min": [5.5, 0.0, 0.0], "max": [8.5, 3.0, 2.0], "volume": 18.0, "surface_area": 42.0})
    );

    let inside_out = object(&report, "inside-out");
    assert_eq!(inside_out["inside_out"], true);
    assert_eq!(inside_out["closed"], true);
    let v = inside_out["volume"].as_f64().unwrap();
    assert!((v - 1.0).abs() < 1e-12, "{v}");
    assert!(inside_out["inbox"].is_object());
}

// ---------------------------------------------------------------------------------------------
// Errors.

#[test]
fn a_missing_scene_file_fails_cleanly() {
    let e = fails(&["bounds", "tests/data/scenes/no-such-scene.toml"]);
    assert!(
        e.starts_with("tests/data/scenes/no-such-scene.toml: "),
        "{e}"
    );
    let e = fails(&["bounds", "no-such-mesh.off"]);
    assert!(e.starts_with("no-such-mesh.off: "), "{e}");
}

#[test]
fn a_missing_file_error_gives_its_reason_once() {
    let e = fails(&["bounds", "tests/data/scenes/no-such-scene.toml"]);
    let reason = e.rsplit(": ").next().unwrap();
    assert_eq!(e.matches(reason).count(), 1, "the reason is repeated: {e}");
}

#[test]
fn a_malformed_scene_fails_with_file_and_line() {
    let e = fails(&["bounds", "tests/data/scenes/syntax_error.toml"]);
    assert!(
        e.starts_with("tests/data/scenes/syntax_error.toml:5: "),
        "{e}"
    );
    let e = fails(&["bounds", "tests/data/scenes/broken_mesh.toml", "--json"]);
    assert!(
        e.starts_with(
            "tests/data/scenes/broken_mesh.toml:7: tests/data/scenes/broken.obj:7: vertex index 9"
        ),
        "{e}"
    );
}

#[test]
fn an_unknown_mesh_format_fails_cleanly() {
    let e = fails(&["bounds", "scene.3ds"]);
    assert!(e.starts_with("scene.3ds: unknown mesh format"), "{e}");
}

#[test]
fn usage_errors_do_not_panic() {
    for args in [
        &[][..],
        &["bounds"][..],
        &["frobnicate"][..],
        &["bounds", "--bogus"][..],
    ] {
        let o = kepler(args);
        assert!(!o.status.success(), "kepler {args:?} succeeded");
        assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
        assert!(stderr(&o).contains("Usage"), "{}", stderr(&o));
    }
}

#[test]
fn a_reader_that_stops_early_is_not_an_error() {
    use std::io::Read;
    use std::process::Stdio;
    // The JSON for the city is about 0.5 MB, more than a pipe holds.
    let mut child = Command::new(env!("CARGO_BIN_EXE_kepler"))
        .args(["bounds", "scenes/city.toml", "--json"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut out = child.stdout.take().unwrap();
    let mut first = [0u8; 16];
    out.read_exact(&mut first).unwrap();
    assert!(first.starts_with(b"{"));
    drop(out);
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    let status = child.wait().unwrap();
    assert!(!err.contains("panicked"), "{err}");
    assert!(status.success(), "{status:?}: {err}");
    assert_eq!(err, "");
}

// ---------------------------------------------------------------------------------------------
// `kepler include` and `kepler visp`.

/// Runs a point query with `input` on standard input; it must succeed and write one summary
/// line on stderr. Returns the answers.
fn answers(args: &[&str], input: &str) -> Vec<String> {
    use std::io::Write as _;
    let mut child = Command::new(env!("CARGO_BIN_EXE_kepler"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the kepler binary runs");
    let mut stdin = child.stdin.take().expect("a pipe");
    stdin.write_all(input.as_bytes()).expect("input written");
    drop(stdin);
    let o = child.wait_with_output().expect("kepler finishes");
    let err = stderr(&o);
    assert!(o.status.success(), "kepler {args:?} failed: {err}");
    assert_eq!(err.lines().count(), 1, "one summary line: {err}");
    assert!(err.starts_with(&format!("kepler {}: ", args[0])), "{err}");
    stdout(&o).lines().map(str::to_owned).collect()
}

/// The cube scene's cube has corners at ±0.5.
const CUBE_POINTS: &str =
    "0 0 0\n# on a face, an edge, a vertex\n0.5, 0, 0\n0.5 0.5 0\n\n0.5,0.5,0.5\n0 0 2\n";

#[test]
fn include_answers_in_order_with_a_summary() {
    let got = answers(
        &["include", "scenes/cube.toml", "--points", "-"],
        CUBE_POINTS,
    );
    assert_eq!(got, ["IN", "ON", "ON", "ON", "OUT"]);
}

#[test]
fn include_summary_counts_the_stages() {
    let o = Command::new(env!("CARGO_BIN_EXE_kepler"))
        .args([
            "include",
            "scenes/cube.toml",
            "--points",
            "tests/data/cube_points.txt",
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("runs");
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(stdout(&o), "IN\nOUT\nON\n");
    assert!(err.contains("3 points: 1 IN, 1 OUT, 1 ON"), "{err}");
    assert!(
        err.contains("INBOX 1 (33.3%), CBOX 1 (33.3%), TRIBOX 0 (0.0%), faces 1 (33.3%)"),
        "{err}"
    );
}

#[test]
fn visp_in_the_standard_view() {
    // From (0, 0, +inf): the centre is inside (hidden by the top face), the top face's points
    // and a point on a side face's silhouette edge are visible, a point below is hidden.
    let input = "0 0 0\n0.1 0.2 0.5\n0.5 0 0\n0 0 -3\n0 0 3\n";
    let got = answers(
        &[
            "visp",
            "scenes/cube.toml",
            "--points",
            "-",
            "--view-dir",
            "0,0,-1",
        ],
        input,
    );
    assert_eq!(got, ["HIDDEN", "VISIBLE", "VISIBLE", "HIDDEN", "VISIBLE"]);
}

#[test]
fn visp_in_a_perspective_and_the_default_views() {
    let input = "0.5 0.5 0.5\n-0.5 -0.5 -0.5\n0.2 0.2 5\n";
    let perspective = [
        "visp",
        "scenes/cube.toml",
        "--points",
        "-",
        "--eye",
        "4,4,4",
        "--target",
        "0,0,0",
        "--fov",
        "30",
    ];
    assert_eq!(
        answers(&perspective, input),
        ["VISIBLE", "HIDDEN", "VISIBLE"]
    );
    // The default view looks along (-1,-1,-1): the same corners.
    assert_eq!(
        answers(&["visp", "scenes/cube.toml", "--points", "-"], input),
        ["VISIBLE", "HIDDEN", "VISIBLE"]
    );
    // Looking the other way swaps the corners.
    let reverse = [
        "visp",
        "scenes/cube.toml",
        "--points",
        "-",
        "--view-dir",
        "1,1,1",
        "--up",
        "0,0,1",
    ];
    assert_eq!(answers(&reverse, input), ["HIDDEN", "VISIBLE", "VISIBLE"]);
}

#[test]
fn a_malformed_point_line_is_an_error_naming_the_line() {
    let path = "tests/data/bad_points.txt";
    assert_eq!(
        fails(&["include", "scenes/cube.toml", "--points", path]),
        format!("{path}:3: coordinate 'x' is not a number")
    );
    assert_eq!(
        fails(&[
            "visp",
            "scenes/cube.toml",
            "--points",
            "tests/data/short_points.txt"
        ]),
        "tests/data/short_points.txt:2: expected 3 coordinates (x y z), found 2"
    );
    assert!(
        fails(&["include", "scenes/cube.toml", "--points", "no/such.txt"])
            .starts_with("no/such.txt: ")
    );
}

#[test]
fn include_on_an_open_mesh_is_an_error() {
    let err = fails(&[
        "include",
        "scenes/meshes.toml",
        "--points",
        "tests/data/cube_points.txt",
    ]);
    assert!(err.contains("'tent'") && err.contains("open mesh"), "{err}");
}

#[test]
fn conflicting_or_bad_view_options_are_errors() {
    let base = [
        "visp",
        "scenes/cube.toml",
        "--points",
        "tests/data/cube_points.txt",
    ];
    let with = |extra: &[&str]| fails(&[&base[..], extra].concat());
    assert!(
        with(&[
            "--view-dir",
            "0,0,-1",
            "--eye",
            "1,1,1",
            "--target",
            "0,0,0"
        ])
        .contains("cannot be combined")
    );
    assert!(with(&["--eye", "1,1,1"]).contains("must be given together"));
    assert!(with(&["--view-dir", "0,0,-1", "--fov", "30"]).contains("perspective views only"));
    assert!(with(&["--view-dir", "0,0,0"]).contains("view direction is zero"));
    assert!(with(&["--view-dir", "0,0,-1", "--up", "0,0,2"]).contains("parallel"));
    assert!(
        with(&["--eye", "1,1,1", "--target", "0,0,0", "--fov", "190"]).contains("field of view")
    );
}

#[test]
fn a_bad_view_vector_is_a_usage_error() {
    let o = kepler(&[
        "visp",
        "scenes/cube.toml",
        "--points",
        "-",
        "--view-dir",
        "1,2",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("expected x,y,z"), "{}", stderr(&o));
}

// ---------------------------------------------------------------------------------------------
// `kepler segx`.

/// Runs `kepler segx` with `input` on standard input.
fn segx_with_stdin(args: &[&str], input: &str) -> Output {
    use std::io::Write as _;
    let mut child = Command::new(env!("CARGO_BIN_EXE_kepler"))
        .arg("segx")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the kepler binary runs");
    let mut stdin = child.stdin.take().expect("a pipe");
    stdin.write_all(input.as_bytes()).expect("input written");
    drop(stdin);
    child.wait_with_output().expect("kepler finishes")
}

/// Checks a summary line `N <n> K <k> seconds <s>` and returns `(n, k)`.
fn segx_summary(line: &str) -> (usize, usize) {
    let words: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(words.len(), 6, "{line:?}");
    assert_eq!(
        [words[0], words[2], words[4]],
        ["N", "K", "seconds"],
        "{line:?}"
    );
    let seconds: f64 = words[5].parse().expect("seconds");
    assert!(seconds.is_finite() && seconds >= 0.0, "{line:?}");
    (words[1].parse().expect("N"), words[3].parse().expect("K"))
}

/// The pairs printed by `--pairs`, one `i j` a line.
fn segx_pairs(out: &str) -> Vec<(usize, usize)> {
    out.lines()
        .map(|line| {
            let v: Vec<usize> = line
                .split_whitespace()
                .map(|w| w.parse().expect("an index"))
                .collect();
            assert_eq!(v.len(), 2, "{line:?}");
            (v[0], v[1])
        })
        .collect()
}

#[test]
fn segx_counts_the_pairs_of_random_segments() {
    use kepler::grid::{intersecting_pairs, random_segments};
    let out = ok(&["segx", "--n", "2000", "--len", "0.05", "--seed", "3"]);
    assert_eq!(out.lines().count(), 1, "{out}");
    assert!(out.ends_with('\n'));
    let k = intersecting_pairs(&random_segments(2000, 0.05, 3)).len();
    assert!(k > 1000, "{k}");
    assert_eq!(segx_summary(&out), (2000, k));
    // The defaults: length 0.01, seed 1.
    let out = ok(&["segx", "--n", "3000"]);
    let k = intersecting_pairs(&random_segments(3000, 0.01, 1)).len();
    assert_eq!(segx_summary(&out), (3000, k));
    // Another seed, other segments.
    let other = ok(&["segx", "--n", "2000", "--len", "0.05", "--seed", "4"]);
    let k = intersecting_pairs(&random_segments(2000, 0.05, 4)).len();
    assert_eq!(segx_summary(&other), (2000, k));
    assert_eq!(segx_summary(&ok(&["segx", "--n", "0"])), (0, 0));
}

#[test]
fn segx_lists_the_pairs_of_random_segments_by_1_based_index() {
    use kepler::grid::{intersecting_pairs, random_segments};
    let o = kepler(&[
        "segx", "--n", "400", "--len", "0.1", "--seed", "2", "--pairs",
    ]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(err.lines().count(), 1, "one summary line: {err}");
    let expected: Vec<(usize, usize)> = intersecting_pairs(&random_segments(400, 0.1, 2))
        .into_iter()
        .map(|(i, j)| (i + 1, j + 1))
        .collect();
    assert!(!expected.is_empty());
    assert_eq!(segx_pairs(&stdout(&o)), expected);
    assert_eq!(segx_summary(&err), (400, expected.len()));
}

#[test]
fn segx_reads_a_segment_file_and_lists_pairs_by_line_number() {
    let path = "tests/data/segments_comments.txt";
    // Comments and blank lines keep the numbering: segments on lines 2, 4, 6, 7, 8 and 9.
    let o = kepler(&["segx", "--input", path, "--pairs"]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(
        stdout(&o),
        "2 4\n2 6\n7 8\n7 9\n8 9\n",
        "an X, a touching end, a touching end, a collinear overlap, a T"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert_eq!(segx_summary(&err), (6, 5));
    // Without --pairs: the summary alone, on standard output.
    assert_eq!(segx_summary(&ok(&["segx", "--input", path])), (6, 5));
}

#[test]
fn segx_reads_standard_input() {
    let input = "# a star of three through (1, 1), and one apart\n\
                 0 0 2 2\n0 2 2 0\n\n1 0 1 3\n5,5,6,6\n";
    let o = segx_with_stdin(&["--input", "-", "--pairs"], input);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert_eq!(stdout(&o), "2 3\n2 5\n3 5\n");
    assert_eq!(segx_summary(&err), (4, 3));
    let o = segx_with_stdin(&["--input", "-"], input);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
    assert_eq!(segx_summary(&stdout(&o)), (4, 3));
    // Nothing to read: no segments, no pairs.
    let o = segx_with_stdin(&["--input", "-", "--pairs"], "# nothing\n\n");
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o), "");
    assert_eq!(segx_summary(&stderr(&o)), (0, 0));
}

#[test]
fn segx_errors() {
    // A malformed segment line names the file and the line.
    assert_eq!(
        fails(&["segx", "--input", "tests/data/segments_short.txt"]),
        "tests/data/segments_short.txt:3: expected 4 coordinates (x1 y1 x2 y2), found 3"
    );
    assert_eq!(
        fails(&[
            "segx",
            "--input",
            "tests/data/segments_short.txt",
            "--pairs"
        ]),
        "tests/data/segments_short.txt:3: expected 4 coordinates (x1 y1 x2 y2), found 3"
    );
    let o = segx_with_stdin(&["--input", "-"], "0 0 1 1\n\n1 1 x 2\n");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(stdout(&o), "");
    assert!(
        err.starts_with("error: standard input:3: ") && err.contains('x'),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(fails(&["segx", "--input", "no/such.txt"]).starts_with("no/such.txt: "));
    // The random segments' length is at most 1, and not negative.
    for len in ["--len=2", "--len=-0.5", "--len=1.000001"] {
        let err = fails(&["segx", "--n", "10", len]);
        assert!(
            err.contains("--len must be between 0 and 1"),
            "{len}: {err}"
        );
    }
    assert_eq!(
        segx_summary(&ok(&["segx", "--n", "10", "--len", "1"])).0,
        10
    );
    assert_eq!(
        segx_summary(&ok(&["segx", "--n", "10", "--len", "0"])).0,
        10
    );
}

#[test]
fn segx_usage_errors() {
    // Neither --n nor --input; both; a bad number.
    for args in [
        &["segx"][..],
        &["segx", "--pairs"][..],
        &[
            "segx",
            "--n",
            "10",
            "--input",
            "tests/data/segments_comments.txt",
        ][..],
        &["segx", "--n", "ten"][..],
        &["segx", "--n", "-3"][..],
        &["segx", "--n", "10", "--seed", "-1"][..],
    ] {
        let o = kepler(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "kepler {args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(err.starts_with("error: "), "{err}");
        assert_eq!(stdout(&o), "", "kepler {args:?}");
    }
    let err = stderr(&kepler(&["segx"]));
    assert!(err.contains("--n") && err.contains("Usage"), "{err}");
    let err = stderr(&kepler(&[
        "segx",
        "--n",
        "10",
        "--input",
        "tests/data/segments_comments.txt",
    ]));
    assert!(err.contains("--input") && err.contains("Usage"), "{err}");
    let err = stderr(&kepler(&["segx", "--n", "ten"]));
    assert!(err.contains("'ten'") && err.contains("--n"), "{err}");
}

/// The JSON in a file a command wrote.
fn json_file(path: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("the JSON")).expect("JSON")
}

/// A path for a test's output file in the build's directory for test files (not the
/// system's temporary directory, where each run would leave one behind).
fn temp_path(name: &str) -> String {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("kepler-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    dir.join(name).to_string_lossy().into_owned()
}

/// The polylines of an SVG written by `kepler render`: `(layer id, points)` in file order.
fn svg_polylines(svg: &str) -> Vec<(String, Vec<[f64; 2]>)> {
    let doc = roxmltree::Document::parse(svg).expect("the SVG parses");
    let mut out = Vec::new();
    for path in doc.descendants().filter(|n| n.has_tag_name("path")) {
        let layer = path
            .parent()
            .and_then(|g| g.attribute("id"))
            .expect("a layer id");
        let numbers: Vec<f64> = path
            .attribute("d")
            .expect("path data")
            .split_whitespace()
            .filter(|t| *t != "M" && *t != "L")
            .map(|t| t.parse().expect("a number"))
            .collect();
        let points = numbers.chunks(2).map(|c| [c[0], c[1]]).collect();
        out.push((layer.to_string(), points));
    }
    out
}

/// The polylines of `kepler render --json`: `(layer id, points)`, the layer id made from the
/// class and visibility as the SVG names it.
fn json_polylines(json: &str) -> Vec<(String, Vec<[f64; 2]>)> {
    let value: Value = serde_json::from_str(json).expect("the JSON parses");
    value["polylines"]
        .as_array()
        .expect("a polylines array")
        .iter()
        .map(|p| {
            let visible = p["visible"].as_bool().expect("visible");
            let class = p["class"].as_str().expect("class");
            let layer = format!("{}-{class}", if visible { "visible" } else { "hidden" });
            // serde_json reads floats exactly with its `float_roundtrip` feature.
            let points = p["points"]
                .as_array()
                .expect("points")
                .iter()
                .map(|xy| [0, 1].map(|k| xy[k].as_f64().expect("a number")))
                .collect();
            (layer, points)
        })
        .collect()
}

#[test]
fn render_writes_an_svg_holding_the_json_polylines() {
    let (svg, json) = (temp_path("cube.svg"), temp_path("cube.json"));
    let args = [
        "render",
        "scenes/cube.toml",
        "-o",
        &svg,
        "--json",
        &json,
        "--view-dir",
        "-1,-2,-3",
        "--up",
        "0,0,1",
    ];
    assert_eq!(ok(&args), "");
    let from_svg = svg_polylines(&std::fs::read_to_string(&svg).expect("the SVG"));
    let mut from_json = json_polylines(&std::fs::read_to_string(&json).expect("the JSON"));
    // The SVG lists hidden layers first, then visible ones; the same polylines, bit for bit.
    from_json.sort_by_key(|(layer, _)| !layer.starts_with("hidden"));
    let mut sorted_svg = from_svg.clone();
    sorted_svg.sort_by_key(|(layer, _)| !layer.starts_with("hidden"));
    assert_eq!(sorted_svg, from_json);
    // The cube from a general direction: 9 visible edges (6 silhouette, 3 crease), 3 hidden.
    let edges = |layer: &str| -> usize {
        from_svg
            .iter()
            .filter(|(l, _)| l == layer)
            .map(|(_, p)| p.len() - 1)
            .sum()
    };
    assert_eq!(edges("visible-silhouette"), 6);
    assert_eq!(edges("visible-crease"), 3);
    assert_eq!(edges("hidden-crease"), 3);
    assert_eq!(from_svg.len(), 1 + 3 + 3);
}

#[test]
fn render_can_omit_hidden_lines_and_report_stats() {
    let svg = temp_path("omit.svg");
    let o = kepler(&[
        "render",
        "scenes/city.toml",
        "-o",
        &svg,
        "--hidden",
        "omit",
        "--stats",
        "--edges",
        "all",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&svg).expect("the SVG");
    assert!(!text.contains("hidden-"), "hidden layers were written");
    assert!(text.contains(r#"id="visible-silhouette""#));
    let stats = stderr(&o);
    for stage in [
        "edges",
        "occluders",
        "intersections",
        "cuts",
        "visibility",
        "chains",
    ] {
        assert!(
            stats.lines().any(|l| l.starts_with(stage)),
            "no {stage} line: {stats}"
        );
    }
    // Every class has a length line; the city's objects pierce each other.
    let intersection = stats
        .lines()
        .find(|l| l.starts_with("intersection "))
        .expect("an intersection length line");
    let visible: f64 = intersection
        .split_whitespace()
        .nth(1)
        .expect("length")
        .parse()
        .expect("number");
    assert!(visible > 0.0, "{intersection}");
}

#[test]
fn render_hatch_writes_a_hatch_layer_between_hidden_and_visible_ones() {
    let svg = temp_path("hatch.svg");
    let args = [
        "render",
        "scenes/cube.toml",
        "-o",
        &svg,
        "--view-dir",
        "-1,-2,-3",
        "--up",
        "0,0,1",
        "--hatch",
        "--light",
        "0,0,-1",
        "--hatch-angle",
        "30",
        "--hatch-spacing",
        "1,4",
        "--stats",
    ];
    let o = kepler(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats = stderr(&o);
    let line = stats
        .lines()
        .find(|l| l.starts_with("hatch "))
        .unwrap_or_else(|| panic!("no hatch line: {stats}"));
    // Lit from below, the three faces seen from above are turned away: all darkest.
    assert!(line.contains("3 of 6 faces hatched"), "{line}");
    assert!(line.contains("(0 dropped"), "{line}");
    let text = std::fs::read_to_string(&svg).expect("the SVG");
    let hatch = text
        .find(r#"<g id="hatch" inkscape:groupmode="layer" inkscape:label="hatch""#)
        .expect("a hatch layer");
    assert!(text.find(r#"id="hidden-crease""#).expect("hidden") < hatch);
    assert!(hatch < text.find(r#"id="visible-silhouette""#).expect("visible"));
    let layers = svg_polylines(&text);
    assert!(layers.iter().filter(|(l, _)| l == "hatch").count() > 50);
    // Without --hatch there is none; --hatch writes SVG only.
    ok(&["render", "scenes/cube.toml", "-o", &svg]);
    assert!(
        !std::fs::read_to_string(&svg)
            .expect("the SVG")
            .contains("hatch")
    );
    let dxf = temp_path("hatch.dxf");
    assert!(fails(&["render", "scenes/cube.toml", "-o", &dxf, "--hatch"]).contains("SVG only"));
    let bad = kepler(&[
        "render",
        "scenes/cube.toml",
        "-o",
        &svg,
        "--hatch-spacing",
        "3,1",
    ]);
    assert!(!bad.status.success() && stderr(&bad).contains("0 < MIN ≤ MAX"));
}

#[test]
fn render_rejects_bad_scenes_views_and_options() {
    let svg = temp_path("bad.svg");
    assert!(
        fails(&["render", "scenes/missing.toml", "-o", &svg]).starts_with("scenes/missing.toml")
    );
    let empty = temp_path("empty.toml");
    std::fs::write(&empty, "# nothing here\n").expect("write the scene");
    assert!(fails(&["render", &empty, "-o", &svg]).contains("no objects to draw"));
    let zero = fails(&[
        "render",
        "scenes/cube.toml",
        "-o",
        &svg,
        "--view-dir",
        "0,0,0",
    ]);
    assert!(zero.contains("invalid view"), "{zero}");
    let parallel = fails(&[
        "render",
        "scenes/cube.toml",
        "-o",
        &svg,
        "--view-dir",
        "0,0,-1",
        "--up",
        "0,0,3",
    ]);
    assert!(parallel.contains("invalid view"), "{parallel}");
    // An eye inside the scene: render and surfaces clip, a near distance must be positive.
    let inside = ["--eye", "0,0,0.5", "--target", "0,0,-5"];
    ok(&[&["render", "scenes/cube.toml", "-o", &svg][..], &inside].concat());
    let near = fails(
        &[
            &["render", "scenes/cube.toml", "-o", &svg, "--near", "-1"][..],
            &inside,
        ]
        .concat(),
    );
    assert!(near.contains("invalid view"), "{near}");
    let json = temp_path("inside.json");
    ok(&[
        &["surfaces", "scenes/cube.toml", "-o", &svg, "--json", &json][..],
        &inside,
    ]
    .concat());
    let report: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // The eye on the top face looks down at the floor: the floor and the two walls along the
    // picture's sides show, cut by its edges (aspect 277/190 on the default page); the other
    // walls lie outside the field of view, the top face in the plane of the eye.
    let faces = report["faces"].as_array().unwrap();
    let statuses: Vec<&str> = faces
        .iter()
        .map(|f| f["status"].as_str().unwrap())
        .collect();
    assert_eq!(
        statuses,
        ["hidden", "hidden", "mixed", "mixed", "mixed", "hidden"],
        "{report}"
    );
    // Up to the rounding of points constructed on the frustum's planes (within 1.5 ulp).
    let [aspect, top] = [277.0 / 190.0, 1.0].map(|s| s * (1.0 + 1e-15));
    for f in faces {
        for polygon in f["polygons"].as_array().unwrap() {
            for p in polygon["outer"].as_array().unwrap() {
                let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
                assert!(x.abs() <= aspect && y.abs() <= top, "{report}");
            }
        }
    }
    let nowhere = format!("{}/no/such/dir/out.svg", temp_path("x"));
    assert!(fails(&["render", "scenes/cube.toml", "-o", &nowhere]).starts_with(&nowhere));
    for bad in [
        ["--page", "10"],
        ["--page", "0x10"],
        ["--stroke", "wobbly=1"],
        ["--stroke", "crease=-1"],
        ["--crease-angle", "400"],
        ["--margin", "200"],
    ] {
        let o = kepler(&["render", "scenes/cube.toml", "-o", &svg, bad[0], bad[1]]);
        let err = stderr(&o);
        assert!(
            !o.status.success() && !err.contains("panicked"),
            "{bad:?}: {err}"
        );
    }
}

#[test]
fn surfaces_writes_shaded_polygons_and_json() {
    let (svg, json) = (temp_path("surfaces.svg"), temp_path("surfaces.json"));
    let args = [
        "surfaces",
        "scenes/cube.toml",
        "-o",
        &svg,
        "--json",
        &json,
        "--view-dir",
        "-1,-2,-3",
        "--up",
        "0,0,1",
        "--outlines",
    ];
    assert_eq!(ok(&args), "");
    let text = std::fs::read_to_string(&svg).expect("the SVG");
    let doc = roxmltree::Document::parse(&text).expect("the SVG parses");
    let paths: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("path"))
        .collect();
    let value: Value = json_file(&json);
    let faces = value["faces"].as_array().expect("faces");
    assert_eq!(faces.len(), 6);
    let status = |s: &str| faces.iter().filter(|f| f["status"] == s).count();
    assert_eq!(
        (status("visible"), status("hidden"), status("mixed")),
        (3, 3, 0)
    );
    // One path per face with visible polygons, each with its object and face.
    assert_eq!(paths.len(), 3);
    for p in &paths {
        assert_eq!(p.attribute("data-object"), Some("cube"));
        assert!(p.attribute("fill").is_some_and(|f| f.starts_with("rgb(")));
    }
    for f in faces.iter().filter(|f| f["status"] == "visible") {
        let polygons = f["polygons"].as_array().expect("polygons");
        assert_eq!(polygons.len(), 1);
        assert_eq!(polygons[0]["outer"].as_array().expect("outer").len(), 4);
        assert_eq!(f["texture_polygons"].as_array().expect("texture").len(), 1);
    }
}

#[test]
fn surfaces_rejects_bad_options() {
    let out = temp_path("bad-surfaces.svg");
    let with = |extra: &[&'static str]| -> Vec<String> {
        let mut all: Vec<String> = ["surfaces", "scenes/cube.toml", "-o", &out]
            .iter()
            .map(|s| s.to_string())
            .collect();
        all.extend(extra.iter().map(|s| s.to_string()));
        all
    };
    // Rejected by the parser (usage errors, exit code 2).
    for (extra, expect) in [
        (["--light", "1,2"], "expected x,y,z"),
        (["--light", "nan,1,1"], "not a finite number"),
        (["--page", "0x10"], "not two positive sizes"),
    ] {
        let args = with(&extra);
        let o = kepler(&args.iter().map(String::as_str).collect::<Vec<_>>());
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with("error: ") && err.contains(expect), "{err}");
    }
    // Rejected by the command.
    let args = with(&["--light", "0,0,0"]);
    let message = fails(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(
        message.contains("--light 0,0,0 has no direction"),
        "{message}"
    );
    let missing = fails(&["surfaces", "scenes/nope.toml", "-o", &out]);
    assert!(missing.contains("scenes/nope.toml"), "{missing}");
}

#[test]
fn visobj_answers_for_named_objects() {
    assert_eq!(
        ok(&["visobj", "scenes/city.toml", "block", "ground"]),
        "MIXED\n"
    );
    assert_eq!(
        ok(&[
            "visobj",
            "scenes/city.toml",
            "ground",
            "block",
            "--view-dir",
            "0,0,-1"
        ]),
        "VISIBLE\n"
    );
    let missing = fails(&["visobj", "scenes/city.toml", "block", "nowhere"]);
    assert!(missing.contains("no object named 'nowhere'"), "{missing}");
}

#[test]
fn cull_prints_a_table_and_json() {
    let json = temp_path("cull.json");
    let table = ok(&["cull", "scenes/city.toml", "--json", &json]);
    let lines: Vec<&str> = table.lines().collect();
    assert!(lines[0].starts_with("328 objects, 53628 pairs"), "{table}");
    let names: Vec<&str> = lines[2..]
        .iter()
        .map(|l| l.split_whitespace().next().unwrap_or(""))
        .collect();
    assert_eq!(names, ["rstar", "cbox", "tribox", "inbox", "left"]);
    let value: Value = json_file(&json);
    assert_eq!(value["pairs"], 53628);
    let filters = value["filters"].as_array().expect("filters");
    assert_eq!(filters.len(), 4);
    // The table's numbers are the JSON's.
    for (row, f) in lines[2..6].iter().zip(filters) {
        let decided: u64 = row.split_whitespace().nth(1).unwrap().parse().unwrap();
        assert_eq!(f["decided"], decided);
    }
    let missing = fails(&["cull", "scenes/nope.toml"]);
    assert!(missing.contains("scenes/nope.toml"), "{missing}");
}

#[test]
fn render_draws_small_objects_as_ideographs() {
    let svg = temp_path("ideographs.svg");
    let o = kepler(&[
        "render",
        "scenes/city.toml",
        "-o",
        &svg,
        "--ideograph-below",
        "20",
        "--stats",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let err = stderr(&o);
    assert!(
        err.starts_with("ideographs: 265 objects below 20 mm² culled (3180 triangles;"),
        "{err}"
    );
    let o = kepler(&[
        "render",
        "scenes/city.toml",
        "-o",
        &svg,
        "--ideograph-below",
        "x",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("not a nonnegative area"));
}

#[test]
fn boxtree_sphere_experiment_prints_ours_beside_the_papers() {
    let json = temp_path("boxtree.json");
    let table = ok(&["boxtree", "--experiment", "spheres", "--json", &json]);
    let value: Value = json_file(&json);
    let rows = value.as_array().expect("rows");
    assert_eq!(rows.len(), 15);
    let shapes: Vec<&str> = rows[..5]
        .iter()
        .map(|r| r["shape"].as_str().unwrap())
        .collect();
    assert_eq!(shapes, ["aabb", "pca-all", "pca-max", "pca-min", "tribox"]);
    let aabb_1996 = rows
        .iter()
        .find(|r| r["facets"] == 1996 && r["shape"] == "aabb")
        .expect("the 1,996-facet AABB row");
    assert_eq!(aabb_1996["paper"], 35749);
    // One table line per row, with the same test counts.
    assert_eq!(table.lines().count(), 16);
    for (line, r) in table.lines().skip(1).zip(rows) {
        let tests: u64 = line.split_whitespace().nth(2).unwrap().parse().unwrap();
        assert_eq!(r["tests"], tests);
    }
}

#[test]
fn triboxes_prints_levels_and_writes_json_and_svg() {
    let (json, svg) = (temp_path("triboxes.json"), temp_path("triboxes.svg"));
    let out = ok(&[
        "triboxes",
        "scenes/solids.toml",
        "--object",
        "l-wall",
        "--levels",
        "3",
        "--json",
        &json,
        "-o",
        &svg,
    ]);
    // The L wall splits once by the gain (at x = 3): two levels, the first one tribox of 7
    // faces. The third level asked for is split below the gain, and marked.
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 6, "{out}");
    assert!(lines[0].starts_with("l-wall: N = 8 faces"), "{out}");
    let first: Vec<&str> = lines[2].split_whitespace().collect();
    assert_eq!(&first[..4], &["0", "1", "7", "1.14"], "{out}");
    assert!(
        lines[3].ends_with(')') && lines[4].ends_with(")  *"),
        "{out}"
    );
    assert!(lines[5].starts_with("* below the gain of 0.05: "), "{out}");
    let report: Value = json_file(&json);
    let levels = report["levels"].as_array().expect("levels");
    assert_eq!(levels.len(), 3);
    assert_eq!(levels[0]["triboxes"], 1);
    assert_eq!(levels[0]["faces"], 7);
    assert_eq!(levels[0]["compression"], 8.0 / 7.0);
    assert_eq!(levels[1]["triboxes"], 2);
    assert_eq!(levels[2]["triboxes"], 4);
    assert_eq!(levels[1].get("below_gain"), None);
    assert_eq!(levels[2]["below_gain"], true);
    for l in levels {
        for key in [
            "hausdorff",
            "hausdorff_lower",
            "volume_excess",
            "area_excess",
        ] {
            assert!(l[key].is_number(), "{key}: {l}");
        }
        assert!(l["hausdorff_lower"].as_f64() <= l["hausdorff"].as_f64());
    }
    // The wall is 27 units³; its tribox 58.5.
    assert_eq!(report["volume"], 27.0);
    assert_eq!(levels[0]["volume"], 58.5);
    // The gain's three nodes, and the four of the third level.
    assert_eq!(report["nodes"].as_array().unwrap().len(), 7);
    assert_eq!(report["nodes"][0]["split"]["direction"], 0);
    // The drawing: the object and three levels, side by side.
    let lines = svg_polylines(&std::fs::read_to_string(&svg).unwrap());
    assert!(lines.len() > 20, "{}", lines.len());
}

#[test]
fn triboxes_of_a_whole_scene_and_its_errors() {
    let out = ok(&["triboxes", "tests/data/cube.obj", "--levels", "2"]);
    assert!(out.starts_with("tests/data/cube.obj: N = 6 faces"), "{out}");
    let err = fails(&["triboxes", "scenes/meshes.toml", "--object", "tent"]);
    assert!(err.contains("'tent'") && err.contains("closed"), "{err}");
    let err = fails(&["triboxes", "scenes/solids.toml", "--object", "nothing"]);
    assert!(err.contains("no object named 'nothing'"), "{err}");
    let err = fails(&["triboxes", "scenes/solids.toml", "--gain", "1.5"]);
    assert!(err.starts_with("--gain: ") && err.contains("1.5"), "{err}");
    // All objects together: the open one is named.
    let err = fails(&["triboxes", "scenes/meshes.toml"]);
    assert!(err.contains("'tent'") && err.contains("closed"), "{err}");
}

#[test]
fn triboxes_says_why_it_stops_and_makes_the_levels_asked_for() {
    let ring = ["triboxes", "scenes/solids.toml", "--object", "round/ring"];
    // The ring (a torus) keeps one tribox under the paper's gain, and a note says why and
    // which gain splits it.
    let o = kepler(&ring);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o).lines().count(), 3, "{}", stdout(&o));
    let note = stderr(&o);
    assert_eq!(note.lines().count(), 1, "{note}");
    assert!(
        note.starts_with("note: the hierarchy stops at depth 0 (1 of 4 levels): "),
        "{note}"
    );
    let gain = note
        .split("--gain ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .unwrap_or_else(|| panic!("no --gain in {note}"));
    assert!(gain.parse::<f64>().unwrap() < 0.05, "{gain}");
    let o = kepler(&[&ring[..], &["--gain", gain]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).lines().count() > 3, "{}", stdout(&o));
    // Asked for four levels, it makes them, marking those split below the gain.
    let out = ok(&[&ring[..], &["--levels", "4"]].concat());
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 7, "{out}");
    for (depth, line) in lines[2..6].iter().enumerate() {
        assert!(line.trim_start().starts_with(&depth.to_string()), "{out}");
    }
    assert!(lines[3].ends_with("  *"), "{out}");
    assert!(lines[6].starts_with("* below the gain of 0.05: "), "{out}");
    // The maximum depth still bounds them, and the note says so.
    let o = kepler(&[&ring[..], &["--levels", "4", "--max-depth", "1"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o).lines().count(), 5, "{}", stdout(&o));
    assert_eq!(
        stderr(&o),
        "note: the hierarchy stops at depth 1 (2 of 4 levels): its cells are at --max-depth 1\n"
    );
}

#[test]
fn render_verify_reports_its_checks_and_writes_the_same_files() {
    let plain = (temp_path("plain.svg"), temp_path("plain.json"));
    let checked = (temp_path("checked.svg"), temp_path("checked.json"));
    for path in ["scenes/city.toml", "scenes/meshes/tent.stl"] {
        ok(&["render", path, "-o", &plain.0, "--json", &plain.1]);
        let o = kepler(&[
            "render", path, "-o", &checked.0, "--json", &checked.1, "--verify",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert_eq!(stdout(&o), "");
        let report = stderr(&o);
        let lines: Vec<&str> = report.lines().collect();
        assert_eq!(lines.len(), 3, "{report}");
        let counts: Vec<&str> = lines[0].split_whitespace().collect();
        assert_eq!(&counts[..2], ["verify:", counts[1]]);
        assert!(counts[1].parse::<usize>().expect("a count") > 0, "{report}");
        assert_eq!(&counts[2..5], ["checks,", "0", "disagreements"], "{report}");
        assert!(lines[1].starts_with("verify: ") && lines[1].contains("visibility samples"));
        assert!(lines[2].starts_with("verify: not checked: "));
        for (a, b) in [(&plain.0, &checked.0), (&plain.1, &checked.1)] {
            assert_eq!(
                std::fs::read(a).unwrap(),
                std::fs::read(b).unwrap(),
                "{path}"
            );
        }
    }
}

#[test]
fn render_verify_reports_its_checks() {
    // A box's edge through the apex of a cone, its lower half inside the cone: the pass cuts
    // the edge at the apex (see tests/verify.rs), and --verify agrees, exiting 0.
    let scene = "tests/data/edge_through_apex.toml";
    let svg = temp_path("cone.svg");
    let o = kepler(&["render", scene, "-o", &svg, "--verify"]);
    let report = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{report}");
    assert!(!report.contains("panicked"), "{report}");
    let first = report.lines().next().unwrap_or_default();
    assert!(
        first.starts_with("verify: ") && first.contains(" checks, 0 disagreements"),
        "{report}"
    );
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
}

// ---------------------------------------------------------------------------------------------
// Issue 14: degenerate faces, polygons not exactly planar, `--strict`, `--edges mesh`, PLY.

/// A unit cube as OBJ with a zero-area sliver along an edge, a face repeating a vertex, and
/// its top quad bent by one ulp (not exactly planar), written to a temporary file.
fn repaired_cube() -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("kepler-cli-issue14-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("repaired.obj");
    let mut text = String::new();
    for i in 0..8 {
        let z = if i == 7 {
            "1.0000000000000002"
        } else {
            ["0", "1"][i >> 2]
        };
        text += &format!("v {} {} {z}\n", i & 1, i >> 1 & 1);
    }
    text += "v 0.5 0 0\n";
    for f in [
        "1 5 7 3", "2 4 8 6", "1 2 6 5", "3 7 8 4", "1 3 4 2", "5 6 8 7", "1 9 2", "5 6 5",
    ] {
        text += &format!("f {f}\n");
    }
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn render_stats_count_the_repairs_and_strict_refuses_them() {
    let path = repaired_cube();
    let file = path.to_str().unwrap();
    let o = kepler(&["render", file, "-o", "-", "--stats", "--edges", "mesh"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).starts_with("<?xml") || stdout(&o).starts_with("<svg"));
    let stats = stderr(&o);
    assert!(
        stats.contains(
            "faces: 2 degenerate faces dropped, 1 polygons not exactly planar split into \
             triangles, 0 sides matched at T-junctions (in 1 meshes)"
        ),
        "{stats}"
    );
    let e = fails(&["render", file, "-o", "-", "--strict"]);
    assert!(e.ends_with("repaired.obj:15: face 6 is not planar: its corner 4 is off the plane of its first corners"), "{e}");
    let e = fails(&["bounds", file, "--strict"]);
    assert!(
        e.ends_with(
            ":15: face 6 is not planar: its corner 4 is off the plane of its first corners"
        ),
        "{e}"
    );
    let table = ok(&["bounds", file]);
    assert!(
        table.lines().nth(1).is_some_and(|l| l.contains(" yes ")),
        "{table}"
    );
}

#[test]
fn an_unknown_scene_key_of_a_megabyte_is_not_echoed_whole() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("kepler-cli-issue14-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("huge-key.toml");
    let key = "k".repeat(1 << 20);
    std::fs::write(
        &path,
        format!("[[object]]\nname = \"c\"\nsolid = \"cube\"\n{key} = 1\n"),
    )
    .unwrap();
    let e = fails(&["bounds", path.to_str().unwrap()]);
    assert!(
        e.len() < 400 && e.contains(":4: unknown field `kkkk"),
        "{} bytes: {}",
        e.len(),
        &e[..e.len().min(400)]
    );
}

/// `kepler gen`: a stiff scene written as OBJ files and a scene file with its camera, which
/// `render --verify` draws and checks; `--list`; a stiffness outside the family's range.
#[test]
fn gen_writes_a_stiff_scene_that_renders_and_lists_the_families() {
    let list = ok(&["gen", "--list"]);
    assert_eq!(list.lines().count(), 11, "{list}");
    assert!(
        list.contains("edge-on") && list.contains("tilt 10^-k"),
        "{list}"
    );
    let dir = temp_path("gen");
    let out = ok(&[
        "gen", "--family", "tilt", "--k", "12", "--seed", "3", "-o", &dir,
    ]);
    let toml = format!("{dir}/tilt-k12-seed3.toml");
    assert_eq!(out, format!("{toml}\n"));
    let text = std::fs::read_to_string(&toml).expect("the scene file");
    assert!(text.contains("[camera]") && text.contains("tilt-k12-seed3-plate.obj"));
    let o = kepler(&["render", &toml, "-o", &temp_path("gen.svg"), "--verify"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains(", 0 disagreements"), "{}", stderr(&o));
    // Negative stiffness; every value of the list without --k.
    let out = ok(&["gen", "--family", "scale", "--k", "-280", "-o", &dir]);
    assert!(out.ends_with("scale-k-280-seed0.toml\n"), "{out}");
    let out = ok(&["gen", "--family", "sliver", "--seed", "2", "-o", &dir]);
    assert_eq!(out.lines().count(), 7, "{out}");
    let e = fails(&["gen", "--family", "tilt", "--k", "17", "-o", &dir]);
    assert_eq!(
        e,
        "tilt: k = 17 is outside 1..=16 (tilt 10^-k (k = 16: coplanar))"
    );
    let o = kepler(&["gen", "--family", "wobble"]);
    assert!(!o.status.success() && stderr(&o).contains("unknown family (one of tilt,"));
}

/// The drawing does not depend on the number of threads (issue 16): the same bytes of SVG and
/// JSON with one thread and with four, for scenes that take every parallel path (many objects,
/// a large mesh, intersection lines, a clipping perspective view).
#[test]
fn one_thread_and_four_write_the_same_bytes() {
    let dir = std::env::temp_dir().join(format!("kepler-threads-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases: [&[&str]; 4] = [
        &["render", "scenes/metropolis.toml", "--edges", "all"],
        &["render", "scenes/bunny.toml", "--edges", "all"],
        &["render", "scenes/solids.toml", "--view-dir", "1,2,-3"],
        &["surfaces", "scenes/city.toml"],
    ];
    for (k, args) in cases.iter().enumerate() {
        let written = |threads: &str| -> (Vec<u8>, Vec<u8>) {
            let svg = dir.join(format!("{k}-{threads}.svg"));
            let json = dir.join(format!("{k}-{threads}.json"));
            let o = Command::new(env!("CARGO_BIN_EXE_kepler"))
                .args(*args)
                .args([
                    "-o",
                    svg.to_str().unwrap(),
                    "--json",
                    json.to_str().unwrap(),
                ])
                .env("RAYON_NUM_THREADS", threads)
                .current_dir(env!("CARGO_MANIFEST_DIR"))
                .output()
                .expect("the kepler binary runs");
            assert!(o.status.success(), "{args:?}: {}", stderr(&o));
            (std::fs::read(svg).unwrap(), std::fs::read(json).unwrap())
        };
        let (one, four) = (written("1"), written("4"));
        assert!(!one.0.is_empty() && !one.1.is_empty());
        assert!(one == four, "{args:?}: one thread and four differ");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `--order` orders the hatch layer too: the same segments, bit for bit, with less travel.
#[test]
fn render_order_orders_the_hatch_layer() {
    let hatch = |order: bool| {
        let svg = temp_path(if order {
            "hatch-ordered.svg"
        } else {
            "hatch-plain.svg"
        });
        let mut args = vec!["render", "scenes/solids.toml", "-o", &svg, "--hatch"];
        if order {
            args.push("--order");
        }
        ok(&args);
        let text = std::fs::read_to_string(&svg).expect("the SVG");
        svg_polylines(&text)
            .into_iter()
            .filter(|(layer, _)| layer == "hatch")
            .map(|(_, points)| points)
            .collect::<Vec<Vec<[f64; 2]>>>()
    };
    let (plain, ordered) = (hatch(false), hatch(true));
    let segments = |paths: &[Vec<[f64; 2]>]| {
        let mut s: Vec<[[u64; 2]; 2]> = paths
            .iter()
            .flat_map(|p| {
                p.windows(2)
                    .map(|w| [w[0], w[1]].map(|q| q.map(f64::to_bits)))
            })
            .map(|[a, b]| if a <= b { [a, b] } else { [b, a] })
            .collect();
        s.sort_unstable();
        s
    };
    assert!(plain.len() > 100);
    assert_eq!(segments(&plain), segments(&ordered));
    let travel = |paths: &[Vec<[f64; 2]>]| {
        paths
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0][w[0].len() - 1], w[1][0]);
                (b[0] - a[0]).hypot(b[1] - a[1])
            })
            .sum::<f64>()
    };
    assert!(
        travel(&ordered) < 0.5 * travel(&plain),
        "{} vs {}",
        travel(&ordered),
        travel(&plain)
    );
}
