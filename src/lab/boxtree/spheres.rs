//! The paper's collision experiment (its Table 1): pairs of concentric sphere models whose
//! surfaces nearly touch, and the number of bound-bound collision tests each node shape needs.
//!
//! "The results of collision tests for three pairs of concentric sphere-models are given in
//! Table 1(b,c,d). Each pair consists of two spheres whose surfaces are very close to each
//! other. This construction was picked in order to enforce many collision tests between
//! hierarchy objects. Each model in the first (resp. second, third) pair contains 280 (resp.
//! 1000, 5000) vertices and 556 (resp. 1996, 9996) facets." Its sphere "contains 556 facets
//! connecting 280 vertices randomly distributed on a unit sphere": the convex hull of random
//! points on a sphere, `2n − 4` triangles for `n` points. The paper states neither the gap
//! between the spheres nor how its search descends; [`sphere_experiment`] takes the gap and
//! counts the tests of a complete search ([`BoxTree::intersecting_pairs`]), which is what
//! clearing two surfaces that do not meet costs.
//!
//! ```
//! use kepler::lab::boxtree::{Merge, Shape, sphere_experiment};
//! let rows = sphere_experiment(&[556], 0.01, 1, Merge::Volume).unwrap();
//! assert_eq!(rows.len(), 5);
//! assert!(rows.iter().all(|r| r.facets == 556 && r.tests > 0));
//! assert_eq!(rows[0].shape, Shape::Aabb);
//! assert_eq!(rows[0].paper, Some(9_479));
//! ```

use super::hull::convex_hull;
use super::pca::{PcaAll, PcaMax, PcaMin};
use super::{BoxTree, Merge, NodeShape, Shape};
use crate::bounds::tribox::TriboxBounds;
use crate::geometry::{Aabb, Point3};
use crate::mesh::Mesh;
use crate::random::SplitMix64;
use crate::solids::{MAX_FACES, SolidError};
use serde::Serialize;

/// The facet counts of the paper's three sphere pairs.
///
/// ```
/// assert_eq!(kepler::lab::boxtree::spheres::PAPER_FACETS, [556, 1996, 9996]);
/// ```
pub const PAPER_FACETS: [usize; 3] = [556, 1996, 9996];

/// The gap used when none is asked for: the paper says only that the surfaces are "very
/// close to each other", and 0.05 is the smallest gap (in steps of 0.01) at which none of the
/// three pairs of seed 1 meet, so that a collision search must clear every candidate pair. (At
/// 0.01 the 556- and 1,996-facet pairs cross each other: random hulls' facets dip inside the
/// sphere by about the square of their size.)
///
/// ```
/// use kepler::lab::boxtree::{Merge, spheres::DEFAULT_GAP, sphere_experiment};
/// let rows = sphere_experiment(&[556], DEFAULT_GAP, 1, Merge::Volume).unwrap();
/// assert!(rows.iter().all(|r| r.intersecting_pairs == 0));
/// ```
pub const DEFAULT_GAP: f64 = 0.05;

/// One row of the experiment: a pair of spheres, a node shape, and the work of the search.
///
/// ```
/// use kepler::lab::boxtree::{Row, Shape};
/// let r = Row { facets: 556, shape: Shape::PcaMin, tests: 7000, triangle_tests: 300,
///     intersecting_pairs: 0, paper: Some(7_721) };
/// assert_eq!(serde_json::to_value(&r).unwrap()["shape"], "pca-min");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Row {
    /// Triangles of each sphere.
    pub facets: usize,
    /// The node shape of both hierarchies.
    pub shape: Shape,
    /// Bound-bound collision tests.
    pub tests: u64,
    /// Triangle-triangle tests.
    pub triangle_tests: u64,
    /// Pairs of triangles that meet (0 when the spheres' surfaces are apart).
    pub intersecting_pairs: usize,
    /// The paper's count for this row (Table 1, and its text for 1,996 facets), if it has one.
    pub paper: Option<u64>,
}

