//! The ten families' layouts: the solids of each scene, by name, and the camera to see them
//! with (see the [module](super) for what each stresses).

use super::Layout;
use super::cameras::{EXACT_DIRECTIONS, generic_view, perspective};
use super::choices::Choices;
use super::shapes::{
    hexahedron, named, outward, parallelepiped, prism, reversed, ten_to_the, tetrahedron,
};
use crate::geometry::exact::ldexp;
use crate::geometry::{Point3, Vector3};
use crate::mesh::Mesh;
use crate::scene::{Camera, Projection};
use crate::solids;

/// A plate sunk into a block, its top tilted `10^-k` about a line in the block's top (so the
/// two tops cross there), and a block in front whose back face is tilted `10^-k` about a
/// vertical line in the block's front face. `k = 16`: both exactly coplanar.
pub(super) fn tilt(k: i32, rng: &mut Choices) -> crate::Result<Layout> {
    let t = if k >= 16 { 0.0 } else { ten_to_the(-k) };
    let (w, y0, h) = (
        rng.eighths(3.0, 4.5),
        rng.eighths(1.0, 1.875),
        rng.eighths(1.0, 1.875),
    );
    let depth = rng.eighths(2.0, 3.0);
    let base = solids::box_between([0.0, y0, 0.0], [w, y0 + depth, h])?;
    // The plate: 2 or 4 wide, its top h ∓ rise at its ends, h at its middle.
    let half = 1.0 + rng.below(2) as f64;
    let xa = rng.eighths(0.25 - half, w - half - 0.25);
    let ya = y0 + rng.eighths(-1.0, 0.5);
    let yb = ya + rng.eighths(1.5, 2.5);
    let bottom = h - rng.eighths(0.5, 0.75);
    let rise = rng.sign() * t * half;
    let plate = hexahedron(std::array::from_fn(|c| {
        let (right, back, top) = (c & 1 != 0, c & 2 != 0, c & 4 != 0);
        let z = match (top, right) {
            (false, _) => bottom,
            (true, false) => h - rise,
            (true, true) => h + rise,
        };
        Point3::new(
            if right { xa + 2.0 * half } else { xa },
            if back { yb } else { ya },
            z,
        )
    }))?;
    // The block in front: 2 wide, its back face y0 ∓ t at its sides.
    let xf = rng.eighths(-0.75, w - 1.25);
    let yf = y0 - rng.eighths(1.0, 2.0);
    let top = rng.eighths(0.75, h + 0.5);
    let lean = rng.sign() * t;
    let front = hexahedron(std::array::from_fn(|c| {
        let (right, back, up) = (c & 1 != 0, c & 2 != 0, c & 4 != 0);
        let y = match (back, right) {
            (false, _) => yf,
            (true, false) => y0 - lean,
            (true, true) => y0 + lean,
        };
        Point3::new(
            if right { xf + 2.0 } else { xf },
            y,
            if up { top } else { 0.0 },
        )
    }))?;
    Ok((
        named([("base", base), ("plate", plate), ("front", front)]),
        generic_view(rng),
    ))
}

/// A needle (a triangular prism about 3.5 long, its cross-section about `4·10^-k`) and a blade
/// (a tetrahedron about 2 across and `2·10^-k` thick), both piercing a box's front face.
pub(super) fn sliver(k: i32, rng: &mut Choices) -> crate::Result<Layout> {
    let h = 4.0 * ten_to_the(-k);
    let (w, y0, depth, height) = (
        rng.eighths(3.0, 4.0),
        rng.eighths(0.5, 1.0),
        rng.eighths(2.0, 3.0),
        rng.eighths(1.5, 2.5),
    );
    let block = solids::box_between([0.0, y0, 0.0], [w, y0 + depth, height])?;
    let o = Point3::new(
        rng.eighths(0.5, w - 1.0),
        y0 - rng.eighths(1.0, 1.5),
        rng.eighths(0.5, height - 0.5),
    );
    let along = Vector3::new(
        rng.eighths(-1.0, 1.0),
        rng.eighths(2.5, 3.5),
        rng.eighths(-0.5, 0.5),
    );
    let needle = prism(
        [
            o,
            o + Vector3::new(h, 0.0, 0.0),
            o + Vector3::new(h / 2.0, 0.0, h),
        ],
        along,
    )?;
    // The blade: one corner inside the box, two in front of it, the fourth just above (or
    // below) a point inside the triangle.
    let z = rng.eighths(0.25, height - 0.25);
    let inner = Point3::new(rng.eighths(1.0, w - 1.0), y0 + rng.eighths(0.5, 1.5), z);
    let left = Point3::new(
        inner.x - rng.eighths(0.5, 1.0),
        y0 - rng.eighths(0.5, 1.5),
        z,
    );
    let right = Point3::new(
        inner.x + rng.eighths(0.5, 1.0),
        y0 - rng.eighths(0.5, 1.5),
        z,
    );
    let middle = (inner.coords + left.coords + 2.0 * right.coords) / 4.0;
    let apex = Point3::new(middle.x, middle.y, z + rng.sign() * h / 2.0);
    let blade = tetrahedron([inner, left, right, apex])?;
    Ok((
        named([("block", block), ("needle", needle), ("blade", blade)]),
        generic_view(rng),
    ))
}

