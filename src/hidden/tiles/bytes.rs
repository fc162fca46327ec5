//! A tile's pieces as bytes, to travel between processes: every double bit for bit, with
//! what each piece is exactly (its line's support, its ends' cuts), so that [`stitch`]
//! orders and joins pieces, and removes overlaps, by exact predicates on the input.
//!
//! The format (little-endian): the magic `KTILE\0\0\x02`; the working range's shift (`i32`),
//! the projection (`u8`), the eye, the slack (`f64`); the lines (a count, then each line's
//! name, class, support and its ends' keys); the pieces (a count, then each piece's line, flags,
//! parameters, pictures and two marks). A form is a tag and its doubles; a point of a meet
//! line a tag and its points and forms.
//!
//! [`stitch`]: super::stitch

use super::LineId;
use crate::geometry::{Point3, Vector3};
use crate::hidden::marks::MarkKey;
use crate::hidden::{Cut, DrawError, EdgeClass, Result};
use crate::le::{Reader, Writer};
use crate::sight::along::{Form, Zero};
use crate::sight::collinear::Support;
use crate::sight::meet::{Meet, OnLine};
use crate::views::Eye;

/// A line drawn in a tile: its name, class, support and the names of its ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct TileLine {
    pub id: LineId,
    pub class: EdgeClass,
    pub support: Support,
    pub keys: [MarkKey; 2],
}

/// Where a piece of a tile begins or ends: an end of its line, or a cut.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum TileMark {
    First,
    Last,
    Cut(Cut),
}

/// A piece of a line drawn in a tile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct TilePiece {
    /// Its line, by index in the tile's lines.
    pub line: u32,
    pub visible: bool,
    pub ends: [[f64; 2]; 2],
    /// The range of the line's parameter it covers (rough: for nothing exact).
    pub t: [f64; 2],
    /// Whether a window's plane passes through each end.
    pub border: [bool; 2],
    pub marks: [TileMark; 2],
}

/// The pieces of one window of a drawing, ready to be [`stitch`](super::stitch)ed with the
/// other windows of a grid, in the working range of the scene (see `queries/range.rs`;
/// `stitch` scales them back).
///
/// ```
/// use kepler::{scene::Scene, views::{View, Window}, hidden::{Options, tiles::{TileDrawing, draw_tile}}};
/// let mut scene = Scene::new();
/// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
/// let left = Window::new([f64::NEG_INFINITY, 0.5], [f64::NEG_INFINITY, f64::INFINITY]).unwrap();
/// let tile = draw_tile(&scene, &View::standard(), &Options::default(), &left).unwrap();
/// assert!(!tile.is_empty());
/// assert_eq!(TileDrawing::from_bytes(&tile.to_bytes()).unwrap(), tile);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TileDrawing {
    pub(super) lines: Vec<TileLine>,
    pub(super) pieces: Vec<TilePiece>,
    /// The working range's power of two.
    pub(super) shift: i32,
    /// Whether the view is a perspective one (its picture does not scale).
    pub(super) perspective: bool,
    /// The eye the pieces were decided from, in the working range.
    pub(super) eye: Eye,
    /// See [`Provenance::slack`](crate::hidden::marks::Provenance::slack).
    pub(super) slack: f64,
}

/// The first bytes of a tile's bytes, with the format's version.
const MAGIC: &[u8; 8] = b"KTILE\x00\x00\x02";

impl TileDrawing {
    /// How many pieces the tile drew.
    ///
    /// ```
    /// use kepler::{scene::Scene, views::{View, Window}, hidden::{Options, tiles::draw_tile}};
    /// let mut scene = Scene::new();
    /// scene.add_mesh(None, "cube", kepler::solids::cube(2.0).unwrap()).unwrap();
    /// let far = Window::new([100.0, 200.0], [0.0, 1.0]).unwrap();
    /// assert_eq!(draw_tile(&scene, &View::standard(), &Options::default(), &far).unwrap().len(), 0);
    /// ```
    pub fn len(&self) -> usize {
        self.pieces.len()
    }

    /// Whether the tile drew nothing.
    ///
    /// ```
    /// let t = kepler::hidden::tiles::TileDrawing::from_bytes(&kepler::hidden::tiles::TileDrawing::empty().to_bytes()).unwrap();
    /// assert!(t.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// A tile with nothing drawn in it (of an orthographic view in the working range).
    ///
    /// ```
    /// assert!(kepler::hidden::tiles::TileDrawing::empty().is_empty());
    /// ```
    pub fn empty() -> TileDrawing {
        TileDrawing {
            lines: Vec::new(),
            pieces: Vec::new(),
            shift: 0,
            perspective: false,
            eye: Eye::Infinity(Vector3::z()),
            slack: 0.0,
        }
    }