/// The paper's number of collision tests for `facets` and `shape`, from Table 1 and the text
/// ("the axis-aligned box strategy performed 35749 collision tests, the
/// all-principal-component box strategy – 30039 tests, the maximum-principal-component box
/// strategy – 33679, the minimum-principal-component box strategy – 22627"); `None` for the
/// tribox and for rows the paper does not give.
///
/// ```
/// use kepler::lab::boxtree::{Shape, paper_tests};
/// assert_eq!(paper_tests(1996, Shape::PcaMin), Some(22_627));
/// assert_eq!(paper_tests(9996, Shape::PcaMax), None);
/// assert_eq!(paper_tests(556, Shape::Tribox), None);
/// ```
pub fn paper_tests(facets: usize, shape: Shape) -> Option<u64> {
    match (facets, shape) {
        (556, Shape::Aabb) => Some(9_479),
        (556, Shape::PcaMin) => Some(7_721),
        (1996, Shape::Aabb) => Some(35_749),
        (1996, Shape::PcaAll) => Some(30_039),
        (1996, Shape::PcaMax) => Some(33_679),
        (1996, Shape::PcaMin) => Some(22_627),
        (9996, Shape::Aabb) => Some(77_841),
        (9996, Shape::PcaMin) => Some(37_937),
        _ => None,
    }
}

/// The paper's counts for its min-principal-component pie slices (Table 1), which kepler does
/// not build, by facets: for comparison only.
///
/// ```
/// assert_eq!(kepler::lab::boxtree::spheres::paper_pie_slice_tests(1996), Some(6_179));
/// ```
pub fn paper_pie_slice_tests(facets: usize) -> Option<u64> {
    match facets {
        556 => Some(3_849),
        1996 => Some(6_179),
        9996 => Some(16_107),
        _ => None,
    }
}

/// Two concentric sphere models of `facets` triangles each (rounded down to an even number,
/// `2n − 4` for `n` vertices): the convex hulls of `n` random points (uniform, seeded) on the
/// unit sphere and of `n` others on the sphere of radius `1 + gap` (larger for a positive gap,
/// smaller for a negative one). The hulls are built exactly (an incremental hull with
/// `orient3d`), so every point is a vertex and the counts are exact.
///
/// Needs `4 ≤ facets ≤` [`MAX_FACES`] and a finite `gap` with `1 + gap` between `1e-6` and
/// `1e6`.
///
/// ```
/// let (inner, outer) = kepler::lab::boxtree::sphere_pair(556, 0.01, 7).unwrap();
/// assert_eq!((inner.triangles().len(), outer.triangles().len()), (556, 556));
/// assert_eq!(inner.vertices().len(), 280);
/// assert!(inner.is_solid() && outer.is_solid());
/// assert!(outer.vertices().iter().all(|v| (v.coords.norm() - 1.01).abs() < 1e-12));
/// let e = kepler::lab::boxtree::sphere_pair(556, -1.0, 7).unwrap_err();
/// assert_eq!(e.to_string(), "sphere pair: gap must be a finite number with 1 + gap between 1e-6 and 1e6, got -1");
/// ```
pub fn sphere_pair(facets: usize, gap: f64, seed: u64) -> Result<(Mesh, Mesh), SolidError> {
    let invalid =
        |parameter: &'static str, value: String, requirement: &str| SolidError::InvalidParameter {
            solid: "sphere pair",
            parameter,
            value,
            requirement: requirement.to_string(),
        };
    if !(4..=MAX_FACES as usize).contains(&facets) {
        return Err(invalid(
            "facets",
            facets.to_string(),
            "between 4 and 1000000",
        ));
    }
    let radius = 1.0 + gap;
    if !(gap.is_finite() && (1e-6..=1e6).contains(&radius)) {
        return Err(invalid(
            "gap",
            gap.to_string(),
            "a finite number with 1 + gap between 1e-6 and 1e6",
        ));
    }
    let n = facets / 2 + 2;
    let mut rng = SplitMix64(seed);
    let inner = random_sphere(n, 1.0, &mut rng)?;
    let outer = random_sphere(n, radius, &mut rng)?;
    Ok((inner, outer))
}