/// A block about 7 wide with three features of size 0.5 to 1.5 on its top (one resting, one
/// sunk, one across its front edge), all moved `10^k` along each axis (the signs by the seed).
/// The features are multiples of 1/8, so every coordinate is exact up to `k = 15`; at
/// `k = 16` the doubles are 2 apart, and the scene is 16 times larger to stay exact.
pub(super) fn offset(k: i32, rng: &mut Choices) -> crate::Result<Layout> {
    let t = 10f64.powi(k);
    let grow = ((t.next_up() - t) * 8.0).max(1.0);
    let origin = [rng.sign() * t, rng.sign() * t, rng.sign() * t];
    let (w, d, h) = (
        rng.eighths(6.0, 7.5),
        rng.eighths(6.0, 7.5),
        rng.eighths(3.0, 4.0),
    );
    let s1 = rng.eighths(0.5, 1.5);
    let (x1, y1) = (rng.eighths(1.0, w - 4.0), rng.eighths(1.0, d - 3.0));
    let s2 = 2.0 * rng.eighths(0.25, 0.75);
    let (x2, y2) = (
        x1 + s1 + rng.eighths(0.25, 1.0),
        y1 + rng.eighths(-0.5, 0.5),
    );
    let s3 = 2.0 * rng.eighths(0.25, 0.75);
    let x3 = rng.eighths(1.0, w - 2.0);
    let boxes = [
        ("block", [0.0, 0.0, 0.0], [w, d, h]),
        ("resting", [x1, y1, h], [x1 + s1, y1 + s1, h + s1]),
        (
            "sunk",
            [x2, y2, h - s2 / 2.0],
            [x2 + s2, y2 + s2, h + s2 / 2.0],
        ),
        (
            "edge",
            [x3, -s3 / 2.0, h - s3 / 2.0],
            [x3 + s3, s3 / 2.0, h + s3 / 2.0],
        ),
    ];
    let at = |c: [f64; 3]| std::array::from_fn(|i| origin[i] + c[i] * grow);
    let objects = boxes
        .into_iter()
        .map(|(name, lo, hi)| Ok((name.to_string(), solids::box_between(at(lo), at(hi))?)))
        .collect::<crate::Result<_>>()?;
    Ok((objects, generic_view(rng)))
}

