//! Check 3: the drawing's segments are exactly the pieces' pictures as drawn (see the module
//! documentation of [`verify`](super)).

use super::super::{EdgeClass, Options};
use super::report::{Check, Disagreement, Verification};
use super::trace::Traced;
use std::collections::HashMap;

/// Check 3: the drawing's segments are the pieces'.
pub(super) fn drawing(options: &Options, traced: &Traced, report: &mut Verification) {
    let key = |p: [f64; 2]| p.map(|x| (x + 0.0).to_bits());
    let segment = |class: EdgeClass, visible: bool, [p, q]: [[f64; 2]; 2]| {
        let (p, q) = (key(p), key(q));
        (class, visible, if p <= q { [p, q] } else { [q, p] })
    };
    let mut count: HashMap<(EdgeClass, bool, [[u64; 2]; 2]), i64> = HashMap::new();
    // A piece whose ends are equal, as traced at the input's scale (of zero length, or
    // rounded to one point when scaled back: `draw_traced` scales them as `Drawing::scaled`
    // scales the drawing), is not drawn.
    for p in &traced.pieces {
        if p.ends[0] != p.ends[1] && (p.visible || options.hidden) {
            *count
                .entry(segment(p.class, p.visible, p.ends))
                .or_default() += 1;
        }
    }
    for l in &traced.kept.as_ref().unwrap_or(&traced.drawing).polylines {
        for w in l.points.windows(2) {
            report.segments += 1;
            *count
                .entry(segment(l.class, l.visible, [w[0], w[1]]))
                .or_default() -= 1;
        }
    }
    let mut differing: Vec<_> = count.into_iter().filter(|&(_, n)| n != 0).collect();
    differing.sort_unstable_by_key(|x| x.0);
    for ((class, visible, [p, q]), n) in differing {
        let point = |k: [u64; 2]| {
            let [x, y] = k.map(f64::from_bits);
            format!("({x}, {y})")
        };
        let what = |n: i64| {
            format!(
                "{} {} {} segment{}",
                n.abs(),
                if visible { "visible" } else { "hidden" },
                class.name(),
                if n.abs() == 1 { "" } else { "s" }
            )
        };
        let (expected, found) = if n > 0 {
            (what(n), "none drawn".to_string())
        } else {
            ("no piece".to_string(), what(n))
        };
        report.disagree(Disagreement {
            check: Check::Drawing,
            object: String::new(),
            line: format!("segment {}–{}", point(p), point(q)),
            at: "its ends".to_string(),
            expected,
            found,
        });
    }
}
