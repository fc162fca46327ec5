//! Visible surfaces (`kepler::surfaces::visible_surfaces`: every face's visible polygons against
//! the whole scene) of the bundled city block, and of a closed torus of 69,600 triangles
//! (34,800 quad faces), from an isometric view. The counts of the early exits are printed
//! once per scene.
//!
//!   cargo bench --bench surfaces

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use kepler::geometry::Vector3;
use kepler::scene::Scene;
use kepler::surfaces::{Status, visible_surfaces};
use kepler::views::View;

/// Prints how the faces came out and what decided them.
fn report(name: &str, scene: &Scene, view: &View) {
    let faces = visible_surfaces(scene, view).expect("visible surfaces");
    let count = |s: Status| faces.iter().filter(|f| f.visible.status == s).count();
    let (mut solid, mut cbox, mut inbox, mut face, mut front, mut tested) = (0, 0, 0, 0, 0, 0);
    for f in &faces {
        solid += f.visible.exits.solid_hid;
        cbox += f.visible.exits.cbox_skipped;
        inbox += f.visible.exits.inbox_hid;
        face += f.visible.exits.face_hid;
        front += f.visible.exits.faces_in_front;
        tested += f.visible.exits.faces_tested;
    }
    eprintln!(
        "{name}: {} faces: {} visible, {} hidden, {} mixed; {solid} hidden by their own solid, CBOX skipped {cbox} objects, INBOX \
         hid {inbox} faces at once, a single face hid {face}, {tested} occluder faces tried, {front} \
         hiding some area",
        faces.len(),
        count(Status::Visible),
        count(Status::Hidden),
        count(Status::Mixed)
    );
}

fn surfaces(c: &mut Criterion) {
    let city = kepler::scene::file::load(std::path::Path::new("scenes/city.toml")).expect("city");
    let city_view = View::from_camera(city.camera().expect("a camera")).expect("view");
    let mut torus = Scene::new();
    torus
        .add_mesh(
            None,
            "torus",
            kepler::solids::torus(2.0, 0.7, 240, 145).expect("torus"),
        )
        .expect("scene");
    let iso = View::orthographic(Vector3::new(-1.0, -2.0, -3.0), Vector3::z()).expect("view");
    report("city", &city, &city_view);
    report("torus", &torus, &iso);

    let mut group = c.benchmark_group("visible surfaces");
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    group.measurement_time(Duration::from_secs(10));
    group.throughput(Throughput::Elements(1_968));
    group.bench_function("city block (1,968 faces)", |b| {
        b.iter(|| visible_surfaces(black_box(&city), &city_view).expect("surfaces"))
    });
    group.throughput(Throughput::Elements(34_800));
    group.bench_function("torus (34,800 faces)", |b| {
        b.iter(|| visible_surfaces(black_box(&torus), &iso).expect("surfaces"))
    });
    group.finish();
}

criterion_group!(benches, surfaces);
criterion_main!(benches);
