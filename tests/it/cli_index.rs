//! `kepler index SCENE -o FILE.kix`: every command reads the index as the scene itself.

use super::cli::{fails, ok};

#[test]
fn an_index_draws_and_bounds_as_its_scene() {
    let dir = std::env::temp_dir().join(format!("kepler-cli-index-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let at = |name: &str| dir.join(name).display().to_string();
    let (kix, a, b) = (at("city.kix"), at("a.svg"), at("b.svg"));
    assert_eq!(ok(&["index", "scenes/city.toml", "-o", &kix]), "");
    for extra in [&[][..], &["--edges", "all", "--view-dir", "-1,-2,-3"][..]] {
        let mut args = vec!["render", "scenes/city.toml", "-o", &a];
        args.extend(extra);
        ok(&args);
        let mut args = vec!["render", &kix, "-o", &b];
        args.extend(extra);
        ok(&args);
        assert!(
            std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap(),
            "{extra:?}"
        );
    }
    assert_eq!(
        ok(&["bounds", &kix, "--json"]),
        ok(&["bounds", "scenes/city.toml", "--json"])
    );
    assert_eq!(
        fails(&["index", "scenes/city.toml", "-o", &a]),
        format!("a scene index's name ends in .kix, not {a}")
    );
    std::fs::write(&b, b"KINDEX\x00\x01").unwrap();
    let bad = at("bad.kix");
    std::fs::copy(&b, &bad).unwrap();
    assert_eq!(
        fails(&["render", &bad, "-o", &a]),
        format!("{bad}:camera: not a kepler scene index, or a damaged one")
    );
}
