use nalgebra::{Matrix4, Rotation3, Vector3};
fn main() {
    let rot = Rotation3::from_euler_angles(-0.37491887956214864, 1.0905305833022987, 0.0)
        .to_homogeneous();
    let m = Matrix4::new_nonuniform_scaling(&Vector3::new(0.3, 0.3, 0.3)) * rot;
    let mesh = kepler::solids::cube(1.0).unwrap().transformed(&m).unwrap();
    println!("{:?}", kepler::bounds::inbox(&mesh));
    println!("vol {}", mesh.volume());
}
