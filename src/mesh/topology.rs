//! Edge structure of a mesh: whether it is closed and consistently oriented.

/// How the faces of a mesh fit together along their edges.
///
/// A mesh is *closed* when every edge is shared by exactly two faces, and *consistently
/// oriented* when no edge is traversed twice in the same direction (for a closed mesh: every
/// edge once in each direction). Only a closed, consistently oriented mesh bounds a solid
/// with an inside, and only such a mesh gets an INBOX.
///
/// ```
/// let t = kepler::solids::cube(1.0).unwrap().topology();
/// assert!(t.closed && t.consistently_oriented);
/// assert_eq!((t.edges, t.boundary_edges, t.nonmanifold_edges), (12, 0, 0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Topology {
    /// Number of distinct (undirected) edges.
    pub edges: usize,
    /// Edges used by one face only.
    pub boundary_edges: usize,
    /// Edges used by more than two faces.
    pub nonmanifold_edges: usize,
    /// Edges used by an odd number of faces (boundary edges included). With none, every
    /// vertical ray crosses the faces an even number of times, so the mesh has an inside for
    /// ray parity even where solids touch along an edge (four faces on it).
    pub odd_edges: usize,
    /// Edges traversed twice in the same direction by two faces.
    pub misoriented_edges: usize,
    /// Every edge is shared by exactly two faces.
    pub closed: bool,
    /// No edge is traversed twice in the same direction.
    pub consistently_oriented: bool,
}

impl Topology {
    /// Analyses the edges of the given faces (vertex index loops).
    ///
    /// ```
    /// use kepler::mesh::Topology;
    /// // Two triangles sharing an edge in opposite directions: open but consistent.
    /// let t = Topology::of_faces([&[0u32, 1, 2][..], &[2, 1, 3][..]]);
    /// assert_eq!((t.edges, t.boundary_edges), (5, 4));
    /// assert!(!t.closed && t.consistently_oriented);
    /// ```
    pub fn of_faces<'a>(faces: impl IntoIterator<Item = &'a [u32]>) -> Topology {
        // (low, high, forward) per directed edge; sorting groups the uses of each edge.
        let mut uses: Vec<(u32, u32, bool)> = Vec::new();
        for f in faces {
            for (i, &a) in f.iter().enumerate() {
                let b = f[(i + 1) % f.len()];
                uses.push((a.min(b), a.max(b), a < b));
            }
        }
        uses.sort_unstable();
        let mut t = Topology {
            edges: 0,
            boundary_edges: 0,
            nonmanifold_edges: 0,
            odd_edges: 0,
            misoriented_edges: 0,
            closed: false,
            consistently_oriented: false,
        };
        for group in uses.chunk_by(|x, y| x.0 == y.0 && x.1 == y.1) {
            t.edges += 1;
            let forward = group.iter().filter(|u| u.2).count();
            match group.len() {
                1 => t.boundary_edges += 1,
                2 => {}
                _ => t.nonmanifold_edges += 1,
            }
            if group.len() % 2 == 1 {
                t.odd_edges += 1;
            }
            if forward > 1 || group.len() - forward > 1 {
                t.misoriented_edges += 1;
            }
        }
        t.closed = t.edges > 0 && t.boundary_edges == 0 && t.nonmanifold_edges == 0;
        t.consistently_oriented = t.misoriented_edges == 0;
        t
    }
}
