//! The invariance harness: a scene of solids and a view, transformed exactly (mirrored,
//! with faces reversed, axes permuted, scaled by a power of two, translated by an exactly
//! representable vector), must draw the same segments, transformed as the picture transforms,
//! bit for bit. Used by the families of `intersection_lines.rs` (intersection lines) and
//! `plotter.rs` (each stretch of line drawn once). Drawings are compared as multisets of
//! segments (class, visibility, ends in either order, `-0` read as `0`): how pieces chain into
//! polylines may legitimately differ, nothing else; and the overlap stage must have removed
//! the same groups of segments.

use super::SplitMix64;
use kepler::geometry::{Point3, Vector3};
use kepler::hidden::{Drawing, EdgeClass, Options, draw};
use kepler::mesh::Mesh;
use kepler::scene::Scene;
use kepler::views::{Picture, View};

/// A solid as input: vertices and polygon faces.
#[derive(Clone, Debug)]
pub struct Solid {
    pub vertices: Vec<Point3>,
    pub faces: Vec<Vec<u32>>,
}

impl Solid {
    pub fn mesh(&self) -> Mesh {
        Mesh::from_polygons(self.vertices.clone(), self.faces.clone()).unwrap()
    }

    pub fn map(&self, f: &impl Fn(&Point3) -> Point3) -> Solid {
        Solid {
            vertices: self.vertices.iter().map(f).collect(),
            faces: self.faces.clone(),
        }
    }

    /// Each face split into a fan of triangles.
    pub fn triangulated(&self) -> Solid {
        Solid {
            vertices: self.vertices.clone(),
            faces: self
                .faces
                .iter()
                .flat_map(|f| (1..f.len() - 1).map(move |i| vec![f[0], f[i], f[i + 1]]))
                .collect(),
        }
    }

    pub fn reversed(&self) -> Solid {
        Solid {
            vertices: self.vertices.clone(),
            faces: self
                .faces
                .iter()
                .map(|f| f.iter().rev().copied().collect())
                .collect(),
        }
    }
}

/// A view as input.
#[derive(Clone, Copy, Debug)]
pub enum ViewSpec {
    Orthographic {
        direction: Vector3,
        up: Vector3,
    },
    Perspective {
        eye: Point3,
        target: Point3,
        up: Vector3,
    },
}

impl ViewSpec {
    pub fn view(&self) -> Option<View> {
        match *self {
            ViewSpec::Orthographic { direction, up } => View::orthographic(direction, up).ok(),
            ViewSpec::Perspective { eye, target, up } => {
                View::perspective(eye, target, up, 40.0).ok()
            }
        }
    }

    pub fn is_perspective(&self) -> bool {
        matches!(self, ViewSpec::Perspective { .. })
    }
}

/// A transformation of scene and view.
#[derive(Clone, Copy, Debug)]
pub enum Transform {
    /// `x[axis] ↦ -x[axis]`.
    Mirror(usize),
    /// `x ↦ (x[p[0]], x[p[1]], x[p[2]])`.
    Permute([usize; 3]),
    /// `x ↦ 2^k·x`.
    Scale(i32),
    /// `x ↦ x + t` (points only).
    Translate([f64; 3]),
}

impl Transform {
    /// The linear part, on a vector.
    pub fn vector(&self, v: &Vector3) -> Vector3 {
        match *self {
            Transform::Mirror(a) => {
                let mut w = *v;
                w[a] = -w[a];
                w
            }
            Transform::Permute(p) => Vector3::new(v[p[0]], v[p[1]], v[p[2]]),
            Transform::Scale(_) | Transform::Translate(_) => *v,
        }
    }

    pub fn point(&self, x: &Point3) -> Point3 {
        match *self {
            Transform::Scale(k) => Point3::from(x.coords * 2f64.powi(k)),
            Transform::Translate(t) => {
                let y = Point3::new(x.x + t[0], x.y + t[1], x.z + t[2]);
                assert_eq!(y - Vector3::from(t), *x, "translation not exact");
                y
            }
            _ => Point3::from(self.vector(&x.coords)),
        }
    }

    pub fn view(&self, v: &ViewSpec) -> ViewSpec {
        match *v {
            ViewSpec::Orthographic { direction, up } => ViewSpec::Orthographic {
                direction: self.vector(&direction),
                up: self.vector(&up),
            },
            ViewSpec::Perspective { eye, target, up } => ViewSpec::Perspective {
                eye: self.point(&eye),
                target: self.point(&target),
                up: self.vector(&up),
            },
        }
    }

