//! The variants of the visibility pipeline that the report compares: the exact engine, the
//! same engine under cheaper arithmetic, and two ways of deciding visibility by samples.
//!
//! The arithmetic variants ([`Variant::Float`], [`Variant::Tolerance`], [`Variant::Single`])
//! run the engine's own [`draw`] with the kernel's [`Arithmetic`] switched: every algorithm,
//! every data structure and every line is the same, only the signs and the constructed points
//! differ. The sampled variants decide visibility the way approximate plotters do, on exactly
//! the lines the engine draws ([`strokes`]):
//!
//! - [`Variant::Sampled`]: like the `ln` family, each line is sampled every `h` in the picture
//!   and each sample decided by a point query (the engine's exact VISP, so the only error is
//!   where the samples fall); visibility changes half way between two samples that disagree.
//! - [`Variant::Raster`]: a z-buffer of `N × N` cells over the picture, each scene triangle
//!   drawn into it at cell centres, and each line sampled once per cell and drawn where it is no
//!   deeper than the buffer plus a depth bias, as a GPU line renderer does.
//!
//! These two are written here rather than taken from a crate: they are the alternatives being
//! measured, and they must run on the engine's own lines and views to be comparable.

use crate::Error;
use crate::geometry::Point3;
use crate::geometry::kernel::{Arithmetic, with_arithmetic};
use crate::hidden::{Drawing, Options, Polyline, Stroke, draw, strokes};
use crate::mesh::Mesh;
use crate::queries::visp::{Visibility, VisibilityIndex};
use crate::scene::Scene;
use crate::views::{Eye, Picture, View};
use nalgebra::Vector3;

/// One way of deciding what is visible.
///
/// ```
/// use kepler::lab::report::variants::Variant;
/// assert_eq!(Variant::Tolerance(1e-9).name(), "epsilon 1e-9");
/// assert_eq!(Variant::Raster(512).kind(), "raster");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Variant {
    /// The engine: exact signs, points rounded once from exact values.
    Exact,
    /// The engine with plain `f64` signs and points ([`Arithmetic::Float`]).
    Float,
    /// The engine with `f64` and a relative tolerance ([`Arithmetic::Tolerance`]).
    Tolerance(f64),
    /// The scene and view rounded to `f32`, points built in `f32` ([`Arithmetic::Single`]).
    Single,
    /// Each line sampled this many times per picture diagonal, each sample decided by VISP.
    Sampled(u32),
    /// A z-buffer of this many cells a side.
    Raster(u32),
}

impl Variant {
    /// The variants a report runs: the exact engine, plain floats, three tolerances, `f32`,
    /// and the sampled and raster variants at two resolutions (three in the full report).
    ///
    /// ```
    /// use kepler::lab::report::variants::Variant;
    /// assert_eq!(Variant::all(true)[0], Variant::Exact);
    /// assert!(Variant::all(false).len() > Variant::all(true).len());
    /// ```
    pub fn all(quick: bool) -> Vec<Variant> {
        let mut all = vec![
            Variant::Exact,
            Variant::Float,
            Variant::Tolerance(1e-12),
            Variant::Tolerance(1e-9),
            Variant::Tolerance(1e-6),
            Variant::Single,
        ];
        let resolutions: &[u32] = if quick {
            &[256, 2048]
        } else {
            &[256, 1024, 2048]
        };
        all.extend(resolutions.iter().map(|&n| Variant::Sampled(n)));
        all.extend(resolutions.iter().map(|&n| Variant::Raster(n)));
        all
    }

