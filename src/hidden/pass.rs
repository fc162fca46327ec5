//! The state of one hidden-line pass ([`Pass`]), how it is set up over the scene's meshes, and
//! stages 1 to 4 run in order ([`decided`]). Each stage is an `impl Pass` block in its own
//! file: `edges.rs`, `intersections.rs`, `cuts.rs`, `visibility.rs`; `chain.rs` chains the
//! pieces (stage 5).

use super::line::{Cut, Line, MeetLine};
use super::piece::Piece;
use super::{Options, Result, StageReport};
use crate::mesh::Mesh;
use crate::scene::{ObjectId, Scene};
use crate::sight::frustum::{Clip, TilePlanes, pictured};
use crate::views::{Eye, Picture, View};
use rayon::prelude::*;
use std::collections::HashMap;
use std::time::Instant;

/// Stages 1 to 4 of the pass (in one tile, with `tile`): the pass and every piece with its
/// visibility.
pub(super) fn decided<'a>(
    scene: &'a Scene,
    view: &View,
    tile: Option<TilePlanes>,
    options: &Options,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<(Pass<'a>, Vec<Piece>)> {
    let mut pass = Pass::new(scene, view, tile)?;
    pass.edges(options);
    pass.intersections();
    pass.contour_cuts();
    let pieces = pass.visibility(progress);
    Ok((pass, pieces))
}

/// A mesh of the scene in the pass: its object, its vertices' pictures, and the range of its
/// edges in [`Pass::lines`].
pub(super) struct Leaf<'a> {
    pub(super) id: ObjectId,
    /// Its index among the scene's mesh objects, the same in every tile.
    pub(super) global: u32,
    pub(super) mesh: &'a Mesh,
    pub(super) pictures: Vec<[f64; 2]>,
    /// When the view clips: whether each vertex is strictly in front of the eye (the others'
    /// pictures mean nothing).
    pub(super) front: Vec<bool>,
    pub(super) lines: std::ops::Range<usize>,
    /// When its mesh bounds a solid seen from outside that does not pierce itself: whether
    /// each triangle is turned away from the eye, hidden by its own solid (see
    /// [`turned_away`](crate::sight::own_solid::turned_away)); else empty. Set with the
    /// edges, cleared where the intersections stage finds the mesh piercing itself.
    pub(super) turned: Vec<bool>,
}

/// The state of one hidden-line pass, stage by stage.
pub(super) struct Pass<'a> {
    pub(super) scene: &'a Scene,
    pub(super) eye: Eye,
    pub(super) picture: Picture,
    pub(super) leaves: Vec<Leaf<'a>>,
    /// The lines to draw: edges, then intersection segments.
    pub(super) lines: Vec<Line>,
    /// The intersection segments, indexed by [`Line::meet`].
    pub(super) meets: Vec<MeetLine>,
    /// Cuts, by line index.
    pub(super) cuts: Vec<(usize, Cut)>,
    pub(super) stages: Vec<StageReport>,
    /// The frustum, when the view clips (a perspective eye with part of the scene not in
    /// front of it).
    pub(super) clip: Option<Clip>,
    /// The mesh objects left out as exact copies of an earlier one.
    pub(super) copies: usize,
    /// The window, when the pass draws one tile of a grid (see [`tiles`](super::tiles)).
    pub(super) tile: Option<TilePlanes>,
    /// The mesh objects left out because their CBOX lies outside the tile.
    pub(super) outside_tile: usize,
    /// See [`Provenance::slack`](super::marks::Provenance::slack).
    pub(super) slack: f64,
}

