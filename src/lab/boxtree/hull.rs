//! The convex hull of points in space as a closed triangulated surface: randomized incremental
//! construction with conflict lists (Clarkson and Shor; de Berg et al., chapter 11), every
//! visibility decided exactly by `orient3d`.
//!
//! Written by hand because the library has no hull: parry3d is only a dev-dependency (and
//! floating point), and a uv-sphere's regular triangulation is not the paper's "vertices
//! randomly distributed on a unit sphere". A point on the plane of a face does not see it, so
//! a point that sees no face is not a vertex of the hull and is skipped.

use crate::geometry::Point3;
use crate::geometry::predicates::orient3d;
use std::cmp::Ordering;

/// A face of the hull: its vertices counter-clockwise seen from outside, the faces across its
/// edges (`neighbours[i]` across the edge from `v[i]` to `v[(i + 1) % 3]`), and the points not
/// yet added that see it.
struct Face {
    v: [u32; 3],
    neighbours: [u32; 3],
    alive: bool,
    conflicts: Vec<u32>,
}

/// The faces (counter-clockwise seen from outside) of the hull of `points`, as indices into
/// `points`; `None` when all points lie in one plane.
pub(crate) fn convex_hull(points: &[Point3]) -> Option<Vec<[u32; 3]>> {
    let start = initial_tetrahedron(points)?;
    let mut faces = tetrahedron_faces(points, start);
    let mut point_conflicts = initial_conflicts(points, start, &mut faces);
    let mut stamp = vec![u32::MAX; points.len()];
    let mut horizon_start = vec![u32::MAX; points.len()];
    for p in 0..points.len() as u32 {
        let visible: Vec<u32> = std::mem::take(&mut point_conflicts[p as usize])
            .into_iter()
            .filter(|&f| faces[f as usize].alive)
            .collect();
        if visible.is_empty() {
            continue;
        }
        for &f in &visible {
            faces[f as usize].alive = false;
        }
        let created = cone_faces(
            points,
            p,
            &visible,
            &mut faces,
            &mut point_conflicts,
            &mut stamp,
            &mut horizon_start,
        );
        // Around the new cone: face (u, w, p) meets, across (w, p), the face starting at w.
        for &n in &created {
            let w = faces[n as usize].v[1];
            let next = horizon_start[w as usize];
            faces[n as usize].neighbours[1] = next;
            faces[next as usize].neighbours[2] = n;
        }
        for &f in &visible {
            faces[f as usize].conflicts = Vec::new();
        }
    }
    Some(faces.into_iter().filter(|f| f.alive).map(|f| f.v).collect())
}

/// Whether point `p` sees face `f`: lies strictly outside its plane.
fn sees(points: &[Point3], f: &Face, p: u32) -> bool {
    let [a, b, c] = f.v.map(|i| &points[i as usize]);
    orient3d(a, b, c, &points[p as usize]) == Ordering::Less
}

/// The faces of the tetrahedron `start`, each oriented to see its fourth vertex from inside,
/// with their neighbours.
fn tetrahedron_faces(points: &[Point3], start: [usize; 4]) -> Vec<Face> {
    let [a, b, c, d] = start;
    let mut faces: Vec<Face> = Vec::new();
    let tet = if orient3d(&points[a], &points[b], &points[c], &points[d]) == Ordering::Greater {
        [[a, b, c], [a, d, b], [b, d, c], [c, d, a]]
    } else {
        [[a, c, b], [a, b, d], [b, c, d], [c, a, d]]
    };
    for v in tet {
        faces.push(Face {
            v: v.map(|i| i as u32),
            neighbours: [u32::MAX; 3],
            alive: true,
            conflicts: Vec::new(),
        });
    }
    link_neighbours(&mut faces);
    faces
}

/// The conflict lists of the tetrahedron's faces (filled in `faces`) and of the points (the
/// faces each sees, returned), the tetrahedron's own corners left out.
fn initial_conflicts(points: &[Point3], start: [usize; 4], faces: &mut [Face]) -> Vec<Vec<u32>> {
    let mut point_conflicts: Vec<Vec<u32>> = vec![Vec::new(); points.len()];
    for p in 0..points.len() as u32 {
        if start.contains(&(p as usize)) {
            continue;
        }
        for (f, face) in faces.iter_mut().enumerate() {
            if sees(points, face, p) {
                face.conflicts.push(p);
                point_conflicts[p as usize].push(f as u32);
            }
        }
    }
    point_conflicts
}

/// The cone of new faces from point `p` to the horizon of the `visible` faces (an edge of a
/// visible face whose neighbour is not visible), linked across the horizon, each with the
/// later points that see it (candidates: the points that saw either face along its edge).
/// Returns the new faces; `horizon_start[u]` is the new face whose horizon edge starts at
/// `u`, and `stamp` marks the candidates already taken for a face.
fn cone_faces(
    points: &[Point3],
    p: u32,
    visible: &[u32],
    faces: &mut Vec<Face>,
    point_conflicts: &mut [Vec<u32>],
    stamp: &mut [u32],
    horizon_start: &mut [u32],
) -> Vec<u32> {
    let mut created: Vec<u32> = Vec::new();
    for &f in visible {
        for i in 0..3 {
            let g = faces[f as usize].neighbours[i];
            if !faces[g as usize].alive {
                continue;
            }
            let (u, w) = (faces[f as usize].v[i], faces[f as usize].v[(i + 1) % 3]);
            let new = faces.len() as u32;
            // Candidates: points that saw either face along the edge.
            let mut conflicts = Vec::new();
            for &q in faces[f as usize]
                .conflicts
                .iter()
                .chain(&faces[g as usize].conflicts)
            {
                if q > p && stamp[q as usize] != new {
                    stamp[q as usize] = new;
                    conflicts.push(q);
                }
            }
            let mut face = Face {
                v: [u, w, p],
                neighbours: [g, u32::MAX, u32::MAX],
                alive: true,
                conflicts: Vec::new(),
            };
            face.conflicts = conflicts
                .into_iter()
                .filter(|&q| sees(points, &face, q))
                .collect();
            for &q in &face.conflicts {
                point_conflicts[q as usize].push(new);
            }
            let back = faces[g as usize]
                .neighbours
                .iter()
                .position(|&h| h == f)
                .unwrap_or(0);
            faces[g as usize].neighbours[back] = new;
            horizon_start[u as usize] = new;
            faces.push(face);
            created.push(new);
        }
    }
    created
}

/// Four points not in one plane, the first ones found in order; `None` if there are none.
fn initial_tetrahedron(points: &[Point3]) -> Option<[usize; 4]> {
    let a = 0;
    let b = (1..points.len()).find(|&i| points[i] != points[a])?;
    let c = (b + 1..points.len())
        .find(|&i| !crate::geometry::predicates::collinear(&points[a], &points[b], &points[i]))?;
    let d = (c + 1..points.len())
        .find(|&i| orient3d(&points[a], &points[b], &points[c], &points[i]) != Ordering::Equal)?;
    Some([a, b, c, d])
}

/// Sets each face's neighbours by matching its directed edges with their reverses.
fn link_neighbours(faces: &mut [Face]) {
    for f in 0..faces.len() {
        for i in 0..3 {
            let (u, w) = (faces[f].v[i], faces[f].v[(i + 1) % 3]);
            let found = (0..faces.len())
                .find(|&g| (0..3).any(|j| faces[g].v[j] == w && faces[g].v[(j + 1) % 3] == u));
            if let Some(g) = found {
                faces[f].neighbours[i] = g as u32;
            }
        }
    }
}