    /// The variant's kind: `exact`, `float`, `epsilon`, `f32`, `sampled` or `raster`.
    pub fn kind(&self) -> &'static str {
        match self {
            Variant::Exact => "exact",
            Variant::Float => "float",
            Variant::Tolerance(_) => "epsilon",
            Variant::Single => "f32",
            Variant::Sampled(_) => "sampled",
            Variant::Raster(_) => "raster",
        }
    }

    /// The variant with its parameter, e.g. `epsilon 1e-9`, `raster 1024`.
    pub fn name(&self) -> String {
        match self {
            Variant::Tolerance(e) => format!("epsilon {e:e}"),
            Variant::Sampled(n) | Variant::Raster(n) => format!("{} {n}", self.kind()),
            _ => self.kind().to_string(),
        }
    }

    /// Draws the scene from the view this way, with every hidden piece kept.
    ///
    /// ```
    /// use kepler::{geometry::Vector3, scene::Scene, views::View, hidden::Options};
    /// use kepler::lab::report::variants::Variant;
    /// let mut scene = Scene::new();
    /// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
    /// let creases = |v: Variant| {
    ///     let d = v.draw(&scene, &view, &Options::default()).unwrap();
    ///     d.length(kepler::hidden::EdgeClass::Crease, true)
    /// };
    /// // A cube in a general view: the arithmetic and sampled variants draw its three visible
    /// // creases whole; the z-buffer loses a little of them near the corners.
    /// let exact = creases(Variant::Exact);
    /// for v in [Variant::Float, Variant::Tolerance(1e-9), Variant::Sampled(256)] {
    ///     assert!((creases(v) - exact).abs() < 1e-6, "{}", v.name());
    /// }
    /// assert!((creases(Variant::Single) - exact).abs() < 1e-6 * exact);
    /// assert!((creases(Variant::Raster(256)) - exact).abs() < 0.05 * exact);
    /// ```
    pub fn draw(&self, scene: &Scene, view: &View, options: &Options) -> Result<Drawing, Error> {
        let options = Options {
            hidden: true,
            ..*options
        };
        match *self {
            Variant::Exact => Ok(with_arithmetic(Arithmetic::Exact, || {
                draw(scene, view, &options)
            })?),
            Variant::Float => Ok(with_arithmetic(Arithmetic::Float, || {
                draw(scene, view, &options)
            })?),
            Variant::Tolerance(e) => Ok(with_arithmetic(Arithmetic::Tolerance(e), || {
                draw(scene, view, &options)
            })?),
            Variant::Single => {
                let (scene, view) = (single_scene(scene)?, single_view(view)?);
                Ok(with_arithmetic(Arithmetic::Single, || {
                    draw(&scene, &view, &options)
                })?)
            }
            Variant::Sampled(n) => with_arithmetic(Arithmetic::Exact, || {
                let lines = strokes(scene, view, &options)?;
                let index = VisibilityIndex::whole_scene(scene, view.clone());
                let nudge = NUDGE * extent(&lines);
                Ok(sampled(&lines, view, n, |p| {
                    let towards = match view.eye() {
                        Eye::Point(eye) => (eye - p).normalize(),
                        Eye::Infinity(v) => v.normalize(),
                    };
                    index.visp(&(p + towards * nudge)).0 == Visibility::Visible
                }))
            }),
            Variant::Raster(n) => with_arithmetic(Arithmetic::Exact, || {
                let lines = strokes(scene, view, &options)?;
                let buffer = DepthBuffer::of(scene, view, &lines, n);
                Ok(sampled(&lines, view, n, |p| buffer.shows(p)))
            }),
        }
    }
}

/// The scene with every coordinate rounded to `f32` (one object per mesh; a face that
/// rounding collapses is dropped as the engine drops degenerate faces).
fn single_scene(scene: &Scene) -> Result<Scene, Error> {
    let mut rounded = Scene::new();
    for (id, mesh) in scene.mesh_objects(scene.roots()) {
        let vertices = mesh.vertices().iter().map(|p| p.map(single)).collect();
        let mesh = Mesh::from_polygons(vertices, mesh.polygons())?;
        rounded.add_mesh(None, scene.path(id), mesh)?;
    }
    Ok(rounded)
}

/// The view with its eye, direction and up rounded to `f32`.
fn single_view(view: &View) -> Result<View, Error> {
    let round = |v: Vector3<f64>| v.map(single);
    let (_, up) = view.right_up();
    Ok(match (view.eye(), view.fov()) {
        (Eye::Point(eye), Some(fov)) => {
            let eye = eye.map(single);
            View::perspective(eye, eye + round(view.forward()), round(up), fov)?
        }
        _ => View::orthographic(round(view.forward()), round(up))?,
    })
}

/// How far a sample is moved towards the eye before its point query, relative to the size of
/// the scene: `ln` ignores hits closer than `1e-9` along its rays, so that a point on an edge is
/// not hidden by its own faces, which rounding puts a little in front of it half of the time.
const NUDGE: f64 = 1e-9;

