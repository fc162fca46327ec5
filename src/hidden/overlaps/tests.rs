//! Overlap removal against a reference that shares none of its geometry: every piece's end
//! as an exact rational point of space, its picture by an exact rational map (perspective:
//! centred exactly at the eye; orthographic: a projection whose kernel is exactly the view
//! direction), lines grouped by comparing every pair, positions along a picture line as
//! rationals. On random scenes of touching, stacked and sunk boxes and tetrahedra with dyadic
//! coordinates, in views along the axes, oblique and in perspective, the two must give the
//! same segments, bit for bit.

use super::{drawn_once, rank, unranked};
use crate::geometry::{Point3, Vector3};
use crate::hidden::marks::Provenance;
use crate::hidden::piece::Piece;
use crate::hidden::{EdgeClass, EdgeSelection, Options, Pass, decided};
use crate::mesh::Mesh;
use crate::scene::Scene;
use crate::sight::collinear::LinePoint;
use crate::views::{Eye, Picture, View};
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use std::collections::HashMap;

type Q = BigRational;

fn q(x: f64) -> Q {
    BigRational::from_float(x).expect("finite")
}

/// A segment of a drawing: class, visibility and its ends' bits in either order.
type KeyedSegment = (EdgeClass, bool, [[u64; 2]; 2]);

fn segment(class: EdgeClass, visible: bool, ends: [[f64; 2]; 2]) -> KeyedSegment {
    let bits = |p: [f64; 2]| p.map(|x| (x + 0.0).to_bits());
    let (a, b) = (bits(ends[0]), bits(ends[1]));
    (class, visible, if a <= b { [a, b] } else { [b, a] })
}

/// An exact picture map whose lines are the planes of sight.
struct Exact {
    eye: Eye,
    rows: [[Q; 3]; 3],
}

impl Exact {
    fn of(picture: &Picture, eye: &Eye) -> Exact {
        let (rows, _) = picture.rows();
        let v = |r: &Vector3| [q(r[0]), q(r[1]), q(r[2])];
        let rows = match eye {
            Eye::Point(_) => [v(&rows[0]), v(&rows[1]), v(&rows[2])],
            Eye::Infinity(u) => {
                // Two rows exactly orthogonal to u.
                let u = v(u);
                let k = (0..3)
                    .min_by(|&i, &j| u[i].abs().cmp(&u[j].abs()))
                    .unwrap_or(0);
                let mut axis = [Q::zero(), Q::zero(), Q::zero()];
                axis[k] = q(1.0);
                let w0 = cross(&u, &axis);
                let w1 = cross(&u, &w0);
                [w0, w1, axis]
            }
        };
        Exact { eye: *eye, rows }
    }

    fn picture(&self, x: &[Q; 3]) -> [Q; 2] {
        match self.eye {
            Eye::Point(e) => {
                let d = [&x[0] - q(e.x), &x[1] - q(e.y), &x[2] - q(e.z)];
                let depth = dot(&self.rows[2], &d);
                [
                    dot(&self.rows[0], &d) / &depth,
                    dot(&self.rows[1], &d) / &depth,
                ]
            }
            Eye::Infinity(_) => [dot(&self.rows[0], x), dot(&self.rows[1], x)],
        }
    }

    /// The exact picture of a point of a line.
    fn of_point(&self, p: &LinePoint) -> [Q; 2] {
        let (v, w) = p.lift::<Q>(&self.eye, &Point3::origin());
        self.picture(&v.map(|c| c / &w))
    }
}

