//! The culling experiment (`kepler::lab::culling::cull`): exact counts on hand-made scenes, and on
//! random scenes every filter's decisions against independent references (geo's polygon
//! intersection for the pictures, VISP for the INBOX).

use geo::{ConvexHull, Intersects, MultiPoint, Point};
use kepler::geometry::{Point3, Vector3};
use kepler::lab::culling::cull;
use kepler::mesh::Mesh;
use kepler::queries::visp::{Visibility, VisibilityIndex, visp};
use kepler::scene::Scene;
use kepler::solids;
use kepler::views::{Picture, View};
use nalgebra::Matrix4;

use crate::common::{SplitMix64, unit_octahedron as octahedron};

fn moved(mesh: &Mesh, t: [f64; 3]) -> Mesh {
    mesh.transformed(&Matrix4::new_translation(&Vector3::new(t[0], t[1], t[2])))
        .unwrap()
}

fn scene_of(meshes: &[Mesh]) -> Scene {
    let mut scene = Scene::new();
    for (i, m) in meshes.iter().enumerate() {
        scene.add_mesh(None, format!("m{i}"), m.clone()).unwrap();
    }
    scene
}

/// `(rstar, cbox, tribox, inbox)` decided counts and the undecided count.
fn counts(scene: &Scene, view: &View) -> ([u64; 4], u64) {
    let r = cull(scene, view).unwrap();
    let d: Vec<u64> = r.filters.iter().map(|f| f.decided).collect();
    ([d[0], d[1], d[2], d[3]], r.undecided)
}

#[test]
fn hand_made_scenes_have_exact_counts() {
    let down = View::standard();
    let cube = solids::cube(2.0).unwrap();
    // Far apart: every filter but the INBOX decides the pair.
    let s = scene_of(&[cube.clone(), moved(&cube, [5.0, 0.0, 0.0])]);
    assert_eq!(counts(&s, &down), ([1, 1, 1, 0], 0));
    // Seen from above, cubes at (0, 0), (1.5, 1.5) and (3, 3) on a diagonal: the pictures of
    // neighbours overlap; those of the ends, [−1, 1]² and [2, 4]², are apart.
    let s = scene_of(&[
        cube.clone(),
        moved(&cube, [1.5, 1.5, 0.0]),
        moved(&cube, [3.0, 3.0, 0.0]),
    ]);
    assert_eq!(counts(&s, &down), ([1, 1, 1, 0], 2));
    // Two octahedra side by side along the diagonal: their CBOXes' pictures overlap, their
    // triboxes' (the diamonds |x| + |y| ≤ 1 and |x − 1.2| + |y − 1.2| ≤ 1) do not.
    let s = scene_of(&[octahedron(), moved(&octahedron(), [1.2, 1.2, 0.0])]);
    assert_eq!(counts(&s, &down), ([0, 0, 1, 0], 0));
    // A big cube above a small one: the big one's INBOX hides all of the small one.
    let s = scene_of(&[
        moved(&solids::cube(4.0).unwrap(), [0.0, 0.0, 5.0]),
        solids::cube(1.0).unwrap(),
    ]);
    assert_eq!(counts(&s, &down), ([0, 0, 0, 1], 0));
    // Seen from below, the small one hides nothing of the big one.
    let up = View::orthographic(Vector3::z(), Vector3::y()).unwrap();
    assert_eq!(counts(&s, &up), ([0, 0, 0, 0], 1));
    // Triangle pairs: 12 · 8 for a cube and an octahedron.
    let s = scene_of(&[cube.clone(), moved(&octahedron(), [9.0, 0.0, 0.0])]);
    let r = cull(&s, &down).unwrap();
    assert_eq!(
        (r.triangle_pairs, r.filters[0].triangle_pairs_saved),
        (96, 96)
    );
}

/// The picture of the points as a geo convex polygon.
fn hull(points: &[Point3], picture: &Picture) -> geo::Polygon<f64> {
    let mp: MultiPoint<f64> = points
        .iter()
        .map(|p| {
            let [x, y] = picture.point(p);
            Point::new(x, y)
        })
        .collect();
    mp.convex_hull()
}