/// A block pierced by a rod and a spike, a box in front of it, all scaled by `2^k` (exactly);
/// seen orthographically on even seeds, in perspective (the eye scaled too) on odd ones.
pub(super) fn scale(k: i32, rng: &mut Choices, seed_is_odd: bool) -> crate::Result<Layout> {
    let (w, d, h) = (
        rng.eighths(3.0, 4.0),
        rng.eighths(3.0, 4.0),
        rng.eighths(2.0, 3.0),
    );
    let (yr, zr) = (rng.eighths(0.5, d - 1.5), rng.eighths(0.5, h - 1.5));
    let rod = (
        [-1.0, yr, zr],
        [
            w + 1.0,
            yr + rng.eighths(0.5, 1.0),
            zr + rng.eighths(0.5, 1.0),
        ],
    );
    // The spike's apex stands above the block; its base, inside, is a triangle around the
    // apex's foot.
    let (xt, yt) = (rng.eighths(1.0, w - 1.0), rng.eighths(1.0, d - 1.0));
    let spike = [
        [xt, yt, h + rng.eighths(0.75, 1.5)],
        [
            xt - rng.eighths(0.5, 1.0),
            yt - rng.eighths(0.25, 0.75),
            h - rng.eighths(0.5, 1.0),
        ],
        [
            xt + rng.eighths(0.5, 1.0),
            yt - rng.eighths(0.25, 0.75),
            h - rng.eighths(0.5, 1.0),
        ],
        [
            xt + rng.eighths(-0.25, 0.25),
            yt + rng.eighths(0.5, 1.0),
            h - rng.eighths(0.5, 1.0),
        ],
    ];
    let xf = rng.eighths(-0.5, w - 2.0);
    let front = (
        [xf, -rng.eighths(2.0, 3.0), 0.0],
        [
            xf + rng.eighths(1.5, 2.5),
            -rng.eighths(0.5, 1.0),
            rng.eighths(1.0, 2.0),
        ],
    );
    let s = |c: [f64; 3]| c.map(|x| ldexp(x, k));
    let p = |c: [f64; 3]| Point3::from(s(c));
    let camera = if seed_is_odd {
        let centre = [w / 2.0, d / 2.0, h / 2.0];
        let eye = [
            centre[0] + rng.sign() * rng.eighths(4.0, 8.0),
            centre[1] - rng.eighths(10.0, 14.0),
            centre[2] + rng.eighths(6.0, 10.0),
        ];
        perspective(s(eye), s(centre))
    } else {
        generic_view(rng)
    };
    Ok((
        named([
            ("block", solids::box_between(s([0.0; 3]), s([w, d, h]))?),
            ("rod", solids::box_between(s(rod.0), s(rod.1))?),
            ("spike", tetrahedron(spike.map(p))?),
            ("front", solids::box_between(s(front.0), s(front.1))?),
        ]),
        camera,
    ))
}

/// Seen along an exact direction `d`: a prism along `d` (faces edge-on, edges end-on), a slab
/// with two faces containing `d` but no edge along it, piercing the prism, a slab behind whose
/// faces are `10^-k` from containing `d`, and a floor.
pub(super) fn edge_on(k: i32, rng: &mut Choices) -> crate::Result<Layout> {
    let d = rng.pick(&EXACT_DIRECTIONS);
    let half = Vector3::from(d) / 2.0;
    let eps = ten_to_the(-k);
    let floor = solids::box_between([-3.5, -2.0, -2.0], [3.5, 4.0, -1.5])?;
    let o = Point3::new(
        rng.eighths(-2.5, -1.5),
        rng.eighths(-1.5, -1.0),
        rng.eighths(-1.25, -0.75),
    );
    let across = Vector3::new(rng.eighths(1.0, 1.5), rng.eighths(-0.25, 0.25), 0.0);
    let up = Vector3::new(rng.eighths(-0.25, 0.25), 0.0, rng.eighths(1.25, 1.75));
    let prism = parallelepiped(o, [half, across, up])?;
    // A corner inside the prism, the slab reaching out of it.
    let inside = o + half / 2.0 + across / 2.0 + up / 4.0;
    let g = Vector3::new(rng.eighths(0.5, 1.0), 0.0, rng.eighths(-0.25, 0.25));
    let rise = Vector3::new(
        rng.eighths(-0.25, 0.25),
        rng.eighths(-0.25, 0.25),
        rng.eighths(1.0, 1.5),
    );
    let slab = parallelepiped(inside, [half + g, half - g, rise])?;
    let behind = o + Vector3::new(
        rng.eighths(0.5, 1.5),
        rng.eighths(1.5, 2.5),
        rng.eighths(-0.25, 0.5),
    );
    let g2 = Vector3::new(rng.eighths(0.5, 1.0), 0.0, 0.0);
    let tilted = parallelepiped(
        behind,
        [half + g2 + Vector3::new(0.0, 0.0, eps), half - g2, rise],
    )?;
    let camera = Camera {
        projection: Projection::Orthographic { direction: d },
        up: [0.0, 0.0, 1.0],
    };
    Ok((
        named([
            ("floor", floor),
            ("prism", prism),
            ("slab", slab),
            ("tilted", tilted),
        ]),
        camera,
    ))
}

