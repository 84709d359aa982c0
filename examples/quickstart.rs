//! The README's first steps in world space: brown hair (eumelanin 1.3) evaluated, sampled and
//! batch-evaluated from a world-space tangent and directions given as glam vectors.
//!
//! `cargo run --release --example quickstart` prints S for one configuration and the estimator
//! weight of one importance sample; `cargo test` runs it (`[[example]] test = true`) and it
//! asserts its own output: S finite and positive, red above blue for brown hair, the f32, SIMD
//! and f64 values within the crate's f32 bound, the sampled direction unit and its pdf the
//! model's pdf.

use hairmath::absorption::Absorption;
use hairmath::bcsdf::{BatchReal, ChiangHair, Model, RandomNumbers};
use hairmath::glam::{DVec3, Vec3};
use hairmath::params::{
    AzimuthalRoughness, CuticleTilt, HairParams, LongitudinalRoughness, RefractiveIndex,
};
use hairmath::world::{eval_batch_world, world_query, WorldBcsdf, WorldSampledBcsdf};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let hair = ChiangHair::<f64>::new(&HairParams {
        beta_m: LongitudinalRoughness::new(0.3)?,
        beta_n: AzimuthalRoughness::new(0.3)?,
        alpha: CuticleTilt::from_degrees(2.0)?,
        eta: RefractiveIndex::new(1.55)?,
        sigma_a: Absorption::from_melanin(1.3, 0.0)?,
    });

    // World space, as a renderer has it: a strand hanging down (+Y up), seen from the side
    // (+X) and lit from behind (a rim light: light through the fibre, the TT lobe). The
    // tangent need not be unit length.
    let tangent = DVec3::new(0.0, -3.0, 0.2);
    let to_light = DVec3::new(-1.0, -0.1, 0.3).normalize();
    let to_camera = DVec3::new(1.0, 0.1, 0.0).normalize();
    let s = hair.eval_world(tangent, to_light, to_camera, 0.0);
    println!(
        "S = {:.6} {:.6} {:.6} (per RGB channel, no cosine factor)",
        s[0], s[1], s[2]
    );
    assert!(s.iter().all(|v| v.is_finite() && *v > 0.0), "{s:?}");
    assert!(s[0] > s[2], "brown hair scatters more red than blue: {s:?}");

    // Untrusted values (a file, a user) go through the checked query.
    assert!(world_query(DVec3::ZERO, to_light, to_camera, 0.0).is_err());

    // f32 with glam's Vec3, and SIMD lanes over slices of them, from the same constants.
    let single = hair.instantiate::<f32>();
    let s32 = single.eval_world(
        tangent.as_vec3(),
        to_light.as_vec3(),
        to_camera.as_vec3(),
        0.0,
    );
    let lanes = hair.instantiate::<BatchReal>();
    let mut out = [[0.0_f32; 3]; 3];
    let [t, i, o] = [tangent, to_light, to_camera].map(|v| [v.as_vec3(); 3]);
    eval_batch_world(&lanes, &t, &i, &o, &[0.0; 3], &mut out)?;
    for (k, reference) in s.iter().enumerate() {
        for value in [s32[k], out[2][k]] {
            let error = (f64::from(value) - reference).abs() / reference;
            assert!(error < 3e-4, "channel {k}: {value} against {reference}");
        }
    }

    // Importance sampling: the next direction towards the light, in world space.
    let u = RandomNumbers {
        lobe: 0.5,
        longitudinal: 0.3,
        cone: 0.7,
        offset: 0.4,
    };
    let sample = hair.sample_world(tangent, to_camera, 0.0, u);
    let w = sample.weight();
    println!(
        "sampled wi = ({:.4}, {:.4}, {:.4}), pdf {:.4}, weight {:.4} {:.4} {:.4}",
        sample.wi.x, sample.wi.y, sample.wi.z, sample.pdf, w[0], w[1], w[2]
    );
    assert!((sample.wi.length() - 1.0).abs() < 1e-12);
    let pdf = hair.pdf_world(tangent, sample.wi, to_camera, 0.0);
    assert!(
        (pdf - sample.pdf).abs() < 1e-9 * sample.pdf,
        "{pdf} vs {}",
        sample.pdf
    );
    let _: Vec3 = Vec3::from(hairmath::geometry::V3::from(sample.wi.as_vec3()));
    Ok(())
}

#[test]
fn quickstart_runs_and_checks_itself() {
    main().unwrap();
}