/// The diagonal of the box of the lines' ends.
fn extent(lines: &[Stroke]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in lines.iter().flat_map(|l| l.ends) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let d = Vector3::from(hi) - Vector3::from(lo);
    if d.norm().is_finite() { d.norm() } else { 0.0 }
}

/// `x` rounded to the nearest `f32` and back.
fn single(x: f64) -> f64 {
    f64::from(x as f32)
}

/// The drawing of `lines` with each line sampled `n` times per picture diagonal, each sample
/// decided by `shows`; visibility changes half way between samples that disagree. Samples
/// not strictly in front of a perspective eye are left out.
fn sampled(lines: &[Stroke], view: &View, n: u32, shows: impl Fn(&Point3) -> bool) -> Drawing {
    let picture = Picture::of(view);
    let step = diagonal(lines, &picture) / f64::from(n.max(1));
    let mut polylines = Vec::new();
    for line in lines {
        let [a, b] = line.ends;
        let at = |t: f64| Point3::from(a.coords * (1.0 - t) + b.coords * t);
        let length = {
            let (p, q) = (picture.point(&a), picture.point(&b));
            (q[0] - p[0]).hypot(q[1] - p[1])
        };
        let count = if length.is_finite() && step > 0.0 {
            (length / step).ceil().clamp(1.0, 1e6) as usize
        } else {
            1
        };
        let mut run: Option<(bool, f64)> = None;
        let close = |run: (bool, f64), end: f64, polylines: &mut Vec<Polyline>| {
            let (p, q) = (at(run.1), at(end));
            if picture.in_front(&p) && picture.in_front(&q) {
                polylines.push(Polyline {
                    class: line.class,
                    visible: run.0,
                    points: vec![picture.point(&p), picture.point(&q)],
                });
            }
        };
        for i in 0..count {
            let t = (i as f64 + 0.5) / count as f64;
            let p = at(t);
            let state = picture.in_front(&p).then(|| shows(&p));
            let start = i as f64 / count as f64;
            match (run, state) {
                (Some((v, _)), Some(w)) if v == w => {}
                (Some(r), _) => {
                    close(r, start, &mut polylines);
                    run = state.map(|w| (w, start));
                }
                (None, _) => run = state.map(|w| (w, start)),
            }
        }
        if let Some(r) = run {
            close(r, 1.0, &mut polylines);
        }
    }
    Drawing {
        polylines,
        stages: Vec::new(),
    }
}

/// The diagonal of the box of the lines' pictures (ends in front of the eye).
fn diagonal(lines: &[Stroke], picture: &Picture) -> f64 {
    let (lo, hi) = picture_box(lines, picture);
    let d = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    if d.is_finite() { d } else { 0.0 }
}

/// The box of the lines' end pictures (in front of the eye).
fn picture_box(lines: &[Stroke], picture: &Picture) -> ([f64; 2], [f64; 2]) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in lines.iter().flat_map(|l| l.ends) {
        if picture.in_front(&p) {
            let q = picture.point(&p);
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
    }
    (lo, hi)
}

/// A z-buffer over the picture: for each cell, the nearness of the nearest triangle over its
/// centre (larger is nearer: minus the depth for an orthographic view, its reciprocal for a
/// perspective one, both affine in the picture over a triangle).
struct DepthBuffer {
    picture: Picture,
    forward: Vector3<f64>,
    eye: Option<Point3>,
    origin: [f64; 2],
    cell: f64,
    size: usize,
    nearness: Vec<f64>,
    /// For each cell, how much the nearest triangle's nearness changes across a cell: the
    /// slope-scaled part of the depth bias (as `glPolygonOffset` adds), since a line's sample
    /// and the cell's centre are up to a cell apart.
    slope: Vec<f64>,
    bias: f64,
}