    /// The tile as bytes, to send to another process ([`TileDrawing::from_bytes`] reads
    /// them back; doubles are kept bit for bit, little-endian).
    ///
    /// ```
    /// let b = kepler::hidden::tiles::TileDrawing::empty().to_bytes();
    /// assert_eq!(b.len(), 8 + 4 + 1 + 25 + 8 + 8 + 8);
    /// ```
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut w = Writer(Vec::with_capacity(64 + 200 * self.pieces.len()));
        w.0.extend_from_slice(MAGIC);
        w.0.extend_from_slice(&self.shift.to_le_bytes());
        w.u8(self.perspective as u8);
        w.eye(&self.eye);
        w.f64(self.slack);
        w.u64(self.lines.len() as u64);
        for l in &self.lines {
            w.line(l);
        }
        w.u64(self.pieces.len() as u64);
        for p in &self.pieces {
            w.piece(p);
        }
        w.0
    }

    /// A tile from the bytes of [`TileDrawing::to_bytes`]; an error for bytes that are not
    /// one (or that hold a number that is not finite where the pass never writes one).
    ///
    /// ```
    /// use kepler::hidden::tiles::TileDrawing;
    /// assert!(TileDrawing::from_bytes(b"not a tile").is_err());
    /// ```
    pub fn from_bytes(bytes: &[u8]) -> Result<TileDrawing> {
        let bad = |why: &str| DrawError::Tiles(format!("not a tile's bytes: {why}"));
        let rest = bytes
            .strip_prefix(MAGIC.as_slice())
            .ok_or_else(|| bad("wrong header"))?;
        let mut r = Reader(rest);
        let header = (|| {
            let shift = i32::from_le_bytes(r.take()?);
            let perspective = match r.u8()? {
                0 => false,
                1 => true,
                _ => return None,
            };
            Some((shift, perspective, r.eye()?, r.finite()?))
        })();
        let (shift, perspective, eye, slack) = header.ok_or_else(|| bad("wrong header"))?;
        let count = r.count().ok_or_else(|| bad("too short"))?;
        let mut lines = Vec::with_capacity(count.min(1 << 20));
        for _ in 0..count {
            lines.push(r.line().ok_or_else(|| bad("a line is malformed"))?);
        }
        let count = r.count().ok_or_else(|| bad("too short"))?;
        let mut pieces = Vec::with_capacity(count.min(1 << 20));
        for _ in 0..count {
            let piece = r
                .piece()
                .filter(|p| (p.line as usize) < lines.len())
                .ok_or_else(|| bad("a piece is malformed"))?;
            pieces.push(piece);
        }
        if !r.0.is_empty() {
            return Err(bad("wrong length"));
        }
        Ok(TileDrawing {
            lines,
            pieces,
            shift,
            perspective,
            eye,
            slack,
        })
    }
}

/// A tile's fields, written in order.
impl Writer {
    fn point(&mut self, p: &Point3) {
        for k in 0..3 {
            self.f64(p[k]);
        }
    }

    fn eye(&mut self, eye: &Eye) {
        let (tag, p) = match eye {
            Eye::Point(p) => (0, *p),
            Eye::Infinity(u) => (1, Point3::from(*u)),
        };
        self.u8(tag);
        self.point(&p);
    }

    fn form(&mut self, form: &Form) {
        match form {
            Form::Plane(t) => {
                self.u8(0);
                t.iter().for_each(|p| self.point(p));
            }
            Form::Sight(c, d) => {
                self.u8(1);
                self.point(c);
                self.point(d);
            }
            Form::Frustum(n, offset) => {
                self.u8(2);
                self.point(&Point3::from(*n));
                self.f64(*offset);
            }
        }
    }

    fn on_line(&mut self, p: &OnLine) {
        match p {
            OnLine::Vertex { point, pivot } => {
                self.u8(0);
                self.point(point);
                self.form(pivot);
            }
            OnLine::Crossing { edge, plane, pivot } => {
                self.u8(1);
                edge.iter().for_each(|p| self.point(p));
                self.form(plane);
                self.form(pivot);
            }
            OnLine::Cut(form) => {
                self.u8(2);
                self.form(form);
            }
        }
    }

    fn line(&mut self, l: &TileLine) {
        let (kind, names) = match l.id {
            LineId::Edge(o, k) => (0u8, [o, k, 0]),
            LineId::Meet(o, q, k) => (1u8, [o, q, k]),
        };
        self.u8(kind);
        names.iter().for_each(|&n| self.u32(n));
        self.u8(l.class as u8);
        match &l.support {
            Support::Edge(ends) => {
                self.u8(0);
                ends.iter().for_each(|p| self.point(p));
            }
            Support::Meet { meet, ends } => {
                self.u8(1);
                meet.planes.iter().flatten().for_each(|p| self.point(p));
                ends.iter().for_each(|e| self.on_line(e));
            }
        }
        l.keys.iter().flatten().for_each(|&k| self.u32(k));
    }

