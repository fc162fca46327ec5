//! The traced drawing: the drawing as [`draw`](crate::hidden::draw) makes it, with every piece
//! kept with the 3-D line it lies on, its range of that line's parameter and its visibility.

use super::super::{
    DrawError, Drawing, EdgeClass, Options, Overlaps, Pass, Piece, Result, chained, decided,
    scaled_back,
};
use crate::geometry::Point3;
use crate::geometry::exact::ldexp;
use crate::scene::{ObjectId, Scene};
use crate::sight::meet::Meet;
use crate::sight::range::in_working_range;
use crate::views::View;

/// The 3-D line a piece of a drawing lies on.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{Options, verify::{Source, draw_traced}}};
/// let mut scene = Scene::new();
/// let cube = scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let traced = draw_traced(&scene, &View::standard(), &Options::default(), &|_, _| {}).unwrap();
/// assert!(traced.pieces.iter().all(|p| p.source == Source::Edge { object: cube }));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// An edge of an object's mesh (its ends are input vertices).
    Edge {
        /// The object.
        object: ObjectId,
    },
    /// An intersection line: where two faces, each `(object, face index)`, pierce each other
    /// (its ends are rounded).
    Intersection {
        /// The two faces.
        faces: [(ObjectId, usize); 2],
    },
}

/// A visible or hidden piece of a drawing with the 3-D line it lies on: the piece is the part
/// `t[0] ≤ t ≤ t[1]` of `X(t) = line[0] + t·(line[1] − line[0])`.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{EdgeClass, Options, verify::draw_traced}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let traced = draw_traced(&scene, &View::standard(), &Options::default(), &|_, _| {}).unwrap();
/// // Straight down: four visible silhouette edges on top, four hidden under them.
/// let count = |v| traced.pieces.iter().filter(|p| p.class == EdgeClass::Silhouette && p.visible == v).count();
/// assert_eq!((count(true), count(false)), (4, 4));
/// assert!(traced.pieces.iter().all(|p| p.t == [0.0, 1.0]));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TracedPiece {
    /// The line's provenance.
    pub source: Source,
    /// The line's ends in 3-D.
    pub line: [Point3; 2],
    /// The line's class.
    pub class: EdgeClass,
    /// Whether the piece is visible.
    pub visible: bool,
    /// The piece's range of the line's parameter.
    pub t: [f64; 2],
    /// The pictures of the piece's ends, as drawn.
    pub ends: [[f64; 2]; 2],
    /// For an intersection line: the exact line it lies on (its `line` ends are rounded).
    pub(crate) meet: Option<Meet>,
}

/// A drawing with its pieces traced to their 3-D lines (see [`draw_traced`]).
///
/// ```
/// let t = kepler::hidden::verify::Traced {
///     drawing: kepler::hidden::Drawing { polylines: Vec::new(), stages: Vec::new() },
///     pieces: Vec::new(),
///     kept: None,
/// };
/// assert!(t.pieces.is_empty());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Traced {
    /// The drawing, bit for bit as [`draw`](super::draw) makes it.
    pub drawing: Drawing,
    /// Every piece, hidden ones too (even when the drawing leaves them out), in the pass's
    /// order: by line, then along it.
    pub pieces: Vec<TracedPiece>,
    /// When the drawing draws each stretch of line once ([`Overlaps::Once`]): the pieces
    /// chained as they are, which check 3 compares them with.
    pub kept: Option<Drawing>,
}

/// [`draw_with_progress`](super::draw_with_progress), keeping every piece with its 3-D line.
///
/// ```
/// use kepler::{scene::Scene, views::View, hidden::{Options, draw, verify::draw_traced}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let (view, options) = (View::standard(), Options::default());
/// let traced = draw_traced(&scene, &view, &options, &|_, _| {}).unwrap();
/// assert_eq!(traced.drawing.polylines, draw(&scene, &view, &options).unwrap().polylines);
/// ```
pub fn draw_traced(
    scene: &Scene,
    view: &View,
    options: &Options,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<Traced> {
    let (traced, shift) = in_working_range::<_, DrawError>(scene, view, |scene, view| {
        let (pass, pieces) = decided(scene, view, None, options, progress)?;
        Ok(traced(pass, pieces, options))
    })?;
    // Back to the input's scale, exactly.
    Ok(traced.scaled(-shift, view))
}

impl Traced {
    /// The traced drawing of the scene scaled by `2^shift`, from this one: lines always,
    /// pictures when they scale (orthographic views). Exact while nothing overflows or
    /// underflows.
    pub(super) fn scaled(self, shift: i32, view: &View) -> Traced {
        if shift == 0 {
            return self;
        }
        let pictures = if view.is_perspective() { 0 } else { shift };
        let pieces = self
            .pieces
            .into_iter()
            .map(|p| TracedPiece {
                line: p.line.map(|q| q.map(|c| ldexp(c, shift))),
                ends: p.ends.map(|e| e.map(|c| ldexp(c, pictures))),
                meet: p.meet.map(|m| Meet {
                    planes: m.planes.map(|t| t.map(|q| q.map(|c| ldexp(c, shift)))),
                }),
                ..p
            })
            .collect();
        Traced {
            drawing: scaled_back(self.drawing, view.is_perspective(), -shift),
            pieces,
            kept: self
                .kept
                .map(|d| scaled_back(d, view.is_perspective(), -shift)),
        }
    }
}

/// The drawing of a pass and its pieces, each traced to its line.
fn traced(mut pass: Pass, pieces: Vec<Piece>, options: &Options) -> Traced {
    let mut sources: Vec<Option<Source>> = pass
        .lines
        .iter()
        .map(|l| {
            l.meet.map(|m| Source::Intersection {
                faces: pass.meets[m].on_faces,
            })
        })
        .collect();
    for leaf in &pass.leaves {
        for l in leaf.lines.clone() {
            sources[l] = Some(Source::Edge { object: leaf.id });
        }
    }
    // Every line is an edge of a leaf or an intersection line: no piece is left out.
    let pieces_traced = pieces
        .iter()
        .filter_map(|p| {
            let line = &pass.lines[p.line];
            Some(TracedPiece {
                source: sources[p.line]?,
                line: [line.a, line.b],
                class: p.class,
                visible: p.visible,
                t: p.t,
                ends: p.ends,
                meet: line.meet.map(|m| pass.meets[m].meet),
            })
        })
        .collect();
    // The pieces chained as they are, for check 3, when the drawing draws each stretch once.
    let kept = (options.overlaps == Overlaps::Once).then(|| {
        let stages = pass.stages.clone();
        let keep = Options {
            overlaps: Overlaps::Keep,
            ..*options
        };
        let kept = chained(&mut pass, pieces.clone(), &keep);
        pass.stages = stages;
        kept
    });
    Traced {
        drawing: chained(&mut pass, pieces, options),
        pieces: pieces_traced,
        kept,
    }
}
