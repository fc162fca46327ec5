//! Stage 2 of the pass: the intersection lines where faces pierce each other (between objects
//! whose CBOXes overlap, and within each object), and the cuts where an edge pierces a face or
//! an intersection line passes through a third face (a triple point).

use super::cuts::frustum_cuts;
use super::line::LineId;
use super::line::{Cut, Line, MeetLine, on_faces, rough_parameter};
use super::pass::Pass;
use super::{EdgeClass, marks};
use crate::geometry::{Aabb, Point3};
use crate::scene::{ObjectId, Scene};
use crate::sight::along::Form;
use crate::sight::intersections;
use rayon::prelude::*;
use rstar::RTree;
use rstar::primitives::{GeomWithData, Rectangle};
use std::cmp::Ordering;
use std::collections::HashMap;
use std::time::Instant;

/// The triangles that stage 2 pairs up, and the lines it will cut where they pass through a
/// third face.
#[derive(Default)]
struct Partners {
    /// Each triangle's partners in intersections (the triangles whose faces it meets).
    partners: HashMap<(ObjectId, usize), Vec<(ObjectId, usize)>>,
    /// The lines to cut.
    crossings: Vec<usize>,
    /// Each intersection line's triangles (by its index in [`Pass::meets`]).
    owned: Vec<Vec<(ObjectId, usize)>>,
}