    fn mark(&mut self, mark: &TileMark) {
        match mark {
            TileMark::First => self.u8(0),
            TileMark::Last => self.u8(1),
            TileMark::Cut(c) => {
                self.u8(2);
                self.form(&c.zero.form);
                self.u8(c.zero.rising as u8);
                self.f64(c.zero.t);
                self.f64(c.zero.error);
                match c.sighted {
                    Some(p) => {
                        self.u8(1);
                        self.f64(p[0]);
                        self.f64(p[1]);
                    }
                    None => self.u8(0),
                }
                c.key.iter().for_each(|&k| self.u32(k));
            }
        }
    }

    fn piece(&mut self, p: &TilePiece) {
        self.u32(p.line);
        self.u8(p.visible as u8 | (p.border[0] as u8) << 1 | (p.border[1] as u8) << 2);
        for x in p.t.iter().chain(p.ends.iter().flatten()) {
            self.f64(*x);
        }
        p.marks.iter().for_each(|m| self.mark(m));
    }
}

/// A tile's fields, read in order; `None` for what the writer never writes.
impl Reader<'_> {
    /// A double that must be finite (the inputs of exact predicates).
    fn finite(&mut self) -> Option<f64> {
        self.f64().filter(|x| x.is_finite())
    }

    fn point(&mut self) -> Option<Point3> {
        Some(Point3::new(self.finite()?, self.finite()?, self.finite()?))
    }

    fn eye(&mut self) -> Option<Eye> {
        match self.u8()? {
            0 => Some(Eye::Point(self.point()?)),
            1 => Some(Eye::Infinity(self.point()?.coords)),
            _ => None,
        }
    }

    fn form(&mut self) -> Option<Form> {
        match self.u8()? {
            0 => Some(Form::Plane([self.point()?, self.point()?, self.point()?])),
            1 => Some(Form::Sight(self.point()?, self.point()?)),
            2 => Some(Form::Frustum(self.point()?.coords, self.finite()?)),
            _ => None,
        }
    }

    fn on_line(&mut self) -> Option<OnLine> {
        match self.u8()? {
            0 => Some(OnLine::Vertex {
                point: self.point()?,
                pivot: self.form()?,
            }),
            1 => Some(OnLine::Crossing {
                edge: [self.point()?, self.point()?],
                plane: self.form()?,
                pivot: self.form()?,
            }),
            2 => Some(OnLine::Cut(self.form()?)),
            _ => None,
        }
    }

    fn line(&mut self) -> Option<TileLine> {
        let kind = self.u8()?;
        let names = [self.u32()?, self.u32()?, self.u32()?];
        let id = match kind {
            0 => LineId::Edge(names[0], names[1]),
            1 => LineId::Meet(names[0], names[1], names[2]),
            _ => return None,
        };
        let class = self.u8()?;
        let class = *EdgeClass::ALL.iter().find(|c| **c as u8 == class)?;
        let support = match self.u8()? {
            0 => Support::Edge([self.point()?, self.point()?]),
            1 => {
                let mut planes = [[Point3::origin(); 3]; 2];
                for p in planes.iter_mut().flatten() {
                    *p = self.point()?;
                }
                Support::Meet {
                    meet: Meet { planes },
                    ends: [self.on_line()?, self.on_line()?],
                }
            }
            _ => return None,
        };
        let mut keys = [[0u32; 6]; 2];
        for k in keys.iter_mut().flatten() {
            *k = self.u32()?;
        }
        Some(TileLine {
            id,
            class,
            support,
            keys,
        })
    }

    fn mark(&mut self) -> Option<TileMark> {
        match self.u8()? {
            0 => Some(TileMark::First),
            1 => Some(TileMark::Last),
            2 => {
                let form = self.form()?;
                let rising = match self.u8()? {
                    0 => false,
                    1 => true,
                    _ => return None,
                };
                let (t, error) = (self.f64()?, self.f64()?);
                let sighted = match self.u8()? {
                    0 => None,
                    1 => Some([self.f64()?, self.f64()?]),
                    _ => return None,
                };
                let key = [self.u32()?, self.u32()?, self.u32()?, self.u32()?];
                let zero = Zero {
                    form,
                    rising,
                    t,
                    error,
                };
                Some(TileMark::Cut(Cut { zero, sighted, key }))
            }
            _ => None,
        }
    }

    fn piece(&mut self) -> Option<TilePiece> {
        let line = self.u32()?;
        let flags = self.u8()?;
        if flags > 7 {
            return None;
        }
        let t = [self.f64()?, self.f64()?];
        let ends = [[self.f64()?, self.f64()?], [self.f64()?, self.f64()?]];
        Some(TilePiece {
            line,
            visible: flags & 1 != 0,
            ends,
            t,
            border: [flags & 2 != 0, flags & 4 != 0],
            marks: [self.mark()?, self.mark()?],
        })
    }
}