    /// How the picture is expected to change, from the two views' picture maps: `(sx, sy,
    /// c)` with `(x, y) ↦ (sx·c·x, sy·c·y)`, or `None` where the transformed view's frame is
    /// not exactly the transformed frame (its normalisation rounded differently).
    pub fn picture(&self, before: &View, after: &View) -> Option<(f64, f64, f64)> {
        let (r, _) = Picture::of(before).rows();
        let (s, _) = Picture::of(after).rows();
        let sign = |k: usize| {
            let t = self.vector(&r[k]);
            if s[k] == t {
                Some(1.0)
            } else if s[k] == -t {
                Some(-1.0)
            } else {
                None
            }
        };
        let (sx, sy, sz) = (sign(0)?, sign(1)?, sign(2)?);
        let perspective = before.is_perspective();
        if perspective && sz != 1.0 {
            return None;
        }
        let c = match *self {
            Transform::Scale(k) if !perspective => 2f64.powi(k),
            _ => 1.0,
        };
        Some((sx, sy, c))
    }
}

pub fn dyadic(rng: &mut SplitMix64, lo: i32, hi: i32) -> f64 {
    rng.int(4 * lo, 4 * hi) / 4.0
}

pub fn box_solid(min: [f64; 3], max: [f64; 3]) -> Solid {
    let m = kepler::solids::box_between(min, max).unwrap();
    Solid {
        vertices: m.vertices().to_vec(),
        faces: m.faces().iter().map(|f| f.vertices().to_vec()).collect(),
    }
}

/// A solid of the given vertices and faces, turned outward.
pub fn outward(vertices: Vec<Point3>, faces: Vec<Vec<u32>>) -> Solid {
    let s = Solid { vertices, faces };
    if s.mesh().volume() < 0.0 {
        s.reversed()
    } else {
        s
    }
}

pub fn small_vector(rng: &mut SplitMix64) -> Vector3 {
    loop {
        let v = Vector3::new(rng.int(-4, 4), rng.int(-4, 4), rng.int(-4, 4));
        if v != Vector3::zeros() {
            return v;
        }
    }
}

pub fn random_view(rng: &mut SplitMix64, perspective: bool) -> ViewSpec {
    loop {
        let up = small_vector(rng);
        let spec = if perspective {
            let eye = Point3::from(small_vector(rng) * 8.0);
            if eye.coords.norm() < 24.0 {
                continue;
            }
            let target = Point3::new(dyadic(rng, -1, 1), dyadic(rng, -1, 1), dyadic(rng, -1, 1));
            ViewSpec::Perspective { eye, target, up }
        } else {
            ViewSpec::Orthographic {
                direction: small_vector(rng),
                up,
            }
        };
        if spec.view().is_some() {
            return spec;
        }
    }
}

pub type Segment = (EdgeClass, bool, [[u64; 2]; 2]);

/// The drawing's segments, sorted: each with its ends in order, `-0` read as `0`.
pub fn segments(d: &Drawing, map: impl Fn([f64; 2]) -> [f64; 2]) -> Vec<Segment> {
    let bits = |p: [f64; 2]| map(p).map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
    let mut out: Vec<Segment> = d
        .polylines
        .iter()
        .flat_map(|p| {
            p.points.windows(2).map(move |w| {
                let (a, b) = (bits(w[0]), bits(w[1]));
                (p.class, p.visible, if a <= b { [a, b] } else { [b, a] })
            })
        })
        .collect();
    out.sort_unstable_by_key(|x| (x.0 as u8, x.1, x.2));
    out
}

/// Where two segment lists differ, for the failure message.
pub fn difference(a: &[Segment], b: &[Segment]) -> String {
    let only = |x: &[Segment], y: &[Segment]| -> Vec<String> {
        x.iter()
            .filter(|s| !y.contains(s))
            .take(4)
            .map(|(c, v, e)| {
                let p = e.map(|p| p.map(f64::from_bits));
                format!("{c:?} {v} {p:?}")
            })
            .collect()
    };
    format!(
        "{} vs {} segments; only in the first: {:?}; only in the second: {:?}",
        a.len(),
        b.len(),
        only(a, b),
        only(b, a)
    )
}

/// What a family of checks covered.
#[derive(Default, Debug)]
pub struct Tally {
    /// The scene's seed.
    pub seed: u64,
    pub compared: usize,
    pub skipped: usize,
    /// Cases whose drawing has what the family is about (see [`Setup::about`]).
    pub interesting: usize,
}

