//! The arithmetic is a property of threads, not of the process (issue 28): the error report's
//! cheaper arithmetic runs on threads of its own, and every other thread stays exact while it
//! runs.

use kepler::geometry::arithmetic::{Arithmetic, builds_exactly, count_filters, with_arithmetic};
use kepler::geometry::kernel::Polynomial;
use kepler::geometry::predicates::Orient2d;
use std::cmp::Ordering;
use std::sync::atomic::{AtomicBool, Ordering::Relaxed};

/// The orientations of 256 points within a few ulps of the line through (12, 12) and
/// (24, 24) (Kettner et al.'s classroom example): plain doubles get many of them wrong.
fn stiff() -> Vec<Ordering> {
    let step = f64::EPSILON / 2.0;
    (0..256)
        .map(|k| {
            let p = [
                0.5 + f64::from(k % 16) * step,
                0.5 + f64::from(k / 16) * step,
            ];
            Orient2d([p, [12.0, 12.0], [24.0, 24.0]]).sign()
        })
        .collect()
}

/// The issue-28 case: exact calls on one thread while another runs a cheaper arithmetic
/// for as long as the exact one works: every exact answer stays exact, and the cheaper
/// one really was cheaper (it answers differently).
#[test]
fn an_exact_call_is_exact_while_another_thread_runs_floats() {
    let exact = stiff();
    let (started, done) = (AtomicBool::new(false), AtomicBool::new(false));
    std::thread::scope(|s| {
        let floats = s.spawn(|| {
            with_arithmetic(Arithmetic::Float, || {
                let mut answers = vec![stiff()];
                started.store(true, Relaxed);
                while !done.load(Relaxed) {
                    answers.push(stiff());
                }
                answers
            })
        });
        while !started.load(Relaxed) {
            std::hint::spin_loop();
        }
        for _ in 0..2_000 {
            assert!(kepler::geometry::arithmetic::arithmetic() == Arithmetic::Exact);
            assert_eq!(stiff(), exact);
            assert!(builds_exactly());
        }
        done.store(true, Relaxed);
        let answers = floats.join().unwrap();
        assert!(
            answers.iter().all(|a| *a != exact),
            "floats agreed with the exact signs"
        );
    });
    assert_eq!(stiff(), exact);
}

#[test]
fn counts_are_those_of_the_work_alone() {
    let (_, first) = count_filters(stiff);
    let (_, second) = count_filters(|| (stiff(), stiff()));
    assert_eq!(first.calls * 2, second.calls);
    assert_eq!(first.misses * 2, second.misses);
    assert!(first.misses >= 1);
}

/// A drawing made while another thread draws the same scene in plain floats (as the error
/// report does) is the drawing made alone, bit for bit.
#[test]
fn an_exact_draw_beside_a_float_draw_is_the_drawing_made_alone() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/solids.toml");
    let scene = kepler::load(std::path::Path::new(path)).unwrap();
    let view =
        kepler::View::orthographic(kepler::Vector3::new(-1.0, -2.0, -3.0), kepler::Vector3::z())
            .unwrap();
    let options = kepler::Options::default();
    let alone = kepler::draw(&scene, &view, &options).unwrap();
    let done = AtomicBool::new(false);
    std::thread::scope(|s| {
        s.spawn(|| {
            with_arithmetic(Arithmetic::Float, || {
                while !done.load(Relaxed) {
                    kepler::draw(&scene, &view, &options).unwrap();
                }
            })
        });
        for _ in 0..5 {
            let beside = kepler::draw(&scene, &view, &options).unwrap();
            assert_eq!(beside.polylines, alone.polylines);
        }
        done.store(true, Relaxed);
    });
}
