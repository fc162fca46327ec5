//! The per-object bounds report behind `kepler bounds`: counts, topology, volumes, the three
//! bounds and how tightly they fit.

use super::{ObjectId, Scene};
use crate::bounds::{Aabb, InboxMethod};
use crate::geometry::exact::ldexp;
use crate::geometry::kernel::Exponents;
use rayon::prelude::*;
use serde::Serialize;

/// A box as `{"min": [x, y, z], "max": [x, y, z], "volume", "surface_area"}`.
///
/// ```
/// use kepler::scene::report::BoxReport;
/// let b = BoxReport::from(&kepler::geometry::Aabb::new([0.0; 3].into(), [1.0; 3].into()));
/// assert_eq!(
///     serde_json::to_string(&b).unwrap(),
///     r#"{"min":[0.0,0.0,0.0],"max":[1.0,1.0,1.0],"volume":1.0,"surface_area":6.0}"#
/// );
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoxReport {
    /// Low corner.
    pub min: [f64; 3],
    /// High corner.
    pub max: [f64; 3],
    /// Volume.
    pub volume: f64,
    /// Surface area.
    pub surface_area: f64,
}

impl From<&Aabb> for BoxReport {
    fn from(b: &Aabb) -> Self {
        BoxReport {
            min: b.min,
            max: b.max,
            volume: b.volume(),
            surface_area: b.surface_area(),
        }
    }
}

/// The tribox of an object: its 18 bounds and its boundary's size.
///
/// ```
/// let s = kepler::scene::file::load("scenes/cube.toml".as_ref()).unwrap();
/// let r = kepler::scene::report::BoundsReport::of(&s);
/// assert_eq!(r.objects[0].tribox.faces, 6);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TriboxReport {
    /// Min then max along x, y, z, x+y, x+z, y+z, x−z, y−x, z−y (the paper's order).
    pub bounds: Vec<f64>,
    /// Faces of the boundary after removing zero-area faces (at most 18).
    pub faces: usize,
    /// Volume enclosed by the tribox.
    pub volume: f64,
    /// Surface area of the tribox.
    pub surface_area: f64,
}

/// One object's line of the report. Volumes of objects that do not bound a solid are `None`.
///
/// ```
/// let s = kepler::scene::file::load("scenes/cube.toml".as_ref()).unwrap();
/// let o = &kepler::scene::report::BoundsReport::of(&s).objects[0];
/// assert_eq!((o.faces, o.vertices, o.closed), (6, 8, true));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObjectReport {
    /// The object's name.
    pub name: String,
    /// Its path of names from the top level, joined by `/`.
    pub path: String,
    /// Depth in the hierarchy (0 for a top-level object).
    pub depth: usize,
    /// Faces in the subtree.
    pub faces: usize,
    /// Vertices in the subtree.
    pub vertices: usize,
    /// Every mesh of the subtree is closed and consistently oriented.
    pub closed: bool,
    /// Some mesh is closed but turned inside out (its faces point inward).
    pub inside_out: bool,
    /// Enclosed volume.
    pub volume: Option<f64>,
    /// Total face area.
    pub surface_area: f64,
    /// The circumscribing box.
    pub cbox: BoxReport,
    /// The inscribing box, or `None` (no interior).
    pub inbox: Option<BoxReport>,
    /// How the inbox was found.
    pub inbox_method: Option<InboxMethod>,
    /// The tribox.
    pub tribox: TriboxReport,
    /// Inbox volume / object volume.
    pub inbox_ratio: Option<f64>,
    /// Object volume / tribox volume.
    pub tribox_ratio: Option<f64>,
    /// Object volume / CBOX volume.
    pub cbox_ratio: Option<f64>,
}

/// The report for every object of a scene, depth-first: `{"objects": [...]}` in JSON.
///
/// ```
/// let s = kepler::scene::file::load("scenes/cube.toml".as_ref()).unwrap();
/// let json = serde_json::to_value(kepler::scene::report::BoundsReport::of(&s)).unwrap();
/// assert_eq!(json["objects"][0]["inbox"]["max"][0], 0.5);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoundsReport {
    /// One entry per object, in depth-first order.
    pub objects: Vec<ObjectReport>,
}

