//! Quick timings of every operation on a 37,538-vertex torus (274 x 137),
//! best of several runs. `cargo run --release -p mesh-curvature --example timing`.
//! The criterion bench (`benches/curvature.rs`) is the reference.

use std::time::Instant;

use mesh_curvature::*;
use mesh_kernel::shapes;

/// CPU time of the calling thread in ns (`clock_gettime` with
/// `CLOCK_THREAD_CPUTIME_ID`), which stays meaningful on a loaded machine
/// for single-threaded runs (`--no-default-features`).
fn thread_cpu_ns() -> u64 {
    #[repr(C)]
    struct Timespec {
        sec: i64,
        nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
    }
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut ts = Timespec { sec: 0, nsec: 0 };
    // SAFETY: clock_gettime writes one timespec into the valid pointer.
    let rc = unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    if rc == 0 {
        ts.sec as u64 * 1_000_000_000 + ts.nsec as u64
    } else {
        0
    }
}

/// Best wall time and best calling-thread CPU time over `reps` runs, in ms.
fn best(reps: usize, f: &mut dyn FnMut()) -> (f64, f64) {
    let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..reps {
        let (t, c) = (Instant::now(), thread_cpu_ns());
        f();
        wall = wall.min(t.elapsed().as_secs_f64() * 1e3);
        cpu = cpu.min((thread_cpu_ns() - c) as f64 * 1e-6);
    }
    (wall, cpu)
}

fn main() {
    let mesh = shapes::torus(2.0, 0.5, 274, 137).unwrap();
    let _ = mesh.connectivity();
    println!("torus 274x137: {} vertices", mesh.vertex_count());
    let reps: usize = std::env::var("REPS").ok().and_then(|s| s.parse().ok()).unwrap_or(15);
    let only = std::env::args().nth(1).unwrap_or_default();
    let best = |name: &str, reps: usize, f: &mut dyn FnMut()| {
        if only.is_empty() || name.contains(only.as_str()) {
            let (wall, cpu) = best(reps, f);
            println!("{name:15} {wall:8.2} ms wall {cpu:8.2} ms cpu (main thread)");
        }
    };
    best("gaussian", reps, &mut || drop(gaussian_curvature(&mesh, &Default::default()).unwrap()));
    best("mean", reps, &mut || drop(mean_curvature(&mesh, &Default::default()).unwrap()));
    let fit = |neighborhood, degree, use_normals, refine_normal| TensorOptions {
        method: TensorMethod::Fit(FitOptions { neighborhood, degree, use_normals, refine_normal }),
        normals: NormalWeighting::Max,
    };
    for (name, o) in [
        ("default", TensorOptions::default()),
        ("quartic r2", fit(Neighborhood::Rings(2), Degree::Quartic, false, true)),
        ("cubic r2", fit(Neighborhood::Rings(2), Degree::Cubic, false, true)),
        ("quadric r1", fit(Neighborhood::Rings(1), Degree::Quadric, false, false)),
        ("rusinkiewicz", TensorOptions { method: TensorMethod::Rusinkiewicz, ..Default::default() }),
        (
            "normal cycle r1",
            TensorOptions { method: TensorMethod::NormalCycle(Neighborhood::Rings(1)), ..Default::default() },
        ),
    ] {
        best(name, reps, &mut || drop(curvature_tensor(&mesh, &o).unwrap()));
    }
    best("connectivity", reps, &mut || drop(mesh_kernel::Connectivity::new(mesh.vertex_count(), mesh.faces())));
    best("cotan_laplacian", reps, &mut || drop(mesh_kernel::operators::cotan_laplacian(&mesh)));
    let mixed = mesh_kernel::operators::MassKind::MixedVoronoi;
    best("lumped_mass", reps, &mut || drop(mesh_kernel::operators::lumped_mass(&mesh, mixed)));
    best("normals max", reps, &mut || drop(mesh_kernel::geometry::vertex_normals(&mesh, NormalWeighting::Max)));
}