/// A cone of `2^k` triangles standing on a floor (closed by its base, a polygon of `2^k`
/// sides, on half the seeds; open, its rim on the floor, on the others), a bar through it
/// below the apex and, on half the seeds, a post whose vertical edge passes exactly through the
/// apex; the eye above looks at a point 1/8 from the apex.
pub(super) fn fan(k: i32, rng: &mut Choices) -> crate::Result<Layout> {
    let (ax, ay, height) = (
        rng.eighths(-0.5, 0.5),
        rng.eighths(-0.5, 0.5),
        rng.eighths(2.5, 3.5),
    );
    let radius = rng.eighths(1.5, 2.5);
    // The base: 2^k points of the circle, from exact rational points of its first quarter
    // (t = j/m, the point ((1 − t²)/(1 + t²), 2t/(1 + t²)), rounded the same way everywhere,
    // unlike sines) turned by quarter turns, which are exact.
    let m = 1u32 << (k - 2);
    let quarter: Vec<(f64, f64)> = (0..m)
        .map(|j| {
            let t = f64::from(j) / f64::from(m);
            let n = 1.0 + t * t;
            (radius * ((1.0 - t * t) / n), radius * (2.0 * t / n))
        })
        .collect();
    let mut vertices = vec![Point3::new(ax, ay, height)];
    for turn in 0..4 {
        vertices.extend(quarter.iter().map(|&(x, y)| {
            let (x, y) = match turn {
                0 => (x, y),
                1 => (-y, x),
                2 => (-x, -y),
                _ => (y, -x),
            };
            Point3::new(x, y, 0.0)
        }));
    }
    let n = 4 * m;
    let mut faces: Vec<Vec<u32>> = (0..n).map(|i| vec![1 + i, 1 + (i + 1) % n, 0]).collect();
    let cone = if rng.below(2) == 0 {
        faces.push((1..=n).rev().collect());
        outward(Mesh::from_polygons(vertices, faces)?)?
    } else {
        Mesh::from_polygons(vertices, faces)?
    };
    let floor = solids::box_between([-3.0, -3.0, -0.5], [3.0, 3.0, 0.0])?;
    let zb = rng.eighths(height / 2.0, height - 0.75);
    let yb = ay - rng.eighths(0.125, 0.375);
    let bar = solids::box_between(
        [-3.0, yb, zb],
        [
            3.0,
            yb + rng.eighths(0.25, 0.5),
            zb + rng.eighths(0.25, 0.5),
        ],
    )?;
    let mut objects = named([("floor", floor), ("cone", cone), ("bar", bar)]);
    if rng.below(2) == 0 {
        let post = solids::box_between(
            [ax, ay, height - 0.75],
            [ax + 0.375, ay + 0.375, height + 0.5],
        )?;
        objects.push(("post".to_string(), post));
    }
    let eye = [
        ax + rng.eighths(-1.5, 1.5),
        ay - rng.eighths(2.0, 3.0),
        height + rng.eighths(3.5, 5.0),
    ];
    Ok((
        objects,
        perspective(eye, [ax + rng.sign() / 8.0, ay, height]),
    ))
}

/// An outer box with 2 to 4 boxes nested in it, each face of each inset by 0, 1, 2 or 3 times
/// `10^-k` or by 1/8 to 1/4; a rod through them all, a lid resting on the outer box and a box
/// against its side; seen in perspective.
pub(super) fn nested(k: i32, rng: &mut Choices) -> crate::Result<Layout> {
    let g = ten_to_the(-k);
    let mut lo = [
        rng.eighths(-2.0, -1.5),
        rng.eighths(-1.5, -1.0),
        rng.eighths(-1.5, -1.0),
    ];
    let mut hi = lo.map(|c| c + rng.eighths(2.5, 3.25));
    let (outer_lo, outer_hi) = (lo, hi);
    let mut objects = vec![("outer".to_string(), solids::box_between(lo, hi)?)];
    let levels = 2 + rng.below(3);
    let mut inset = || match rng.below(5) {
        4 => rng.eighths(0.125, 0.25),
        m => m as f64 * g,
    };
    for level in 1..=levels {
        for i in 0..3 {
            lo[i] += inset();
            hi[i] -= inset();
        }
        objects.push((format!("inner{level}"), solids::box_between(lo, hi)?));
    }
    // Through the middle, which every nested box contains.
    let mid = |i: usize| ((outer_lo[i] + outer_hi[i]) * 4.0).floor() / 8.0;
    let rod = solids::box_between(
        [outer_lo[0] - 1.0, mid(1) - 0.125, mid(2) - 0.125],
        [outer_hi[0] + 1.0, mid(1) + 0.125, mid(2) + 0.125],
    )?;
    let s = rng.eighths(0.5, 1.0);
    let (xl, yl) = (
        rng.eighths(outer_lo[0], outer_hi[0] - 0.5),
        rng.eighths(outer_lo[1], outer_hi[1] - 0.5),
    );
    let lid = solids::box_between([xl, yl, outer_hi[2]], [xl + s, yl + s, outer_hi[2] + s])?;
    let zs = rng.eighths(outer_lo[2], outer_hi[2] - 0.75);
    let side = solids::box_between(
        [outer_lo[0] - 0.75, outer_lo[1] + 0.5, zs],
        [outer_lo[0], outer_lo[1] + 1.25, zs + 0.75],
    )?;
    objects.extend(named([("rod", rod), ("lid", lid), ("side", side)]));
    let centre = [0, 1, 2].map(mid);
    let eye = [
        centre[0] + rng.sign() * rng.eighths(4.0, 6.0),
        centre[1] - rng.eighths(7.0, 9.0),
        centre[2] + rng.eighths(4.0, 6.0),
    ];
    Ok((objects, perspective(eye, centre)))
}