/// What a family draws: its options, its random scenes, and what its drawings must have
/// for a case to count.
pub struct Setup {
    pub options: Options,
    pub seeds: u64,
    pub base: u64,
    pub scene: fn(&mut SplitMix64) -> Vec<Solid>,
    /// Whether a drawing has what the family is about (intersection lines, overlaps).
    pub about: fn(&Drawing) -> bool,
}

pub fn drawing(solids: &[Solid], view: &View, options: &Options) -> Drawing {
    let mut scene = Scene::new();
    for (i, s) in solids.iter().enumerate() {
        scene.add_mesh(None, format!("s{i}"), s.mesh()).unwrap();
    }
    draw(&scene, view, options).unwrap()
}

/// What the overlap stage removed: its report without the length removed (which scales).
pub fn overlaps_removed(d: &Drawing) -> String {
    d.stages
        .iter()
        .find(|s| s.name == "overlaps")
        .map(|s| s.done.split(" (").next().unwrap_or("").to_string())
        .unwrap_or_default()
}

/// Draws the scene and its transformed copy (solids also passed through `solids`) and checks
/// that the second drawing is the first with the expected picture change.
pub fn check(
    setup: &Setup,
    tally: &mut Tally,
    name: &str,
    scene: &[Solid],
    spec: &ViewSpec,
    t: Option<Transform>,
    solids: impl Fn(&Solid) -> Solid,
) {
    let view = spec.view().unwrap();
    let changed = |s: &Solid| match t {
        Some(t) => solids(&s.map(&|p| t.point(p))),
        None => solids(s),
    };
    // A quad whose vertices, moved far, no longer pass the meshes' planarity check (done in
    // floating point) is split into triangles in both scenes.
    let scene: Vec<Solid> = scene
        .iter()
        .map(|s| {
            let c = changed(s);
            if Mesh::from_polygons(c.vertices, c.faces).is_ok() {
                s.clone()
            } else {
                s.triangulated()
            }
        })
        .collect();
    let scene = &scene[..];
    let spec2 = t.map_or(*spec, |t| t.view(spec));
    let scene2: Vec<Solid> = scene.iter().map(changed).collect();
    let Some(view2) = spec2.view() else {
        tally.skipped += 1;
        return;
    };
    let (sx, sy, c) = match t {
        Some(t) => match t.picture(&view, &view2) {
            Some(m) => m,
            None => {
                tally.skipped += 1;
                return;
            }
        },
        None => (1.0, 1.0, 1.0),
    };
    let d1 = drawing(scene, &view, &setup.options);
    let d2 = drawing(&scene2, &view2, &setup.options);
    let a = segments(&d1, |p| [sx * c * p[0], sy * c * p[1]]);
    let b = segments(&d2, |p| p);
    assert!(
        a == b,
        "{name}, seed {}: {t:?}, view {spec:?}: {}",
        tally.seed,
        difference(&a, &b)
    );
    assert_eq!(
        overlaps_removed(&d1),
        overlaps_removed(&d2),
        "{name}, seed {}: {t:?}, view {spec:?}: other overlaps removed",
        tally.seed
    );
    tally.compared += 1;
    if (setup.about)(&d1) {
        tally.interesting += 1;
    }
}

/// Runs `family` over the setup's random scenes, in both projections, and checks that half
/// the cases compared had what the family is about.
pub fn over_scenes(
    setup: &Setup,
    name: &str,
    family: impl Fn(&mut Tally, &mut SplitMix64, &[Solid], &ViewSpec),
) -> Tally {
    let mut tally = Tally::default();
    for seed in 0..setup.seeds {
        let mut rng = SplitMix64(setup.base + seed);
        tally.seed = seed;
        let scene = (setup.scene)(&mut rng);
        for perspective in [false, true] {
            let spec = random_view(&mut rng, perspective);
            family(&mut tally, &mut rng, &scene, &spec);
        }
    }
    assert!(
        tally.interesting >= tally.compared / 2 && tally.compared >= setup.seeds as usize,
        "{name}: too few cases with what the family is about: {tally:?}"
    );
    eprintln!("{name}: {tally:?}");
    tally
}

/// A random orthographic view along an axis (its index), with an up direction across it: its
/// frame has exact zeros along the axis, so a translation along it leaves every exact picture
/// unchanged.
pub fn along_an_axis(rng: &mut SplitMix64) -> (usize, ViewSpec) {
    let axis = rng.below(3);
    let mut direction = Vector3::zeros();
    direction[axis] = if rng.below(2) == 0 { 1.0 } else { -2.0 };
    let mut up = small_vector(rng);
    up[axis] = 0.0;
    if up == Vector3::zeros() {
        up[(axis + 1) % 3] = 1.0;
    }
    (axis, ViewSpec::Orthographic { direction, up })
}
