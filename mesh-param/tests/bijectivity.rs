//! Tutte's and Floater's theorems: positive weights and a convex boundary
//! give a bijective map, on every disk of the data folder and on random
//! perturbed disks; non-disks are cut first.

mod common;

use glam::DVec3;
use mesh_kernel::shapes;
use mesh_param::{parameterize, parameterize_cut, BoundaryMap, ParamError, ParamMethod, ParamOptions, Spacing};
use proptest::prelude::*;

fn run(mesh: &mesh_kernel::TriMesh, method: ParamMethod, boundary: BoundaryMap) -> mesh_param::DistortionSummary {
    parameterize(mesh, &ParamOptions { method, boundary, ..Default::default() }).unwrap().report.summary
}

#[test]
fn data_disks_map_bijectively() {
    for name in ["cgal_nefertiti.off", "cgal_mushroom.off", "cgal_degtri_sliding.off"] {
        let Some(m) = common::read(name) else { return };
        for spacing in [Spacing::Uniform, Spacing::ChordLength] {
            for method in [ParamMethod::Tutte, ParamMethod::MeanValue] {
                let s = run(&m, method, BoundaryMap::Circle(spacing));
                assert!(s.bijective && s.flipped_faces == 0, "{name} {} {spacing:?}", method.name());
            }
        }
        // Observed, not guaranteed by a theorem: the conformal methods are
        // bijective on these meshes too.
        for method in [ParamMethod::Harmonic, ParamMethod::Lscm] {
            let s = run(&m, method, BoundaryMap::default());
            eprintln!(
                "{name} {}: bijective {}, angle distortion {:.3}",
                method.name(),
                s.bijective,
                s.angle_distortion_mean
            );
            assert!(s.bijective, "{name} {}", method.name());
        }
    }
}

#[test]
fn data_non_disks_are_refused_then_cut() {
    let expected = [
        ("cgal_elephant.off", "closed surface of genus 3"),
        ("cgal_fandisk.off", "closed surface of genus 0"),
        ("npm_bunny.obj", "closed surface of genus 0"),
        ("cgal_holes.off", "genus 0 with 7 boundary loops"),
    ];
    for (name, found) in expected {
        let Some(m) = common::read(name) else { return };
        match parameterize(&m, &ParamOptions::default()) {
            Err(ParamError::NotADisk { found: f }) => assert!(f.contains(found), "{name}: {f}"),
            other => panic!("{name}: {other:?}"),
        }
        for method in [ParamMethod::Tutte, ParamMethod::Harmonic] {
            let p = parameterize_cut(&m, &ParamOptions { method, ..Default::default() }).unwrap();
            let s = p.param.report.summary;
            eprintln!("{name} cut along {} edges, {}: bijective {}", p.cut.seam.len(), method.name(), s.bijective);
            assert!(s.bijective, "{name} {}", method.name());
            let corners = p.corner_uvs();
            assert_eq!(corners.len(), m.face_count());
            assert!(corners.iter().flatten().all(|q| q.is_finite()));
        }
    }
}

/// A disk with jittered interior vertices and a random height field.
fn perturbed_disk(rings: usize, seed: u64, height: f64, waves: f64) -> mesh_kernel::TriMesh {
    let mut m = shapes::disk(rings, seed).unwrap();
    for p in m.positions_mut() {
        p.z = height * ((waves * p.x).sin() * (waves * p.y + seed as f64).cos());
    }
    m
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn tutte_and_mean_value_never_flip(rings in 1usize..12, seed in 0u64..10_000, height in 0.0f64..2.0, waves in 0.5f64..8.0) {
        let m = perturbed_disk(rings, seed, height, waves);
        for method in [ParamMethod::Tutte, ParamMethod::MeanValue] {
            let s = run(&m, method, BoundaryMap::Circle(Spacing::ChordLength));
            prop_assert_eq!(s.flipped_faces + s.collapsed_faces, 0);
            prop_assert!(s.bijective);
        }
    }

    #[test]
    fn folded_disks_still_map_bijectively(rings in 2usize..8, seed in 0u64..1000) {
        // Fold the disk over itself along x = 0 (a non-embedded surface):
        // the combinatorial theorems still hold.
        let mut m = shapes::disk(rings, seed).unwrap();
        for p in m.positions_mut() {
            if p.x > 0.0 {
                *p = DVec3::new(-p.x, p.y, 0.3 * p.x);
            }
        }
        for method in [ParamMethod::Tutte, ParamMethod::MeanValue] {
            prop_assert!(run(&m, method, BoundaryMap::default()).bijective);
        }
    }
}
