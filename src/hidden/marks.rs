//! What a piece of a drawing is, exactly: the [`Support`] its line lies on and the
//! [`LinePoint`]s its ends are, so that stages after the pass (overlap removal, stitching
//! tiles) decide from the input, never from the rounded pictures.
//!
//! A piece names its ends by [`Mark`]s: an end of its line or one of the pass's cuts. A
//! [`Provenance`] turns a line and a mark into the exact point, and names it by a
//! [`MarkKey`] that is the same in a transformed scene and in every tile of a grid, so that
//! where several points are one (several cuts at one point of a picture line), the same one
//! is drawn whatever the transformation.

use super::{Line, MeetLine, Pass};
use crate::mesh::Mesh;
use crate::sight::along::Zero;
use crate::sight::collinear::{LinePoint, Support};
use crate::sight::meet::OnLine;
use crate::views::Eye;

/// Where a piece of a line begins or ends: an end of the line (its first or last, in the
/// line's direction), or a cut of it, by the cut's index in its [`Provenance`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mark {
    /// The line's first end.
    First,
    /// The line's last end.
    Last,
    /// A cut.
    Cut(u32),
}

/// The name of a point a piece begins or ends at, from the indices of the input that make
/// it (the same in a transformed scene and in every tile): `[0, object, vertex, ..]` for an
/// input vertex (and for a cut drawn at the picture of one), a cut's own key (kinds 1 to 4)
/// for a cut, `[5, object, u, v, object', face]` for an intersection segment's end where the
/// edge `uv` crosses the plane of a face of another object. Of several points that are one,
/// the one with the smallest key is drawn.
pub(crate) type MarkKey = [u32; 6];

/// The exact description of the lines and cuts that pieces refer to.
pub(crate) trait Provenance: Sync {
    /// The eye the pieces were decided from.
    fn eye(&self) -> &Eye;

    /// How far the rounded picture of a point may lie from the picture line of its plane of
    /// sight beyond its own rounding: zero in perspective; in an orthographic view, whose
    /// picture map is built from rounded directions, a few units in the last place of the
    /// scene's extent from the picture's origin. For filters only.
    fn slack(&self) -> f64;

    /// The support of line `line`.
    fn support(&self, line: usize) -> Support;

    /// The point `mark` of line `line`.
    fn point(&self, line: usize, mark: Mark) -> LinePoint;

    /// The name of the point `mark` of line `line`.
    fn key(&self, line: usize, mark: Mark) -> MarkKey;
}

/// The point `mark` of a line on `support`, its cuts' zeros given by `zero` (a cut of an
/// intersection line is where its zero's form vanishes on the line).
pub(crate) fn point_of(support: &Support, mark: Mark, zero: impl FnOnce(u32) -> Zero) -> LinePoint {
    match support {
        Support::Edge([a, b]) => match mark {
            Mark::First => LinePoint::Vertex(*a),
            Mark::Last => LinePoint::Vertex(*b),
            Mark::Cut(k) => LinePoint::Cut {
                edge: [*a, *b],
                zero: zero(k),
            },
        },
        Support::Meet { meet, ends } => LinePoint::Meet {
            meet: *meet,
            point: match mark {
                Mark::First => ends[0],
                Mark::Last => ends[1],
                Mark::Cut(k) => OnLine::Cut(zero(k).form),
            },
        },
    }
}

/// A cut's key as a [`MarkKey`].
pub(crate) fn cut_key(key: [u32; 4]) -> MarkKey {
    [key[0], key[1], key[2], key[3], 0, 0]
}

/// The support of a line of the pass (an edge, or a segment of an intersection line).
pub(crate) fn support_of(line: &Line, meets: &[MeetLine]) -> Support {
    match line.meet {
        Some(m) => Support::Meet {
            meet: meets[m].meet,
            ends: meets[m].ends,
        },
        None => Support::Edge([line.a, line.b]),
    }
}

impl Provenance for Pass<'_> {
    fn eye(&self) -> &Eye {
        &self.eye
    }

    fn slack(&self) -> f64 {
        self.slack
    }

    fn support(&self, line: usize) -> Support {
        support_of(&self.lines[line], &self.meets)
    }

    fn point(&self, line: usize, mark: Mark) -> LinePoint {
        point_of(&self.support(line), mark, |k| self.cuts[k as usize].1.zero)
    }

    fn key(&self, line: usize, mark: Mark) -> MarkKey {
        let l = &self.lines[line];
        match (l.meet, mark) {
            (_, Mark::Cut(k)) => cut_key(self.cuts[k as usize].1.key),
            (None, Mark::First) => [0, l.object(), l.vertices[0], 0, 0, 0],
            (None, Mark::Last) => [0, l.object(), l.vertices[1], 0, 0, 0],
            (Some(m), Mark::First) => self.meets[m].keys[0],
            (Some(m), Mark::Last) => self.meets[m].keys[1],
        }
    }
}

/// The keys of an intersection segment's ends (see [`MarkKey`]): each end found among the
/// vertices of the segment's triangles, in mesh 0 first. `objects` are the two meshes'
/// indices among the scene's mesh objects, `faces` the segment's faces in them.
pub(crate) fn end_keys(
    ends: &[OnLine; 2],
    meshes: [(u32, &Mesh); 2],
    triangles: &[[usize; 2]],
    faces: [usize; 2],
) -> [MarkKey; 2] {
    let index = |side: usize, p: &crate::geometry::Point3| -> Option<u32> {
        let mesh = meshes[side].1;
        triangles.iter().find_map(|pair| {
            let t = mesh.triangles()[pair[side]];
            t.into_iter().find(|&v| mesh.vertices()[v as usize] == *p)
        })
    };
    ends.map(|end| match end {
        OnLine::Vertex { point, .. } => (0..2)
            .find_map(|side| index(side, &point).map(|v| [0, meshes[side].0, v, 0, 0, 0]))
            .unwrap_or([u32::MAX; 6]),
        OnLine::Crossing { edge, .. } => (0..2)
            .find_map(|side| {
                let (u, v) = (index(side, &edge[0])?, index(side, &edge[1])?);
                let other = 1 - side;
                Some([
                    5,
                    meshes[side].0,
                    u.min(v),
                    u.max(v),
                    meshes[other].0,
                    faces[other] as u32,
                ])
            })
            .unwrap_or([u32::MAX; 6]),
        OnLine::Cut(_) => [u32::MAX; 6],
    })
}
