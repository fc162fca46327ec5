use kepler::bounds::tribox::TriboxBounds;
fn main() {
    for p in kepler::solids::Polyhedron::ALL {
        let m = p.mesh(1.0).unwrap();
        let b = TriboxBounds::from_points(m.vertices());
        let t = b.boundary();
        let c = t.cleaned();
        println!(
            "{:28} raw {:2} cleaned {:2} vol {:.6} verts {}",
            p.name(),
            t.face_count(),
            c.face_count(),
            c.volume(),
            c.vertices().len()
        );
    }
}