/// Boxes in the cells of a 3 × 2 × 2 grid (each cell taken with probability 2/3), neighbours
/// touching or apart by `10^-k` or `2·10^-k` along each axis, and a tetrahedron standing on
/// the top of one with a corner at the box's corner; seen in perspective.
pub(super) fn touching(k: i32, rng: &mut Choices) -> crate::Result<Layout> {
    let g = ten_to_the(-k);
    let cells = [3, 2, 2];
    let start = [-2.25, -1.5, -1.25];
    // Along each axis, where each cell starts and how long it is.
    let axes: Vec<Vec<(f64, f64)>> = (0..3)
        .map(|i| {
            let mut at = start[i];
            (0..cells[i])
                .map(|_| {
                    let cell = (at, rng.eighths(1.0, 1.5));
                    at += cell.1 + g * rng.below(3) as f64;
                    cell
                })
                .collect()
        })
        .collect();
    let mut chosen: Vec<[usize; 3]> = Vec::new();
    for x in 0..cells[0] {
        for y in 0..cells[1] {
            for z in 0..cells[2] {
                if rng.below(3) != 0 || chosen.len() + (12 - 4 * x - 2 * y - z) <= 3 {
                    chosen.push([x, y, z]);
                }
            }
        }
    }
    let mut objects = Vec::new();
    for c in &chosen {
        let lo: [f64; 3] = std::array::from_fn(|i| axes[i][c[i]].0);
        let hi: [f64; 3] = std::array::from_fn(|i| axes[i][c[i]].0 + axes[i][c[i]].1);
        objects.push((
            format!("box{}{}{}", c[0], c[1], c[2]),
            solids::box_between(lo, hi)?,
        ));
    }
    // On the highest chosen box, at its corner of smallest x and y.
    let top = chosen
        .iter()
        .max_by_key(|c| c[2])
        .copied()
        .unwrap_or([0; 3]);
    let (x, y) = (axes[0][top[0]].0, axes[1][top[1]].0);
    let z = axes[2][top[2]].0 + axes[2][top[2]].1;
    let (a, b) = (rng.eighths(0.5, 1.0), rng.eighths(0.5, 1.0));
    let tetra = tetrahedron([
        Point3::new(x, y, z),
        Point3::new(x + a, y, z),
        Point3::new(x, y + b, z),
        Point3::new(x + a / 4.0, y + b / 4.0, z + rng.eighths(0.5, 1.0)),
    ])?;
    objects.push(("tetra".to_string(), tetra));
    let eye = [
        rng.sign() * rng.eighths(4.0, 6.0),
        -rng.eighths(7.0, 9.0),
        rng.eighths(5.0, 7.0),
    ];
    Ok((objects, perspective(eye, [0.0; 3])))
}

/// The block of the tangent and inside-out families and its width, front, depth and height:
/// `[0, w] × [y0, y0 + d] × [0, h]`.
pub(super) fn block(rng: &mut Choices) -> crate::Result<(Mesh, [f64; 4])> {
    let (w, y0, d, h) = (
        rng.eighths(3.0, 3.75),
        rng.eighths(0.0, 0.5),
        rng.eighths(2.5, 3.0),
        rng.eighths(1.5, 2.0),
    );
    Ok((
        solids::box_between([0.0, y0, 0.0], [w, y0 + d, h])?,
        [w, y0, d, h],
    ))
}

