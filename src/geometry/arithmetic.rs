//! Which arithmetic decides a sign and builds a point: the engine's exact one, or, for the
//! error report only, a cheaper one run on threads of its own.
//!
//! The error report (`kepler report`) measures what exactness buys by running the engine's
//! algorithms unchanged under plain `f64`, a tolerance or `f32`. The arithmetic is a property
//! of the *threads* the work runs on, never of the process: [`with_arithmetic`] builds a
//! thread pool whose workers are set to that arithmetic when they start, and runs the work on
//! it (the engine's parallel steps then run on the same workers). Every other thread, the
//! caller's and rayon's global pool included, stays exact, so an exact call is exact whatever
//! else runs in the process.
//!
//! Why threads and not a type parameter: the filter behind every sign
//! ([`Estimate::sign`](super::estimate::Estimate::sign)) is called from hundreds of
//! predicates and constructions; threading a kernel type through all of them, the pass and
//! the picture would make the whole engine generic over a concern that only the lab's
//! measurement has. A worker's setting is read only while some thread runs another
//! arithmetic (a shared count of such threads, [`others_running`], keeps the exact path
//! free of even that read), so the exact engine pays nothing.
//!
//! ```
//! use kepler::geometry::arithmetic::{Arithmetic, with_arithmetic};
//! use kepler::geometry::estimate::Estimate;
//! use std::cmp::Ordering;
//! let tiny = Estimate { value: 1e-20, bound: 1e-18 };
//! assert_eq!(tiny.sign(), None); // exact: the expansion must decide
//! assert_eq!(with_arithmetic(Arithmetic::Float, || tiny.sign()), Some(Ordering::Greater));
//! let tolerance = Arithmetic::Tolerance(1e-6);
//! assert_eq!(with_arithmetic(tolerance, || tiny.sign()), Some(Ordering::Equal));
//! assert_eq!(tiny.sign(), None); // and this thread was exact all along
//! ```

use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

/// The arithmetic that decides the engine's signs and builds its points: exact, or one of the
/// cheaper ones that the error report (`kepler report`, issue 15) measures against it. Every
/// filter of the kernel ([`Estimate::sign`](super::estimate::Estimate::sign)) and every
/// constructed point of a drawing consults its thread's, so the engine's algorithms run
/// unchanged and only the arithmetic differs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Arithmetic {
    /// The engine's: every sign certified or decided exactly, every point rounded once from
    /// exact values.
    Exact,
    /// Plain `f64`: a sign is the sign of the rounded value (zero when it is zero), a point
    /// is the same formula evaluated in `f64`, as an engine without exact predicates computes
    /// them.
    Float,
    /// `f64` with a tolerance, as most CAD and plotting engines decide: a value within `ε`
    /// times the magnitude of its terms is zero (the magnitude is read off the estimate's
    /// bound, a few roundoffs of it); points as [`Float`](Self::Float).
    Tolerance(f64),
    /// Single precision for the points, as GPU and game engines build them: each constructed
    /// coordinate evaluated in `f32`. Signs as [`Float`](Self::Float) (the report also rounds
    /// the scene's coordinates to `f32`; the `f64` signs make this a lower bound on a pure
    /// `f32` engine's error).
    Single,
}

/// A thread's arithmetic: an [`Arithmetic`], or the exact one with its filters counted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Mode {
    /// [`Arithmetic::Exact`].
    Exact,
    /// Exact, counting filter calls and misses ([`count_filters`]).
    Counted,
    /// [`Arithmetic::Float`].
    Float,
    /// [`Arithmetic::Tolerance`].
    Tolerance(f64),
    /// [`Arithmetic::Single`].
    Single,
}

impl From<Arithmetic> for Mode {
    fn from(arithmetic: Arithmetic) -> Mode {
        match arithmetic {
            Arithmetic::Exact => Mode::Exact,
            Arithmetic::Float => Mode::Float,
            Arithmetic::Tolerance(e) => Mode::Tolerance(e),
            Arithmetic::Single => Mode::Single,
        }
    }
}

thread_local! {
    /// This thread's arithmetic: exact unless the thread is a worker of [`with_arithmetic`]
    /// or [`count_filters`].
    static MODE: Cell<Mode> = const { Cell::new(Mode::Exact) };
    /// This thread's filter calls and misses, while counting.
    static COUNTS: Cell<FilterCounts> = const { Cell::new(FilterCounts { calls: 0, misses: 0 }) };
}

/// How many threads run under a mode other than the plain exact one. Not a setting: only a
/// hint that lets every exact thread skip reading its own mode while there are none.
static OTHERS: AtomicUsize = AtomicUsize::new(0);

/// Whether some thread of the process runs under a mode other than the plain exact one (then
/// the filters read their own thread's [`mode`]).
#[inline]
pub(super) fn others_running() -> bool {
    OTHERS.load(Relaxed) != 0
}

/// This thread's mode.
#[inline]
pub(super) fn mode() -> Mode {
    if others_running() {
        MODE.with(Cell::get)
    } else {
        Mode::Exact
    }
}

/// Counts one filter call on this thread (a miss when the filter could not decide).
pub(super) fn count_filter(miss: bool) {
    COUNTS.with(|c| {
        let FilterCounts { calls, misses } = c.get();
        c.set(FilterCounts {
            calls: calls + 1,
            misses: misses + u64::from(miss),
        });
    });
}

/// This thread's arithmetic (see [`with_arithmetic`]); [`Arithmetic::Exact`] while filters are
/// being counted.
///
/// ```
/// use kepler::geometry::arithmetic::{Arithmetic, arithmetic};
/// assert_eq!(arithmetic(), Arithmetic::Exact);
/// ```
pub fn arithmetic() -> Arithmetic {
    match mode() {
        Mode::Exact | Mode::Counted => Arithmetic::Exact,
        Mode::Float => Arithmetic::Float,
        Mode::Tolerance(e) => Arithmetic::Tolerance(e),
        Mode::Single => Arithmetic::Single,
    }
}