impl BoundsReport {
    /// Computes the bounds of every object (the leaves' inboxes in parallel) and reports them.
    ///
    /// ```
    /// let s = kepler::scene::file::load("scenes/cube.toml".as_ref()).unwrap();
    /// assert_eq!(kepler::scene::report::BoundsReport::of(&s).objects.len(), 1);
    /// ```
    pub fn of(scene: &Scene) -> BoundsReport {
        // An object of extreme coordinates is measured brought into the kernel's working range
        // by a power of two (volumes and areas of huge or tiny objects neither overflow nor
        // underflow there, and the tribox's corners are classified exactly), then scaled back:
        // each object by the power of two its own subtree needs, one copy of the scene per
        // power with those subtrees scaled.
        let walk = scene.walk();
        let shifts: Vec<i32> = walk
            .iter()
            .map(|&(id, _)| {
                let vertices = scene.meshes(id).into_iter().flat_map(|m| m.vertices());
                vertices
                    .fold(Exponents::NONE, |e, p| {
                        e.union(Exponents::of(p.coords.as_slice()))
                    })
                    .shift()
            })
            .collect();
        let mut distinct: Vec<i32> = shifts.clone();
        distinct.sort_unstable();
        distinct.dedup();
        let mut objects: Vec<Option<ObjectReport>> = vec![None; walk.len()];
        for wanted in distinct {
            // (Where the scaled scene is not valid, the objects are measured as they are.)
            let scaled = match wanted {
                0 => None,
                _ => {
                    let roots: Vec<ObjectId> = (0..walk.len())
                        .filter(|&k| shifts[k] == wanted)
                        .map(|k| walk[k].0)
                        .collect();
                    scene.scaled_subtrees(wanted, &roots).ok()
                }
            };
            let (at, shift) = match &scaled {
                Some(s) => (s, wanted),
                None => (scene, 0),
            };
            at.compute_bounds();
            let reports: Vec<(usize, ObjectReport)> = walk
                .par_iter()
                .enumerate()
                .filter(|(k, _)| shifts[*k] == wanted)
                .map(|(k, &(id, depth))| {
                    let mut o = object_report(at, id, depth);
                    o.scale_back(shift);
                    (k, o)
                })
                .collect();
            for (k, o) in reports {
                objects[k] = Some(o);
            }
        }
        BoundsReport {
            objects: objects.into_iter().flatten().collect(),
        }
    }

    /// The report as an aligned text table, one line per object, names indented by depth.
    ///
    /// ```
    /// let s = kepler::scene::file::load("scenes/cube.toml".as_ref()).unwrap();
    /// let t = kepler::scene::report::BoundsReport::of(&s).table();
    /// assert!(t.lines().next().unwrap().starts_with("object"));
    /// ```
    pub fn table(&self) -> String {
        let fmt_box = |b: &BoxReport| {
            format!(
                "[{} {} {}]..[{} {} {}]",
                short(b.min[0]),
                short(b.min[1]),
                short(b.min[2]),
                short(b.max[0]),
                short(b.max[1]),
                short(b.max[2])
            )
        };
        let ratio = |r: Option<f64>| r.map_or("-".to_string(), |r| format!("{r:.3}"));
        let mut rows = vec![
            [
                "object",
                "faces",
                "vertices",
                "solid",
                "cbox",
                "inbox",
                "tribox faces",
                "inbox/object",
                "object/tribox",
                "object/cbox",
            ]
            .map(String::from),
        ];
        for o in &self.objects {
            rows.push([
                format!("{}{}", "  ".repeat(o.depth), o.name),
                o.faces.to_string(),
                o.vertices.to_string(),
                if !o.closed {
                    "open".into()
                } else if o.inside_out {
                    "inside-out".into()
                } else {
                    "yes".into()
                },
                fmt_box(&o.cbox),
                o.inbox.as_ref().map_or("empty".into(), fmt_box),
                o.tribox.faces.to_string(),
                ratio(o.inbox_ratio),
                ratio(o.tribox_ratio),
                ratio(o.cbox_ratio),
            ]);
        }
        let widths: Vec<usize> = (0..10)
            .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
            .collect();
        let mut out = String::new();
        for r in &rows {
            let line: Vec<String> = r
                .iter()
                .zip(&widths)
                .enumerate()
                .map(|(c, (cell, w))| {
                    if c == 0 || c == 3 || c == 4 || c == 5 {
                        format!("{cell:<w$}")
                    } else {
                        format!("{cell:>w$}")
                    }
                })
                .collect();
            out.push_str(line.join("  ").trim_end());
            out.push('\n');
        }
        out
    }
}