/// A block with a box sunk `10^-k` into its top, one pressed `10^-k` into its front face, and
/// two tetrahedra whose lowest edge runs `10^-k` below and `10^-k` above its top.
pub(super) fn tangent(k: i32, rng: &mut Choices) -> crate::Result<Layout> {
    let g = ten_to_the(-k);
    let (block, [w, y0, d, h]) = block(rng)?;
    let (xs, ys) = (
        rng.eighths(w - 1.25, w - 0.5),
        rng.eighths(y0 + 0.5, y0 + 1.25),
    );
    let sunk = solids::box_between(
        [xs, ys, h - g],
        [
            xs + rng.eighths(1.0, 1.5),
            ys + rng.eighths(1.0, 1.5),
            h - g + rng.eighths(0.5, 1.0),
        ],
    )?;
    let (xp, zp) = (rng.eighths(0.25, 1.25), rng.eighths(0.25, h - 1.0));
    let pressed = solids::box_between(
        [xp, y0 - rng.eighths(0.5, 1.0), zp],
        [
            xp + rng.eighths(0.75, 1.25),
            y0 + g,
            zp + rng.eighths(0.5, 0.75),
        ],
    )?;
    let at = Point3::new(
        rng.eighths(0.25, 1.0),
        rng.eighths(y0 + 1.5, y0 + d - 0.5),
        h - g,
    );
    let below = wedge(rng, at)?;
    let at = Point3::new(rng.eighths(0.25, 1.0), y0 + 0.75, h + g);
    let above = wedge(rng, at)?;
    Ok((
        named([
            ("block", block),
            ("sunk", sunk),
            ("pressed", pressed),
            ("grazing-in", below),
            ("grazing-out", above),
        ]),
        generic_view(rng),
    ))
}

/// A block; a box turned inside out, through the block's side, its top `10^-k` above or below
/// the block's; a tetrahedron turned inside out through the block's front face; an outward box
/// in front, `10^-k` from the front face.
pub(super) fn inside_out(k: i32, rng: &mut Choices) -> crate::Result<Layout> {
    let g = ten_to_the(-k);
    let (block, [w, y0, _, h]) = block(rng)?;
    let (xb, yb, zb) = (
        rng.eighths(w - 1.0, w - 0.5),
        rng.eighths(y0 + 0.25, y0 + 1.0),
        rng.eighths(0.25, h - 0.75),
    );
    let inverted_box = reversed(&solids::box_between(
        [xb, yb, zb],
        [
            xb + rng.eighths(1.5, 2.0),
            yb + rng.eighths(1.0, 1.5),
            h + rng.sign() * g,
        ],
    )?)?;
    let (xc, zc) = (rng.eighths(0.75, w - 1.5), rng.eighths(0.5, h - 0.75));
    let inverted_tetra = reversed(&tetrahedron([
        Point3::new(xc, y0 + rng.eighths(0.5, 1.0), zc),
        Point3::new(xc - 0.5, y0 - 1.0, zc - rng.eighths(0.25, 0.5)),
        Point3::new(xc + 0.5, y0 - 1.0, zc - rng.eighths(0.25, 0.5)),
        Point3::new(xc, y0 - 0.75, zc + 0.5),
    ])?)?;
    let xf = rng.eighths(-0.5, w - 1.5);
    let front = solids::box_between(
        [xf, y0 - rng.eighths(0.75, 1.25), 0.0],
        [xf + rng.eighths(1.0, 1.5), y0 - g, rng.eighths(0.5, 1.0)],
    )?;
    Ok((
        named([
            ("block", block),
            ("inverted-box", inverted_box),
            ("inverted-tetra", inverted_tetra),
            ("front", front),
        ]),
        generic_view(rng),
    ))
}

/// A wedge: a tetrahedron whose lowest edge runs from `a` along `x` (1 to 1.5 long), its other
/// two corners above the edge's middle, one on each side.
pub(super) fn wedge(rng: &mut Choices, a: Point3) -> crate::Result<Mesh> {
    let length = rng.eighths(1.0, 1.5);
    let b = Point3::new(a.x + length, a.y + rng.eighths(-0.25, 0.25), a.z);
    let up = a.z + rng.eighths(0.5, 0.75);
    let xm = a.x + length / 2.0;
    let c = Point3::new(xm, a.y - rng.eighths(0.25, 0.5), up);
    let e = Point3::new(xm, a.y + rng.eighths(0.25, 0.5), up);
    tetrahedron([a, b, c, e])
}