impl<'a> Pass<'a> {
    /// The pass over every mesh of the scene; a perspective view with a vertex not strictly
    /// in front of the eye clips to its frustum (see `queries/frustum.rs`).
    /// With a `tile`, the pass draws only what lies in it, from the objects whose CBOX may
    /// reach it (see [`tiles`](super::tiles)).
    pub(super) fn new(scene: &'a Scene, view: &View, tile: Option<TilePlanes>) -> Result<Pass<'a>> {
        let picture = Picture::of(view);
        let (meshes, clip) = pictured(scene, view)?;
        // In a tile, the objects that may reach it, each with its index among all (so named
        // the same in every tile). Exact copies share their CBOX: a copy and its first are
        // left out together, so the copies found among the rest are those of the whole.
        let all = meshes.len();
        let meshes: Vec<(usize, (ObjectId, &Mesh))> = meshes
            .into_iter()
            .enumerate()
            .filter(|(_, (id, _))| {
                tile.as_ref()
                    .is_none_or(|t| !t.surely_outside(&scene.cbox(*id).corners()))
            })
            .collect();
        let outside_tile = all - meshes.len();
        let (globals, meshes): (Vec<usize>, Vec<(ObjectId, &Mesh)>) = meshes.into_iter().unzip();
        // Exact copies of an earlier mesh are left out (see [`originals`]): a copy hides
        // exactly what the first hides, meets nothing the first does not (coincident faces
        // make no intersection line), and its edges are the first's. Copies stacked in one
        // place would otherwise cost every pair of them.
        let first = originals(&meshes);
        let copies = (0..meshes.len()).filter(|&n| first[n] != n).count();
        let leaves: Vec<Leaf> = meshes
            .into_iter()
            .zip(globals)
            .enumerate()
            .filter(|(n, _)| first[*n] == *n)
            .map(|(_, ((id, mesh), global))| Leaf {
                id,
                global: global as u32,
                mesh,
                pictures: Vec::new(),
                front: Vec::new(),
                lines: 0..0,
                turned: Vec::new(),
            })
            .collect();
        let slack = picture_slack(scene, &picture, leaves.iter().map(|l| l.id));
        Ok(Pass {
            slack,
            tile,
            outside_tile,
            clip,
            scene,
            eye: *view.eye(),
            picture,
            leaves,
            lines: Vec::new(),
            meets: Vec::new(),
            cuts: Vec::new(),
            stages: Vec::new(),
            copies,
        })
    }

    /// Records a stage for `--stats`.
    pub(super) fn stage(
        &mut self,
        name: &'static str,
        clock: Instant,
        done: String,
        skipped: Option<String>,
    ) {
        timed(&mut self.stages, name, clock, done, skipped);
    }
}

/// How far the picture of a point of the objects `ids` may lie from the picture line of its
/// plane of sight beyond its rounding (see
/// [`Provenance::slack`](super::marks::Provenance::slack)): an orthographic picture's rows are
/// rounded unit vectors, whose products with the view direction are within a few units in the
/// last place of zero, times the depth of a point from the picture's origin.
pub(super) fn picture_slack(
    scene: &Scene,
    picture: &Picture,
    ids: impl Iterator<Item = ObjectId>,
) -> f64 {
    if picture.is_perspective() {
        return 0.0;
    }
    let (_, origin) = picture.rows();
    let extent = ids
        .flat_map(|id| scene.cbox(id).corners())
        .fold(0.0f64, |m, c| m.max((c - origin).amax()));
    16.0 * f64::EPSILON * extent
}

/// Records a stage that started at `clock` (a free function, for stages that hold borrows of
/// the pass's other fields).
pub(super) fn timed(
    stages: &mut Vec<StageReport>,
    name: &'static str,
    clock: Instant,
    done: String,
    skipped: Option<String>,
) {
    stages.push(StageReport {
        name,
        done,
        skipped,
        seconds: clock.elapsed().as_secs_f64(),
    });
}

/// For each mesh object, the index of the first whose mesh is the same (the same vertices, bit
/// for bit, and the same faces and triangles): itself unless it is an exact copy.
pub(crate) fn originals(meshes: &[(ObjectId, &Mesh)]) -> Vec<usize> {
    use std::hash::{Hash, Hasher};
    let key = |m: &Mesh| {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        for p in m.vertices() {
            p.map(f64::to_bits).hash(&mut h);
        }
        m.triangles().hash(&mut h);
        h.finish()
    };
    let keys: Vec<u64> = meshes.par_iter().map(|(_, m)| key(m)).collect();
    let mut seen: HashMap<u64, Vec<usize>> = HashMap::new();
    let mut first = Vec::with_capacity(meshes.len());
    for (n, (&(_, m), k)) in meshes.iter().zip(keys).enumerate() {
        let earlier = seen.entry(k).or_default();
        let same = earlier.iter().copied().find(|&e| {
            let o = meshes[e].1;
            o.vertices() == m.vertices()
                && o.triangles() == m.triangles()
                && o.faces().len() == m.faces().len()
                && o.faces()
                    .iter()
                    .zip(m.faces())
                    .all(|(f, g)| f.vertices() == g.vertices())
        });
        first.push(same.unwrap_or_else(|| {
            earlier.push(n);
            n
        }));
    }
    first
}