/// For each facet count and each shape, the collision tests of a complete search between the
/// two spheres of [`sphere_pair`]`(facets, gap, seed + facets)` under `merge`, beside the
/// paper's count.
///
/// ```
/// use kepler::lab::boxtree::{Merge, sphere_experiment};
/// let rows = sphere_experiment(&[100], 0.2, 3, Merge::Area).unwrap();
/// assert!(rows.iter().all(|r| r.intersecting_pairs == 0 && r.paper.is_none()));
/// assert!(sphere_experiment(&[2], 0.2, 3, Merge::Area).is_err());
/// ```
pub fn sphere_experiment(
    facets: &[usize],
    gap: f64,
    seed: u64,
    merge: Merge,
) -> Result<Vec<Row>, SolidError> {
    let mut rows = Vec::new();
    for &f in facets {
        let (a, b) = sphere_pair(f, gap, seed.wrapping_add(f as u64))?;
        for shape in Shape::ALL {
            let (pairs, work) = match shape {
                Shape::Aabb => search::<Aabb>(&a, &b, merge),
                Shape::PcaAll => search::<PcaAll>(&a, &b, merge),
                Shape::PcaMax => search::<PcaMax>(&a, &b, merge),
                Shape::PcaMin => search::<PcaMin>(&a, &b, merge),
                Shape::Tribox => search::<TriboxBounds>(&a, &b, merge),
            };
            rows.push(Row {
                facets: a.triangles().len(),
                shape,
                tests: work.tests,
                triangle_tests: work.triangle_tests,
                intersecting_pairs: pairs,
                paper: paper_tests(a.triangles().len(), shape),
            });
        }
    }
    Ok(rows)
}

/// Both hierarchies of one shape and their complete search: meeting pairs and the work.
fn search<S: NodeShape>(a: &Mesh, b: &Mesh, merge: Merge) -> (usize, super::Collision) {
    let ta = BoxTree::<S>::build(a, merge);
    let tb = BoxTree::<S>::build(b, merge);
    let (pairs, work) = ta.intersecting_pairs(&tb);
    (pairs.len(), work)
}

/// The convex hull of `n` random points on the sphere of `radius` about the origin.
fn random_sphere(n: usize, radius: f64, rng: &mut SplitMix64) -> Result<Mesh, SolidError> {
    let points: Vec<Point3> = (0..n)
        .map(|_| {
            // Archimedes: z uniform in [-1, 1] and a uniform angle give a uniform point.
            let z = 2.0 * rng.unit() - 1.0;
            let angle = std::f64::consts::TAU * rng.unit();
            let r = (1.0 - z * z).max(0.0).sqrt();
            Point3::new(r * angle.cos(), r * angle.sin(), z) * radius
        })
        .collect();
    let faces = convex_hull(&points).ok_or_else(|| SolidError::InvalidParameter {
        solid: "sphere pair",
        parameter: "facets",
        value: (2 * n - 4).to_string(),
        requirement: "enough for points not all in one plane".to_string(),
    })?;
    // Keep the vertices the hull uses (every point, barring coincidences), renumbered.
    let mut index = vec![u32::MAX; points.len()];
    let mut vertices = Vec::with_capacity(points.len());
    let faces = faces
        .into_iter()
        .map(|f| {
            f.iter()
                .map(|&v| {
                    if index[v as usize] == u32::MAX {
                        index[v as usize] = vertices.len() as u32;
                        vertices.push(points[v as usize]);
                    }
                    index[v as usize]
                })
                .collect()
        })
        .collect();
    Ok(Mesh::from_polygons(vertices, faces)?)
}