fn dot(a: &[Q; 3], b: &[Q; 3]) -> Q {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

fn cross(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

fn turn(a: &[Q; 2], b: &[Q; 2], c: &[Q; 2]) -> Q {
    (&b[0] - &a[0]) * (&c[1] - &a[1]) - (&b[1] - &a[1]) * (&c[0] - &a[0])
}

/// The reference: overlap removal by brute force in rationals.
fn reference(pass: &Pass, pieces: &[Piece]) -> Vec<KeyedSegment> {
    let exact = Exact::of(&pass.picture, &pass.eye);
    let mut lines: Vec<usize> = pieces.iter().map(|p| p.line).collect();
    lines.sort_unstable();
    lines.dedup();
    // Each pictured line's exact picture: two distinct points.
    let pictured: HashMap<usize, [[Q; 2]; 2]> = lines
        .iter()
        .filter(|&&l| pass.support(l).is_pictured(&pass.eye))
        .map(|&l| (l, pass.support(l).points().map(|p| exact.of_point(&p))))
        .collect();
    let groups = collinear_groups(&lines, &pictured);
    let mut out = Vec::new();
    let mut replaced = vec![false; pieces.len()];
    for group in groups.values().filter(|g| g.len() > 1) {
        let ends = &pictured[&group[0]];
        sweep_group(pass, &exact, pieces, group, ends, &mut replaced, &mut out);
    }
    out.extend(
        pieces
            .iter()
            .zip(&replaced)
            .filter(|(_, r)| !**r)
            .map(|(p, _)| segment(p.class, p.visible, p.ends)),
    );
    out.sort_unstable_by_key(|s| (s.0 as u8, s.1, s.2));
    out
}

/// The pictured `lines` grouped by the line of the picture they lie on (`pictured`: each
/// one's exact picture, two distinct points), comparing every pair: each group by its least
/// line.
fn collinear_groups(
    lines: &[usize],
    pictured: &HashMap<usize, [[Q; 2]; 2]>,
) -> HashMap<usize, Vec<usize>> {
    let mut parent: HashMap<usize, usize> = lines.iter().map(|&l| (l, l)).collect();
    fn root(parent: &mut HashMap<usize, usize>, mut l: usize) -> usize {
        while parent[&l] != l {
            l = parent[&l];
        }
        l
    }
    for (i, &a) in lines.iter().enumerate() {
        for &b in &lines[i + 1..] {
            let (Some(pa), Some(pb)) = (pictured.get(&a), pictured.get(&b)) else {
                continue;
            };
            if turn(&pa[0], &pa[1], &pb[0]).is_zero() && turn(&pa[0], &pa[1], &pb[1]).is_zero() {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                parent.insert(ra.max(rb), ra.min(rb));
            }
        }
    }
    let mut groups: HashMap<usize, Vec<usize>> = HashMap::new();
    for &l in lines {
        let r = root(&mut parent, l);
        groups.entry(r).or_default().push(l);
    }
    groups
}

/// Sweeps the pieces on the lines of one `group` (one line of the picture through `ends`)
/// along it: each run covered without a gap, when covered twice somewhere, is drawn once by
/// the rank on top, its pieces marked `replaced`, its segments added to `out`.
fn sweep_group(
    pass: &Pass,
    exact: &Exact,
    pieces: &[Piece],
    group: &[usize],
    ends: &[[Q; 2]; 2],
    replaced: &mut [bool],
    out: &mut Vec<KeyedSegment>,
) {
    let [p0, p1] = ends;
    let d = [&p1[0] - &p0[0], &p1[1] - &p0[1]];
    let position = |x: &[Q; 2]| (&x[0] - &p0[0]) * &d[0] + (&x[1] - &p0[1]) * &d[1];
    // (position, key, picture, rank, +1 / −1, piece)
    let mut events = Vec::new();
    let members: Vec<usize> = (0..pieces.len())
        .filter(|&k| group.contains(&pieces[k].line))
        .collect();
    for &k in &members {
        let p = &pieces[k];
        let at = |e: usize| {
            let x = exact.of_point(&pass.point(p.line, p.marks[e]));
            (position(&x), pass.key(p.line, p.marks[e]), p.ends[e])
        };
        let (a, b) = (at(0), at(1));
        let (lo, hi) = if a.0 < b.0 { (a, b) } else { (b, a) };
        events.push((lo.0, lo.1, lo.2, rank(p.class, p.visible), 1, k));
        events.push((hi.0, hi.1, hi.2, rank(p.class, p.visible), -1, k));
    }
    events.sort_by(|x, y| x.0.cmp(&y.0));
    // Runs of the line covered without a gap, each drawn once if covered twice.
    let mut count = [0i32; 10];
    let (mut covering, mut twice) = (0, false);
    let mut run: Vec<usize> = Vec::new();
    let mut swept: Vec<(usize, [[f64; 2]; 2], usize)> = Vec::new();
    let mut from: Option<[f64; 2]> = None;
    let (mut i, mut position) = (0, 0);
    while i < events.len() {
        let j = (i..events.len())
            .find(|&j| events[j].0 != events[i].0)
            .unwrap_or(events.len());
        let here = events[i..j].iter().min_by_key(|e| e.1).unwrap().2;
        if let (Some(start), Some(top)) = (from, count.iter().rposition(|&c| c > 0)) {
            twice |= covering >= 2;
            match swept.last_mut() {
                Some(last) if last.0 == top && last.2 + 1 == position => {
                    last.1[1] = here;
                    last.2 = position;
                }
                _ => swept.push((top, [start, here], position)),
            }
        }
        for e in &events[i..j] {
            count[e.3] += e.4;
            covering += e.4;
            if e.4 > 0 {
                run.push(e.5);
            }
        }
        if covering == 0 {
            if twice {
                run.iter().for_each(|&k| replaced[k] = true);
                out.extend(swept.drain(..).map(|(r, ends, _)| {
                    let (class, visible) = unranked(r);
                    segment(class, visible, ends)
                }));
            }
            (twice, run, swept) = (false, Vec::new(), Vec::new());
        }
        from = Some(here);
        position += 1;
        i = j;
    }
}

/// A small seeded generator (SplitMix64).
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) % n
    }

    /// A multiple of 1/4 in `[0, n/4]`.
    fn quarter(&mut self, n: u64) -> f64 {
        self.below(n + 1) as f64 / 4.0
    }
}

fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Mesh {
    let v: Vec<Point3> = (0..8)
        .map(|i| {
            let c = |k: usize| if i >> k & 1 == 0 { lo[k] } else { hi[k] };
            Point3::new(c(0), c(1), c(2))
        })
        .collect();
    let faces = vec![
        vec![0, 2, 3, 1],
        vec![4, 5, 7, 6],
        vec![0, 1, 5, 4],
        vec![2, 6, 7, 3],
        vec![0, 4, 6, 2],
        vec![1, 3, 7, 5],
    ];
    Mesh::from_polygons(v, faces).expect("a box")
}

fn tetrahedron(rng: &mut Rng) -> Option<Mesh> {
    let mut v: Vec<Point3> = (0..4)
        .map(|_| Point3::new(rng.quarter(16), rng.quarter(16), rng.quarter(12)))
        .collect();
    match crate::geometry::predicates::orient3d(&v[0], &v[1], &v[2], &v[3]) {
        std::cmp::Ordering::Equal => return None,
        std::cmp::Ordering::Less => v.swap(0, 1),
        std::cmp::Ordering::Greater => {}
    }
    Mesh::from_polygons(
        v,
        vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![0, 3, 2]],
    )
    .ok()
}

/// A scene of boxes on a quarter lattice (stacked, touching, sunk) and some tetrahedra.
fn scene(rng: &mut Rng) -> Scene {
    let mut scene = Scene::new();
    for k in 0..3 + rng.below(5) {
        let lo = [rng.quarter(12), rng.quarter(12), rng.quarter(8)];
        let size = [0, 1, 2].map(|_| 0.5 * (1 + rng.below(4)) as f64);
        let hi = [0, 1, 2].map(|i| lo[i] + size[i]);
        scene
            .add_mesh(None, format!("box{k}"), cuboid(lo, hi))
            .expect("added");
        if rng.below(3) == 0 {
            // Its neighbour, face to face along x, or stacked on it.
            let axis = [0, 2][rng.below(2) as usize];
            let (mut lo2, mut hi2) = (lo, hi);
            lo2[axis] = hi[axis];
            hi2[axis] = hi[axis] + size[axis];
            scene
                .add_mesh(None, format!("next{k}"), cuboid(lo2, hi2))
                .expect("added");
        }
    }
    for k in 0..rng.below(3) {
        if let Some(t) = tetrahedron(rng) {
            scene.add_mesh(None, format!("tet{k}"), t).expect("added");
        }
    }
    scene
}

fn views() -> Vec<View> {
    let o = |x: f64, y: f64, z: f64, up: Vector3| View::orthographic(Vector3::new(x, y, z), up);
    let p =
        |e: [f64; 3]| View::perspective(e.into(), Point3::new(2.0, 2.0, 1.0), Vector3::z(), 40.0);
    [
        o(0.0, -1.0, 0.0, Vector3::z()),
        o(1.0, 0.0, 0.0, Vector3::z()),
        o(0.0, 0.0, -1.0, Vector3::y()),
        o(-1.0, -2.0, -3.0, Vector3::z()),
        o(1.0, 1.0, -1.0, Vector3::z()),
        p([9.0, -7.0, 5.0]),
        p([2.0, -9.0, 1.0]),
    ]
    .into_iter()
    .map(|v| v.expect("a view"))
    .collect()
}

#[test]
fn the_sweep_agrees_with_rational_brute_force() {
    let mut changed = 0;
    for seed in 0..8 {
        let mut rng = Rng(0x0727_0000 + seed);
        let scene = scene(&mut rng);
        for (k, view) in views().iter().enumerate() {
            for edges in [EdgeSelection::Feature, EdgeSelection::All] {
                let options = Options {
                    edges,
                    ..Options::default()
                };
                let (pass, pieces) = decided(&scene, view, None, &options, &|_, _| {}).unwrap();
                let expected = reference(&pass, &pieces);
                let (once, report) = drawn_once(&pass, pieces);
                let mut got: Vec<KeyedSegment> = once
                    .iter()
                    .map(|p| segment(p.class, p.visible, p.ends))
                    .collect();
                got.sort_unstable_by_key(|s| (s.0 as u8, s.1, s.2));
                assert!(
                    got == expected,
                    "seed {seed}, view {k}, {edges:?}: {report:?}"
                );
                changed += report.groups;
            }
        }
    }
    eprintln!("{changed} groups changed");
    assert!(
        changed > 1000,
        "only {changed} groups changed: the test tests little"
    );
}
