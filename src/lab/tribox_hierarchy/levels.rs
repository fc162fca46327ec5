//! The report of one level of detail: the union of the triboxes of a cut through the tree.

use super::{Hierarchy, hausdorff};
use crate::bounds::tribox::{Tribox, TriboxBounds};
use crate::clip::{self, ClipError};
use crate::geometry::Vector3;
use geo::{Area, LineString, MultiPolygon, Polygon};
use serde::Serialize;

/// One level of detail, compared with the object (the paper's Table 1 and more).
///
/// ```
/// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
/// let h = Hierarchy::build(&kepler::solids::cube(1.0).unwrap(), &HierarchyOptions::default()).unwrap();
/// let l = &h.levels(1)[0];
/// assert_eq!((l.depth, l.triboxes, l.faces, l.compression), (0, 1, 6, 1.0));
/// assert_eq!((l.volume_excess, l.area_excess), (0.0, 0.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Level {
    /// The depth of the cut.
    pub depth: usize,
    /// The number of triboxes.
    pub triboxes: usize,
    /// Their total number of faces, the paper's M.
    pub faces: usize,
    /// The paper's compression τ = N / M, with N the object's number of faces.
    pub compression: f64,
    /// The triboxes' total volume (their interiors are disjoint).
    pub volume: f64,
    /// `volume / object's volume − 1`.
    pub volume_excess: f64,
    /// The area of the boundary of the triboxes' union (faces shared by two triboxes are not
    /// boundary).
    pub area: f64,
    /// `area / object's area − 1` (may be negative: a bound can have less area than a
    /// bumpy object).
    pub area_excess: f64,
    /// An upper bound on the Hausdorff distance from the union to the object.
    pub hausdorff: f64,
    /// A lower bound on the same distance (the exact value is between the two).
    pub hausdorff_lower: f64,
    /// Whether the level was split from the one above although no split lowered a cell's
    /// tribox area by the gain, because [`levels`](super::HierarchyOptions::levels) asked for
    /// it (left out of JSON when false).
    ///
    /// ```
    /// use kepler::lab::tribox_hierarchy::{Hierarchy, HierarchyOptions};
    /// let cube = kepler::solids::cube(1.0).unwrap();
    /// let o = HierarchyOptions { levels: Some(2), ..HierarchyOptions::default() };
    /// let levels = Hierarchy::build(&cube, &o).unwrap().levels(2);
    /// assert_eq!((levels[0].below_gain, levels[1].below_gain), (false, true));
    /// assert_eq!((levels[1].triboxes, levels[1].volume_excess), (2, 0.0));
    /// ```
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub below_gain: bool,
}

/// The report of the cut at `depth`.
pub(crate) fn level(h: &Hierarchy, depth: usize) -> Level {
    let cut = h.cut(depth);
    let triboxes: Vec<TriboxBounds> = cut.iter().map(|&i| h.nodes()[i].tribox).collect();
    let faces: usize = cut.iter().map(|&i| h.nodes()[i].faces).sum();
    let volume: f64 = cut.iter().map(|&i| h.nodes()[i].volume).sum();
    // Tribox vertices are within MAX_COORDINATE-sized values, far inside the clipping range.
    let area = union_area(&triboxes).expect("tribox faces of a mesh are within clipping range");
    let distance = hausdorff(&triboxes, &h.tree, h.tolerance);
    Level {
        depth,
        triboxes: cut.len(),
        faces,
        compression: h.object_faces as f64 / faces as f64,
        volume,
        volume_excess: volume / h.object_volume - 1.0,
        area,
        area_excess: area / h.object_area - 1.0,
        hausdorff: distance.upper,
        hausdorff_lower: distance.lower,
        below_gain: h.below_gain.contains(&depth),
    }
}

/// The boundary area of the union of triboxes with disjoint interiors: their areas, less
/// twice the overlap of every pair of faces on one plane (one tribox's maximum along a
/// direction equal to the other's minimum), each overlap clipped in the plane.
///
/// ```
/// use kepler::bounds::tribox::TriboxBounds;
/// use kepler::geometry::Point3;
/// use kepler::lab::tribox_hierarchy::union_area;
/// let cube = |x: f64, y: f64| TriboxBounds::from_points(&[
///     Point3::new(x, y, 0.0), Point3::new(x + 1.0, y + 1.0, 1.0),
///     Point3::new(x + 1.0, y, 0.0), Point3::new(x, y + 1.0, 1.0),
///     Point3::new(x, y, 1.0), Point3::new(x + 1.0, y + 1.0, 0.0),
///     Point3::new(x + 1.0, y, 1.0), Point3::new(x, y + 1.0, 0.0)]);
/// assert_eq!(union_area(&[cube(0.0, 0.0), cube(1.0, 0.0)])?, 10.0);
/// assert_eq!(union_area(&[cube(0.0, 0.0), cube(1.0, 0.5)])?, 11.0);
/// # Ok::<(), kepler::clip::ClipError>(())
/// ```
pub fn union_area(triboxes: &[TriboxBounds]) -> Result<f64, ClipError> {
    let boundaries: Vec<Tribox> = triboxes.iter().map(|t| Tribox::new(t).cleaned()).collect();
    let mut area: f64 = boundaries.iter().map(Tribox::surface_area).sum();
    for (i, a) in triboxes.iter().enumerate() {
        for (j, b) in triboxes.iter().enumerate() {
            if i == j || a.is_empty() || b.is_empty() {
                continue;
            }
            for d in 0..9 {
                if a.max()[d] == b.min()[d] && a.min()[d] <= b.max()[d] {
                    area -= 2.0 * shared_area(&boundaries[i], 2 * d + 1, &boundaries[j], 2 * d)?;
                }
            }
        }
    }
    Ok(area)
}

/// The area of the overlap of face `fa` of `a` and face `fb` of `b`, on one plane.
fn shared_area(a: &Tribox, fa: usize, b: &Tribox, fb: usize) -> Result<f64, ClipError> {
    let n = TriboxBounds::DIRECTIONS[fa / 2];
    // Drop the first axis the direction has: the other two are coordinates in the plane,
    // and areas scale by |n| / |n_k| = |n|.
    let k = (0..3).find(|&k| n[k] != 0.0).unwrap_or(0);
    let (u, v) = ((k + 1) % 3, (k + 2) % 3);
    let polygon = |t: &Tribox, f: usize| -> MultiPolygon<f64> {
        let ring: Vec<(f64, f64)> = t
            .face(f)
            .iter()
            .map(|&i| {
                let p = t.vertices()[i as usize];
                (p[u], p[v])
            })
            .collect();
        if ring.len() < 3 {
            MultiPolygon::new(vec![])
        } else {
            Polygon::new(LineString::from(ring), vec![]).into()
        }
    };
    let overlap = clip::intersection(&polygon(a, fa), &polygon(b, fb))?;
    Ok(overlap.unsigned_area() * Vector3::from(n).norm())
}