#[test]
fn random_scenes_agree_with_independent_references() {
    let mut rng = SplitMix64(0xc011);
    let mut decided_by_inbox = 0;
    for case in 0..40 {
        let n = 2 + rng.below(7);
        let meshes: Vec<Mesh> = (0..n)
            .map(|_| {
                let base = if rng.below(2) == 0 {
                    solids::cuboid(Vector3::new(
                        rng.range(0.3, 2.0),
                        rng.range(0.3, 2.0),
                        rng.range(0.3, 2.0),
                    ))
                    .unwrap()
                } else {
                    octahedron()
                };
                moved(
                    &base,
                    [
                        rng.range(-4.0, 4.0),
                        rng.range(-4.0, 4.0),
                        rng.range(-4.0, 4.0),
                    ],
                )
            })
            .collect();
        let scene = scene_of(&meshes);
        let view = if case % 3 == 0 {
            View::perspective(
                Point3::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0), 20.0),
                Point3::origin(),
                Vector3::y(),
                50.0,
            )
            .unwrap()
        } else {
            View::orthographic(rng.vector(1.0), Vector3::new(0.3, 0.2, 1.0)).unwrap()
        };
        let picture = Picture::of(&view);
        let ids: Vec<_> = scene.roots().to_vec();
        let (mut rstar, mut cbox, mut tribox, mut inbox, mut left) = (0, 0, 0, 0u64, 0);
        let index = VisibilityIndex::new(&scene, &ids, view.clone());
        for i in 0..n {
            for j in i + 1..n {
                let bound = |k: usize| scene.cbox(ids[k]).corners().to_vec();
                let tri = |k: usize| {
                    kepler::bounds::tribox::Tribox::new(&scene.tribox(ids[k]))
                        .vertices()
                        .to_vec()
                };
                let (ci, cj) = (hull(&bound(i), &picture), hull(&bound(j), &picture));
                let boxes_apart = {
                    use geo::BoundingRect;
                    let (a, b) = (ci.bounding_rect().unwrap(), cj.bounding_rect().unwrap());
                    !a.intersects(&b)
                };
                let cbox_apart = !ci.intersects(&cj);
                let tribox_apart = !hull(&tri(i), &picture).intersects(&hull(&tri(j), &picture));
                // The INBOX reference: every corner of one CBOX hidden by the other object
                // (VISP against that object alone). The filter needs more (the INBOX), so it
                // can decide at most these pairs.
                let hidden_by = |k: usize, by: usize| {
                    bound(k)
                        .iter()
                        .all(|c| visp(&scene, ids[by], &view, c).0 == Visibility::Hidden)
                };
                rstar += u64::from(boxes_apart);
                cbox += u64::from(cbox_apart);
                tribox += u64::from(tribox_apart);
                let one_hides = hidden_by(i, j) || hidden_by(j, i);
                inbox += u64::from(one_hides);
                // The whole scene hides what one object hides.
                if one_hides {
                    let k = if hidden_by(i, j) { i } else { j };
                    assert!(
                        bound(k)
                            .iter()
                            .all(|c| index.visp(c).0 == Visibility::Hidden)
                    );
                }
                left += u64::from(!(boxes_apart || cbox_apart || tribox_apart));
            }
        }
        let r = cull(&scene, &view).unwrap();
        let got: Vec<u64> = r.filters.iter().map(|f| f.decided).collect();
        assert_eq!(&got[..3], &[rstar, cbox, tribox], "case {case}");
        assert!(got[1] >= got[0] && got[2] >= got[1], "case {case}");
        assert!(
            got[3] <= inbox,
            "case {case}: INBOX decided {} of {inbox}",
            got[3]
        );
        assert!(r.undecided <= left, "case {case}");
        assert_eq!(r.pairs, (n * (n - 1) / 2) as u64);
        decided_by_inbox += got[3];
    }
    // The random scenes exercise the INBOX filter too.
    assert!(decided_by_inbox > 0);
}

#[test]
fn ideographs_replace_objects_by_their_exact_projected_area() {
    use kepler::hidden::ideographs::{Ideograph, ideographs};
    use kepler::hidden::{Options, draw};
    // Cubes of side 1, 2 and 3 seen from above have pictures of area 1, 4 and 9 exactly.
    let cubes: Vec<Mesh> = [1.0, 2.0, 3.0]
        .iter()
        .enumerate()
        .map(|(i, &s)| moved(&solids::cube(s).unwrap(), [10.0 * i as f64, 0.0, 0.0]))
        .collect();
    let scene = scene_of(&cubes);
    let down = View::standard();
    let culled = |min: f64| {
        ideographs(&scene, &down, min, Ideograph::Omit)
            .unwrap()
            .culled
    };
    assert_eq!(culled(1.0), 0);
    assert_eq!(culled(4.0), 1);
    assert_eq!(culled(4.0f64.next_up()), 2);
    assert_eq!(culled(f64::INFINITY), 3);
    let omitted = ideographs(&scene, &down, 4.0, Ideograph::Omit).unwrap();
    assert_eq!(omitted.scene.roots().len(), 2);
    assert_eq!((omitted.triangles_culled, omitted.triangles_added), (12, 0));
    // An octahedron drawn as its bound draws exactly as its CBOX would.
    let scene = scene_of(&[
        octahedron(),
        moved(&solids::cube(4.0).unwrap(), [9.0, 0.0, 0.0]),
    ]);
    let view = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).unwrap();
    let bound = ideographs(&scene, &view, 20.0, Ideograph::Bound).unwrap();
    assert_eq!(
        (bound.culled, bound.triangles_culled, bound.triangles_added),
        (1, 8, 12)
    );
    let by_hand = scene_of(&[
        solids::cube(2.0).unwrap(),
        moved(&solids::cube(4.0).unwrap(), [9.0, 0.0, 0.0]),
    ]);
    let options = Options::default();
    // The same segments (the two meshes number their vertices differently, so chains may
    // start elsewhere or run the other way).
    let segments = |scene: &Scene| {
        let mut out: Vec<(String, bool, [[u64; 2]; 2])> = draw(scene, &view, &options)
            .unwrap()
            .polylines
            .iter()
            .flat_map(|p| {
                p.points.windows(2).map(|w| {
                    let mut ends = [w[0], w[1]].map(|[x, y]| [x.to_bits(), y.to_bits()]);
                    ends.sort_unstable();
                    (format!("{:?}", p.class), p.visible, ends)
                })
            })
            .collect();
        out.sort_unstable();
        out
    };
    let got = segments(&bound.scene);
    assert_eq!(got.len(), 24); // per cube: 6 silhouette, 3 visible and 3 hidden creases
    assert_eq!(got, segments(&by_hand));
}