impl ObjectReport {
    /// The report of the object scaled by `2^shift`, brought back to the object's scale:
    /// lengths scaled by `2^-shift`, areas and volumes by its square and cube (infinite where
    /// the true value exceeds the doubles), ratios as they are. A coordinate that does not
    /// scale back exactly (below the normal range) is rounded outward for the CBOX and the
    /// tribox and inward for the INBOX, so each bound still holds.
    fn scale_back(&mut self, shift: i32) {
        if shift == 0 {
            return;
        }
        let length = |x: f64| ldexp(x, -shift);
        let area = |x: f64| ldexp(x, -2 * shift);
        let volume = |x: f64| ldexp(x, -3 * shift);
        // `outward`: towards -inf for a low bound (`low`), +inf for a high one.
        let bound = |x: f64, low: bool, outward: bool| {
            let y = length(x);
            let back = ldexp(y, shift);
            match (low == outward, back.partial_cmp(&x)) {
                (true, Some(std::cmp::Ordering::Greater)) => y.next_down(),
                (false, Some(std::cmp::Ordering::Less)) => y.next_up(),
                _ => y,
            }
        };
        let boxed = |b: &mut BoxReport, outward: bool| {
            b.min = b.min.map(|x| bound(x, true, outward));
            b.max = b.max.map(|x| bound(x, false, outward));
            b.volume = volume(b.volume);
            b.surface_area = area(b.surface_area);
        };
        boxed(&mut self.cbox, true);
        if let Some(inbox) = &mut self.inbox {
            boxed(inbox, false);
            if (0..3).any(|k| inbox.min[k] > inbox.max[k]) {
                self.inbox = None;
                self.inbox_method = None;
                self.inbox_ratio = None;
            }
        }
        // Min then max of each direction.
        for (k, b) in self.tribox.bounds.iter_mut().enumerate() {
            *b = bound(*b, k % 2 == 0, true);
        }
        self.tribox.volume = volume(self.tribox.volume);
        self.tribox.surface_area = area(self.tribox.surface_area);
        self.volume = self.volume.map(volume);
        self.surface_area = area(self.surface_area);
    }
}

/// A compact rendering of a coordinate for the table (JSON keeps full precision): four
/// decimals, or five significant digits with an exponent for magnitudes from 10⁷ up or below
/// 10⁻⁴ (so neither a 151-digit integer nor a row of zeros).
///
/// ```text
/// 0.5 → 0.5, -0 → 0, 1e150 → 1e150, 2^-1070 → 7.9050e-323 → 7.905e-323
/// ```
fn short(x: f64) -> String {
    let trimmed = |s: &str| s.trim_end_matches('0').trim_end_matches('.').to_string();
    if x != 0.0 && (x.abs() >= 1e7 || x.abs() < 1e-4) {
        let s = format!("{x:.4e}");
        return match s.split_once('e') {
            Some((mantissa, exponent)) => format!("{}e{exponent}", trimmed(mantissa)),
            None => s,
        };
    }
    let s = trimmed(&format!("{x:.4}"));
    if s == "-0" { "0".into() } else { s }
}

fn object_report(scene: &Scene, id: ObjectId, depth: usize) -> ObjectReport {
    let o = &scene[id];
    let volume = scene.volume(id);
    let cbox = scene.cbox(id);
    let inbox = scene.inbox(id);
    let bounds = scene.tribox(id);
    let boundary = bounds.boundary().cleaned();
    let tribox = TriboxReport {
        bounds: bounds.to_array18().to_vec(),
        faces: boundary.face_count(),
        volume: boundary.volume(),
        surface_area: boundary.surface_area(),
    };
    let over = |num: Option<f64>, den: f64| match num {
        Some(n) if den > 0.0 => Some(n / den),
        _ => None,
    };
    ObjectReport {
        name: o.name().to_string(),
        path: scene.path(id),
        depth,
        faces: scene.face_count(id),
        vertices: scene.vertex_count(id),
        closed: scene.is_solid(id),
        inside_out: scene
            .meshes(id)
            .iter()
            .any(|m| m.is_solid() && m.volume() < 0.0),
        volume,
        surface_area: scene.surface_area(id),
        cbox: BoxReport::from(&cbox),
        inbox: inbox.as_ref().map(|i| BoxReport::from(&i.aabb)),
        inbox_method: inbox.map(|i| i.method),
        inbox_ratio: volume.and_then(|v| over(inbox.map(|i| i.aabb.volume()), v)),
        tribox_ratio: over(volume, tribox.volume),
        cbox_ratio: over(volume, cbox.volume()),
        tribox,
    }
}