impl DepthBuffer {
    /// The buffer of `size × size` cells over the lines' pictures, every triangle of the
    /// scene in front of the eye drawn into it.
    fn of(scene: &Scene, view: &View, lines: &[Stroke], size: u32) -> DepthBuffer {
        let picture = Picture::of(view);
        let (lo, hi) = picture_box(lines, &picture);
        let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let size = size.max(1) as usize;
        let cell = if side.is_finite() && side > 0.0 {
            side / size as f64
        } else {
            1.0
        };
        let mut buffer = DepthBuffer {
            picture,
            forward: view.forward(),
            eye: match view.eye() {
                Eye::Point(p) => Some(*p),
                Eye::Infinity(_) => None,
            },
            origin: if lo[0].is_finite() { lo } else { [0.0; 2] },
            cell,
            size,
            nearness: vec![f64::NEG_INFINITY; size * size],
            slope: vec![0.0; size * size],
            bias: 0.0,
        };
        let (mut least, mut most) = (f64::INFINITY, f64::NEG_INFINITY);
        for (_, mesh) in scene.mesh_objects(scene.roots()) {
            for t in 0..mesh.triangles().len() {
                let corners = mesh.triangle(t);
                if corners.iter().all(|p| buffer.picture.in_front(p)) {
                    for p in &corners {
                        let z = buffer.nearness_of(p);
                        least = least.min(z);
                        most = most.max(z);
                    }
                    buffer.fill(&corners);
                }
            }
        }
        // A 16-bit depth resolution over the scene's range, as a depth bias.
        buffer.bias = if most > least {
            (most - least) / 65536.0
        } else {
            0.0
        };
        buffer
    }

    /// The nearness of `p`.
    fn nearness_of(&self, p: &Point3) -> f64 {
        match self.eye {
            Some(eye) => 1.0 / (p - eye).dot(&self.forward),
            None => -p.coords.dot(&self.forward),
        }
    }

    /// The cell holding the picture point `q`, if any.
    fn cell_of(&self, q: [f64; 2]) -> Option<usize> {
        let i = ((q[0] - self.origin[0]) / self.cell).floor();
        let j = ((q[1] - self.origin[1]) / self.cell).floor();
        let n = self.size as f64;
        // The far edge of the box belongs to the last cell.
        let (i, j) = (i.min(n - 1.0), j.min(n - 1.0));
        (i >= 0.0 && j >= 0.0).then(|| j as usize * self.size + i as usize)
    }

    /// Draws a triangle: every cell whose centre lies in its picture keeps the larger
    /// nearness.
    fn fill(&mut self, corners: &[Point3; 3]) {
        let q = corners.map(|p| self.picture.point(&p));
        let z = corners.map(|p| self.nearness_of(&p));
        let area =
            (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[2][0] - q[0][0]) * (q[1][1] - q[0][1]);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        // The cells whose centres lie in the triangle's box.
        let range = |k: usize| {
            let lo = q.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let hi = q.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
            let first = ((lo - self.origin[k]) / self.cell - 0.5).ceil().max(0.0);
            let last = ((hi - self.origin[k]) / self.cell - 0.5)
                .floor()
                .min(self.size as f64 - 1.0);
            first as usize..(last + 1.0).max(0.0) as usize
        };
        // The change of nearness across one cell, from the plane of the triangle's nearness.
        let (dz1, dz2) = (z[1] - z[0], z[2] - z[0]);
        let dx = (dz1 * (q[2][1] - q[0][1]) - dz2 * (q[1][1] - q[0][1])) / area;
        let dy = ((q[1][0] - q[0][0]) * dz2 - (q[2][0] - q[0][0]) * dz1) / area;
        let slope = (dx.abs() + dy.abs()) * self.cell;
        for j in range(1) {
            for i in range(0) {
                let c = [
                    self.origin[0] + (i as f64 + 0.5) * self.cell,
                    self.origin[1] + (j as f64 + 0.5) * self.cell,
                ];
                let w = |a: [f64; 2], b: [f64; 2]| {
                    ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / area
                };
                let (w0, w1, w2) = (w(q[1], q[2]), w(q[2], q[0]), w(q[0], q[1]));
                if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                    let near = w0 * z[0] + w1 * z[1] + w2 * z[2];
                    let cell = j * self.size + i;
                    if near > self.nearness[cell] {
                        self.nearness[cell] = near;
                        self.slope[cell] = slope;
                    }
                }
            }
        }
    }

    /// Whether the buffer shows `p`: nothing nearer than `p` by more than the bias covers its
    /// cell.
    fn shows(&self, p: &Point3) -> bool {
        match self.cell_of(self.picture.point(p)) {
            Some(cell) if cell < self.nearness.len() => {
                self.nearness_of(p) + self.bias + self.slope[cell] >= self.nearness[cell]
            }
            _ => true,
        }
    }
}