/// Runs `f` on a thread pool of its own, as many threads as rayon's global pool, whose
/// workers all run under `mode`; returns its result and the filter counts of those workers.
/// The pool's threads leave the count of [`OTHERS`] when they end.
///
/// # Panics
/// If the operating system cannot start the pool's threads (no input causes that).
fn run_in<T: Send>(mode: Mode, f: impl FnOnce() -> T + Send) -> (T, FilterCounts) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(rayon::current_num_threads())
        .thread_name(|i| format!("kepler-arithmetic-{i}"))
        .start_handler(move |_| {
            MODE.with(|m| m.set(mode));
            OTHERS.fetch_add(1, Relaxed);
        })
        .exit_handler(|_| {
            OTHERS.fetch_sub(1, Relaxed);
        })
        .build()
        .unwrap_or_else(|e| panic!("cannot start the threads of another arithmetic: {e}"));
    let result = pool.install(f);
    let counts = pool
        .broadcast(|_| COUNTS.with(Cell::take))
        .into_iter()
        .fold(FilterCounts::default(), |sum, c| FilterCounts {
            calls: sum.calls + c.calls,
            misses: sum.misses + c.misses,
        });
    (result, counts)
}

/// Runs `f` with `arithmetic` deciding every sign and building every point of the engine,
/// on threads of its own (see the [module documentation](self)): the calling thread and every
/// other stay exact, also while `f` runs. This is the error report's tool; the engine never
/// calls it. [`Arithmetic::Exact`] runs `f` on the calling thread.
///
/// ```
/// use kepler::geometry::arithmetic::{Arithmetic, arithmetic, with_arithmetic};
/// assert_eq!(with_arithmetic(Arithmetic::Single, arithmetic), Arithmetic::Single);
/// assert_eq!(arithmetic(), Arithmetic::Exact);
/// ```
///
/// # Panics
/// If the operating system cannot start threads.
pub fn with_arithmetic<T: Send>(arithmetic: Arithmetic, f: impl FnOnce() -> T + Send) -> T {
    if arithmetic == Arithmetic::Exact {
        return f();
    }
    run_in(Mode::from(arithmetic), f).0
}

/// How often the kernel's filters ran and how often they could not decide, so that the exact
/// (slow) path ran: see [`count_filters`].
///
/// ```
/// let c = kepler::geometry::arithmetic::FilterCounts { calls: 200, misses: 3 };
/// assert_eq!(c.share(), 0.015);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FilterCounts {
    /// Filter calls ([`Estimate::sign`](super::estimate::Estimate::sign)).
    pub calls: u64,
    /// Calls whose estimate could not certify a sign.
    pub misses: u64,
}

impl FilterCounts {
    /// The share of calls that needed the exact path (0 without calls).
    pub fn share(&self) -> f64 {
        if self.calls == 0 {
            0.0
        } else {
            self.misses as f64 / self.calls as f64
        }
    }
}

/// Runs `f` in the exact arithmetic on threads of its own, counting the kernel's filter calls
/// and misses on them (slower than plain exact runs: each call updates its thread's counts).
///
/// ```
/// use kepler::geometry::arithmetic::count_filters;
/// use kepler::geometry::{Point3, predicates::orient3d};
/// let p = |x, y, z| Point3::new(x, y, z);
/// let ((), counts) = count_filters(|| {
///     orient3d(&p(0.0, 0.0, 0.0), &p(1.0, 0.0, 0.0), &p(0.0, 1.0, 0.0), &p(0.0, 0.0, 1.0));
///     orient3d(&p(0.0, 0.0, 0.0), &p(1.0, 0.0, 0.0), &p(0.0, 1.0, 0.0), &p(0.3, 0.3, 0.0));
/// });
/// assert_eq!((counts.calls, counts.misses), (2, 1));
/// ```
///
/// # Panics
/// If the operating system cannot start threads.
pub fn count_filters<T: Send>(f: impl FnOnce() -> T + Send) -> (T, FilterCounts) {
    run_in(Mode::Counted, f)
}

/// Whether this thread builds its points exactly (each coordinate the exact value rounded
/// once): so unless it runs under a cheaper [`Arithmetic`].
///
/// ```
/// assert!(kepler::geometry::arithmetic::builds_exactly());
/// ```
#[inline]
pub fn builds_exactly() -> bool {
    matches!(mode(), Mode::Exact | Mode::Counted)
}

/// Whether this thread builds its points in `f32` ([`Arithmetic::Single`]).
#[inline]
pub(super) fn builds_in_single() -> bool {
    mode() == Mode::Single
}

/// `Σ row[i]·(p[i] − origin[i])` as this thread's cheaper [`Arithmetic`] evaluates it (a
/// coordinate of a picture): in `f64`, or `f32` for [`Arithmetic::Single`].
///
/// ```
/// use kepler::geometry::arithmetic::plain_dot;
/// assert_eq!(plain_dot(&[1.0, 2.0, 0.0], &[3.0, 4.0, 5.0], &[1.0, 1.0, 1.0]), 8.0);
/// ```
pub fn plain_dot(row: &[f64; 3], p: &[f64; 3], origin: &[f64; 3]) -> f64 {
    if builds_in_single() {
        let term = |i: usize| row[i] as f32 * (p[i] as f32 - origin[i] as f32);
        f64::from(term(0) + term(1) + term(2))
    } else {
        let term = |i: usize| row[i] * (p[i] - origin[i]);
        term(0) + term(1) + term(2)
    }
}
