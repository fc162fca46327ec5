//! The working range: where the kernel's expansions are exact.
//!
//! A scene whose coordinates (with a perspective eye) fall outside the kernel's window,
//! `2⁻⁶⁰` to `2¹⁰⁰` ([`Exponents::WINDOW`]), is worked on scaled into it by an exact power of
//! two, and its results are scaled back: every sign and every rounded construction of the
//! scaled inputs is that of the inputs, scaled, so the results are the same bits, scaled (a
//! perspective picture does not scale at all). Both drawing layers, `hidden` and `surfaces`,
//! work this way.
//!
//! [`Exponents::WINDOW`]: crate::geometry::kernel::Exponents::WINDOW

use crate::scene::{Scene, SceneError};
use crate::views::View;

/// `work` on the scene and view brought into the kernel's working range by a power of two,
/// `2^shift`, with that shift (0 when they are in it already).
pub(crate) fn in_working_range<T, E: From<SceneError>>(
    scene: &Scene,
    view: &View,
    work: impl FnOnce(&Scene, &View) -> Result<T, E>,
) -> Result<(T, i32), E> {
    let shift = working_shift(scene, view);
    if shift == 0 {
        return Ok((work(scene, view)?, 0));
    }
    Ok((work(&scene.scaled(shift)?, &view.scaled(shift))?, shift))
}

/// The power of two, `2^shift`, by which [`in_working_range`] scales the scene and view.
pub(crate) fn working_shift(scene: &Scene, view: &View) -> i32 {
    scene.exponents().union(view.exponents()).shift()
}
