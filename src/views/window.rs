//! Windows of a picture: the rectangles a drawing is made in, tile by tile (see
//! [`crate::hidden::tiles`]).

use super::ViewError;
use crate::geometry::exact::ldexp;

/// A rectangle of a view's picture, half open: `x[0] ≤ x < x[1]` and `y[0] ≤ y < y[1]` in
/// picture coordinates ([`Picture`](super::Picture)). A bound may be infinite: the tiles at
/// the edge of a grid reach to infinity on their outer sides, so that a grid of windows covers
/// every point of the picture exactly once.
///
/// ```
/// use kepler::views::Window;
/// let w = Window::new([0.0, 1.0], [f64::NEG_INFINITY, 2.0]).unwrap();
/// assert!(w.contains([0.0, -1e300]) && !w.contains([1.0, 0.0]));
/// assert!(Window::new([1.0, 1.0], [0.0, 1.0]).is_err()); // empty
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// The lower and upper bounds of `x`.
    pub x: [f64; 2],
    /// The lower and upper bounds of `y`.
    pub y: [f64; 2],
}

impl Window {
    /// The whole picture.
    ///
    /// ```
    /// assert!(kepler::views::Window::ALL.contains([1e308, -1e308]));
    /// ```
    pub const ALL: Window = Window {
        x: [f64::NEG_INFINITY, f64::INFINITY],
        y: [f64::NEG_INFINITY, f64::INFINITY],
    };

    /// The window with these bounds: an error unless each lower bound is less than its upper
    /// bound (no NaN).
    ///
    /// ```
    /// assert!(kepler::views::Window::new([0.0, f64::NAN], [0.0, 1.0]).is_err());
    /// ```
    pub fn new(x: [f64; 2], y: [f64; 2]) -> Result<Window, ViewError> {
        if !(x[0] < x[1] && y[0] < y[1]) {
            return Err(ViewError::Options(
                "a window's lower bounds must be less than its upper bounds",
            ));
        }
        Ok(Window { x, y })
    }

    /// Whether the picture point `p` lies in the window.
    ///
    /// ```
    /// let w = kepler::views::Window::new([0.0, 1.0], [0.0, 1.0]).unwrap();
    /// assert!(w.contains([0.0, 0.5]) && !w.contains([0.5, 1.0]));
    /// ```
    pub fn contains(&self, p: [f64; 2]) -> bool {
        self.x[0] <= p[0] && p[0] < self.x[1] && self.y[0] <= p[1] && p[1] < self.y[1]
    }

    /// A grid of `n[0]` by `n[1]` windows over the rectangle from `low` to `high` (row by
    /// row, from the bottom left), split evenly; the outer windows reach to infinity, so the
    /// grid covers the whole picture. Where the rectangle is too thin to split (the splits
    /// would not increase strictly), it has fewer columns or rows. An error for a count of
    /// zero or bounds that are not finite.
    ///
    /// ```
    /// use kepler::views::Window;
    /// let g = Window::grid([0.0, 0.0], [4.0, 2.0], [2, 2]).unwrap();
    /// assert_eq!(g.len(), 4);
    /// assert_eq!(g[0].x, [f64::NEG_INFINITY, 2.0]);
    /// assert_eq!(g[3].y, [1.0, f64::INFINITY]);
    /// assert_eq!(Window::grid([0.0, 0.0], [0.0, 1.0], [3, 1]).unwrap(), vec![Window::ALL]);
    /// ```
    pub fn grid(low: [f64; 2], high: [f64; 2], n: [usize; 2]) -> Result<Vec<Window>, ViewError> {
        if n.contains(&0) {
            return Err(ViewError::Options(
                "a grid of windows needs at least one of each",
            ));
        }
        if !(low.iter().chain(&high).all(|c| c.is_finite())
            && low[0] <= high[0]
            && low[1] <= high[1])
        {
            return Err(ViewError::Options(
                "a grid of windows needs finite bounds, low below high",
            ));
        }
        let cuts = |k: usize| -> Vec<f64> {
            let mut cuts = vec![f64::NEG_INFINITY];
            for i in 1..n[k] {
                let f = i as f64 / n[k] as f64;
                let c = low[k] * (1.0 - f) + high[k] * f;
                if c > *cuts.last().unwrap_or(&f64::NEG_INFINITY) && c < high[k] {
                    cuts.push(c);
                }
            }
            cuts.push(f64::INFINITY);
            cuts
        };
        let (xs, ys) = (cuts(0), cuts(1));
        Ok(ys
            .windows(2)
            .flat_map(|y| {
                xs.windows(2).map(move |x| Window {
                    x: [x[0], x[1]],
                    y: [y[0], y[1]],
                })
            })
            .collect())
    }

    /// The window scaled by `2^exponent` (exactly, but for underflow): the same window of an
    /// orthographic picture of the scene scaled so.
    ///
    /// ```
    /// let w = kepler::views::Window::new([1.0, 3.0], [-2.0, f64::INFINITY]).unwrap();
    /// assert_eq!(w.scaled(1).x, [2.0, 6.0]);
    /// assert_eq!(w.scaled(1).y, [-4.0, f64::INFINITY]);
    /// ```
    pub fn scaled(&self, exponent: i32) -> Window {
        Window {
            x: self.x.map(|c| ldexp(c, exponent)),
            y: self.y.map(|c| ldexp(c, exponent)),
        }
    }
}
