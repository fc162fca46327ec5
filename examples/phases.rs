use std::time::Instant;
fn main() {
    let t = Instant::now();
    let s = kepler::scene::file::load("scenes/metropolis.toml".as_ref()).unwrap();
    let t1 = t.elapsed();
    let walk = s.walk();
    let t = Instant::now();
    for (id, _) in &walk {
        s.cbox(*id);
    }
    let t2 = t.elapsed();
    let t = Instant::now();
    for (id, _) in &walk {
        s.tribox(*id);
    }
    let t3 = t.elapsed();
    let t = Instant::now();
    for (id, _) in &walk {
        s.inbox(*id);
    }
    let t4 = t.elapsed();
    let t = Instant::now();
    for (id, _) in &walk {
        let b = s.tribox(*id).boundary().cleaned();
        std::hint::black_box(b.face_count());
    }
    let t5 = t.elapsed();
    let t = Instant::now();
    let r = kepler::scene::report::BoundsReport::of(&s);
    let t6 = t.elapsed();
    let t = Instant::now();
    let tab = r.table();
    let t7 = t.elapsed();
    println!(
        "load {t1:?} cbox {t2:?} tribox {t3:?} inbox {t4:?} boundary+clean {t5:?} report(cached) {t6:?} table {t7:?} {}",
        tab.len()
    );
}