impl Pass<'_> {
    /// Stage 2: intersection lines between objects whose CBOXes overlap and within each
    /// object, and the cuts where edges pierce faces.
    pub(super) fn intersections(&mut self) {
        let clock = Instant::now();
        let eye = self.eye;
        let ids: Vec<ObjectId> = self.leaves.iter().map(|l| l.id).collect();
        let pairs = overlapping_cboxes(self.scene, &ids);
        let apart = ids.len() * (ids.len() + 1) / 2 - pairs.len();
        let leaves = &self.leaves;
        let found: Vec<(Vec<intersections::Segment>, Vec<[usize; 3]>)> = pairs
            .par_iter()
            .map(|&(i, j)| intersections::meetings(leaves[i].mesh, leaves[j].mesh, i == j, &eye))
            .collect();
        let mut segments = 0usize;
        let mut self_intersecting = Vec::new();
        let mut found_partners = Partners::default();
        for (&(i, j), (found, contacts)) in pairs.iter().zip(found) {
            let (id0, id1) = (ids[i], ids[j]);
            // A triangle that crosses another's plane: an edge of it may pass through the other
            // even where their faces only touch (an edge entering a solid exactly across an
            // edge of its surface), so the other is its partner for piercings.
            for [k, t, u] in contacts {
                let (x, y) = if k == 0 {
                    ((id0, t), (id1, u))
                } else {
                    ((id1, t), (id0, u))
                };
                found_partners.partners.entry(x).or_default().push(y);
            }
            for (k, s) in found.into_iter().enumerate() {
                segments += 1;
                if self.meet_line((i, j), (id0, id1), (k, s), &mut found_partners)
                    && i == j
                    && self_intersecting.last() != Some(&i)
                {
                    // Once per mesh (its segments come together): clearing its lines' `back`
                    // for each of its segments would cost segments × edges.
                    self_intersecting.push(i);
                }
            }
        }
        let (triple, pierced) = self.piercings(&ids, found_partners);
        // A mesh that pierces itself is not a proper solid: its back faces decide nothing.
        for i in self_intersecting {
            let range = self.leaves[i].lines.clone();
            self.lines[range].iter_mut().for_each(|l| l.back = false);
            self.leaves[i].turned = Vec::new();
        }
        let done = format!(
            "{segments} segments from {} object pairs with overlapping CBOXes (each object with \
             itself included); {pierced} cuts where edges pierce faces, {triple} triple points",
            pairs.len()
        );
        let skipped =
            (apart > 0).then(|| format!("{apart} object pairs whose CBOXes do not overlap"));
        self.stage("intersections", clock, done, skipped);
    }

    /// The line of the `k`th intersection segment `s` between leaves `i` and `j` (objects
    /// `id0` and `id1`), with its triangles as each other's partners, and the cuts where the
    /// view's frustum or the tile clips it. Whether it was added (not wholly behind the eye).
    fn meet_line(
        &mut self,
        (i, j): (usize, usize),
        (id0, id1): (ObjectId, ObjectId),
        (k, s): (usize, intersections::Segment),
        found: &mut Partners,
    ) -> bool {
        let (eye, clip) = (self.eye, self.clip);
        let tile = self.tile.as_ref();
        let leaves = &self.leaves;
        // Which ends are in front of the eye, and whether both are inside the frustum,
        // decided exactly at the ends (points of the meet line).
        let sign_at = |k: usize| move |form: &Form| s.meet.sign_at(&eye, &s.ends[k], form);
        let front =
            [0, 1].map(|k| clip.is_none_or(|n| sign_at(k)(&n.depth()) == Ordering::Greater));
        let inside = [0, 1].map(|k| {
            clip.is_none_or(|n| n.contains_by(sign_at(k)))
                && tile.is_none_or(|t| t.contains_by(sign_at(k)))
        });
        if front == [false, false] {
            // Wholly behind the eye: nothing of it is drawn or bounds what is seen.
            return false;
        }
        let mut own = Vec::with_capacity(2 * s.triangles.len());
        for &[t0, t1] in &s.triangles {
            let (x, y) = ((id0, t0), (id1, t1));
            found.partners.entry(x).or_default().push(y);
            found.partners.entry(y).or_default().push(x);
            own.extend([x, y]);
        }
        found.owned.push(own);
        found.crossings.push(self.lines.len());
        self.lines.push(Line {
            a: s.points[0],
            b: s.points[1],
            ends: [0, 1].map(|k| match front[k] {
                true => s.meet.picture(&self.picture, &eye, &s.ends[k]),
                false => [0.0, 0.0],
            }),
            class: EdgeClass::Intersection,
            meet: Some(self.meets.len()),
            back: false,
            triangles: None,
            wide: front != [true, true],
            clipped: inside != [true, true],
            leaf: 0,
            vertices: [0; 2],
            id: LineId::Meet(leaves[i].global, leaves[j].global, k as u32),
        });
        let meshes = [i, j].map(|n| (leaves[n].global, leaves[n].mesh));
        self.meets.push(MeetLine {
            meet: s.meet,
            ends: s.ends,
            on_faces: [(id0, s.faces[0]), (id1, s.faces[1])],
            keys: marks::end_keys(&s.ends, meshes, &s.triangles, s.faces),
        });
        let line = self.lines.len() - 1;
        if self.lines[line].clipped {
            let meet = self.meets.last();
            let cuts = frustum_cuts(clip, tile, &eye, (line, &self.lines[line], meet));
            self.cuts.extend(cuts);
        }
        true
    }

    /// The cuts where an edge passes through a face, and an intersection line through a third
    /// face (a triple point), where it may go behind it; that face pierces a face the line
    /// lies on, so it is among that face's partners. Each cut is where the face's plane (the
    /// one that stands for all its triangles) vanishes on the line. How many triple points,
    /// and how many cuts where edges pierce faces.
    fn piercings(&mut self, ids: &[ObjectId], found: Partners) -> (usize, usize) {
        let Partners {
            partners,
            mut crossings,
            owned,
        } = found;
        for leaf in self.leaves.iter().filter(|_| !partners.is_empty()) {
            for l in leaf.lines.clone() {
                if self.lines[l].triangles.is_some() {
                    crossings.push(l);
                }
            }
        }
        // Each object's index among the scene's mesh objects (the same in every tile), for
        // naming cuts.
        let leaf_of: HashMap<ObjectId, u32> = self
            .leaves
            .iter()
            .map(|leaf| (leaf.id, leaf.global))
            .collect();
        let (mut triple, mut pierced) = (0usize, 0usize);
        for l in crossings {
            let line = self.lines[l];
            let edge_triangles;
            let own: &[(ObjectId, usize)] = match (line.meet, line.triangles) {
                (Some(m), _) => &owned[m],
                (None, Some(triangles)) => {
                    edge_triangles = triangles.map(|t| (ids[line.leaf as usize], t as usize));
                    &edge_triangles
                }
                (None, None) => &[],
            };
            let mut third: Vec<(ObjectId, usize)> = own
                .iter()
                .flat_map(|t| partners.get(t).into_iter().flatten().copied())
                .filter(|t| !own.contains(t))
                .collect();
            third.sort_unstable();
            third.dedup();
            let reach = line.meet.map(|_| self.reach(&line, own));
            for (object, t) in third {
                match self.pierce(l, &line, reach, (object, t), &leaf_of) {
                    Some(true) => triple += 1,
                    Some(false) => pierced += 1,
                    None => {}
                }
            }
        }
        (triple, pierced)
    }

    /// An intersection line's box, grown by far more than the error of its approximate ends
    /// (a few units in 2⁻⁴⁴ of its triangles' coordinates, `own`): a face whose box misses it
    /// cannot meet the line.
    fn reach(&self, line: &Line, own: &[(ObjectId, usize)]) -> Aabb {
        let scene = self.scene;
        let triangle = |(object, t): (ObjectId, usize)| scene[object].mesh().map(|m| m.triangle(t));
        let size = own
            .iter()
            .filter_map(|&t| triangle(t))
            .flatten()
            .fold(0.0f64, |m, p| m.max(p.coords.amax()));
        let margin = size / (1u64 << 40) as f64;
        let b = Aabb::from_points(&[line.a, line.b]);
        Aabb::new(
            Point3::from(b.min.map(|v| v - margin)),
            Point3::from(b.max.map(|v| v + margin)),
        )
    }

    /// The cut of line `l` where it passes through triangle `t` of `object` (`reach`: an
    /// intersection line's box), if it does: `Some(true)` for a triple point on an
    /// intersection line, `Some(false)` where an edge pierces the face.
    fn pierce(
        &mut self,
        l: usize,
        line: &Line,
        reach: Option<Aabb>,
        (object, t): (ObjectId, usize),
        leaf_of: &HashMap<ObjectId, u32>,
    ) -> Option<bool> {
        let eye = self.eye;
        let mesh = self.scene[object].mesh()?;
        let tri = mesh.triangle(t);
        match line.meet {
            Some(m) => {
                let MeetLine { meet, ends, .. } = &self.meets[m];
                let apart = reach.is_some_and(|r| !r.intersects(&Aabb::from_points(&tri)));
                if apart || on_faces(&self.meets[m], self.scene, object, t) {
                    return None;
                }
                let (_, plane) = intersections::plane_of(mesh, t);
                let form = intersections::pierces_line(meet, &eye, ends, &tri, &plane)?;
                let face = mesh.face_of(t) as u32;
                let t = rough_parameter(&eye, &form, &line.a, &line.b);
                let key = [1, leaf_of[&object], face, 0];
                self.cuts.push((l, Cut::on_line(form, t, None, key)));
                Some(true)
            }
            None => {
                let key = [1, leaf_of[&object], mesh.face_of(t) as u32, 0];
                let zero = intersections::pierces(&eye, &line.a, &line.b, mesh, t)?;
                self.cuts.push((l, Cut::on_edge(zero, None, key)));
                Some(false)
            }
        }
    }
}

/// Every pair `(i, j)`, `i <= j`, of the objects `ids` whose CBOXes meet (closed boxes), in
/// increasing order: a simultaneous descent of an R-tree of the CBOXes with itself.
pub(super) fn overlapping_cboxes(scene: &Scene, ids: &[ObjectId]) -> Vec<(usize, usize)> {
    let boxes: Vec<GeomWithData<Rectangle<[f64; 3]>, usize>> = ids
        .iter()
        .enumerate()
        .map(|(i, &id)| {
            let b = scene.cbox(id);
            GeomWithData::new(Rectangle::from_corners(b.min, b.max), i)
        })
        .collect();
    let tree = RTree::bulk_load(boxes);
    let mut pairs: Vec<(usize, usize)> = tree
        .intersection_candidates_with_other_tree(&tree)
        .filter(|(a, b)| a.data <= b.data)
        .map(|(a, b)| (a.data, b.data))
        .collect();
    pairs.sort_unstable();
    pairs
}
