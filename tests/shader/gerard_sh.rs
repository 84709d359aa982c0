//! Gerard's spherical-harmonic shading as emitted shader code
//! ([`hairmath::models::gerard_sh::trace_shade`]): the phase tables as textures, the SH
//! rotation and the triple product as arithmetic, run on the device and compared with the
//! traced graph's `f32` evaluation under the WGSL accuracy rules' forward error bound.

use crate::error_bound::{gpu_error_bound, AccuracyRules};
use crate::gpu::{device, textures_of};
use hairmath::absorption::Absorption;
use hairmath::azimuthal::CausticParams;
use hairmath::bcsdf::Marschner2003;
use hairmath::models::gerard_sh::{trace_shade, GerardSh, PhaseQuadrature, SHADE_FUNCTION};
use hairmath::models::{GerardLobe, GERARD_K_TRT, GERARD_K_TT};
use hairmath::params::{LobeShift, LobeWidth, MarschnerLobes, RefractiveIndex};
use hairmath::quadrature::kronecker;

fn shading() -> GerardSh<f64, 6> {
    let source = Marschner2003 {
        lobes: MarschnerLobes {
            alpha_r: LobeShift::new((-5f64).to_radians()).unwrap(),
            beta_r: LobeWidth::new(7.5f64.to_radians()).unwrap(),
        },
        eta: RefractiveIndex::new(1.55).unwrap(),
        sigma_a: Absorption::new([0.5447, 0.9061, 1.781]).unwrap(),
        caustic: Some(CausticParams::default()),
    };
    let quadrature = PhaseQuadrature { n_z: 32, n_phi: 64 };
    let k = [GERARD_K_TT, GERARD_K_TRT];
    GerardSh::new(&source, GerardLobe::Printed, k, 0.1, 33, &quadrature).unwrap()
}

/// A unit vector from two coordinates in [0, 1).
fn sphere(u: f64, v: f64) -> [f32; 3] {
    let z = 2.0 * u - 1.0;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = core::f64::consts::TAU * v;
    [(r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32]
}

/// `n` rows: tangent, wo, light, the light's radiance, nine transmittance coefficients (V
/// about 0.6 with some structure).
fn rows(n: usize) -> Vec<f32> {
    let mut rows = Vec::new();
    let mut p = [0.0; 6];
    for k in 0..n {
        kronecker(k, 6, &mut p);
        rows.extend(sphere(p[0], p[1]));
        rows.extend(sphere(p[2], p[3]));
        rows.extend(sphere(p[4], p[5]));
        rows.extend([1.0, 0.8, 0.6]);
        let v: [f32; 9] = core::array::from_fn(|j| match j {
            0 => 2.1,
            _ => 0.3 * ((j as f64 + 1.0) * (p[0] + p[5])).sin() as f32,
        });
        rows.extend(v);
    }
    rows
}

#[test]
fn gerards_sh_shading_computes_on_the_device_what_the_cpu_computes() {
    let Some(device) = device() else { return };
    let environment = [0.9, 0.6, 0.3].map(|scale: f64| {
        (0..16)
            .map(|k| scale * if k == 0 { 3.5 } else { 0.4 / (k as f64) })
            .collect::<Vec<f64>>()
    });
    let graph = trace_shade(&shading(), 2, &environment).unwrap();
    let module = hairmath::shader::lower(&graph, SHADE_FUNCTION).unwrap();
    let stride = module.argument_scalars();
    assert_eq!(stride, 21);
    let compute = module.with_compute_entry(stride).unwrap();
    let wgsl = compute.wgsl().unwrap();
    let queries = rows(512);
    let gpu = device
        .run(&wgsl, "hair_main", &queries, stride, &textures_of(&module))
        .unwrap();
    let rules = AccuracyRules::wgsl_on_llvmpipe();
    let (mut failures, mut infinite, mut worst) = (Vec::new(), 0, 0f64);
    for (k, row) in queries.chunks(stride).enumerate() {
        let cpu = graph.eval_f32(row);
        let bound = gpu_error_bound(&graph, row, &rules);
        for c in 0..3 {
            let difference = (f64::from(gpu[3 * k + c]) - f64::from(cpu[c])).abs();
            if !bound[c].is_finite() {
                infinite += 1;
            } else if difference.is_nan() || difference > bound[c] {
                failures.push(format!(
                    "row {k} channel {c}: GPU {} CPU {} bound {}",
                    gpu[3 * k + c],
                    cpu[c],
                    bound[c]
                ));
            } else if bound[c] > 0.0 {
                worst = worst.max(difference / bound[c]);
            }
        }
    }
    eprintln!("gerard_sh on the device: worst difference / bound {worst:.3e}, {infinite} infinite bounds of {}", 3 * 512);
    assert!(
        failures.is_empty(),
        "{}",
        failures[..failures.len().min(6)].join("\n")
    );
    assert!(
        infinite * 20 < 3 * 512 * 3,
        "{infinite} values without a finite bound"
    );
}
