//! Gerard's spherical-harmonic shading (`hairmath::models::gerard_sh`):
//!
//! - the phase function's projection: the coefficients of `sin(|m| phi)` vanish (the lobes are
//!   even in phi), the default quadrature is converged, and reconstructing S from bands
//!   `l <= L` approaches S as L grows, measured against S itself (not by Parseval) at grazing
//!   views and low roughness;
//! - rotating the coefficients ([`rotation_blocks`]) equals projecting the rotated function, to
//!   1e-12, near-gimbal tangents included, and equals [`ShRotation`];
//! - the shading's triple product equals direct quadrature of the product of the three
//!   reconstructed functions (phase in the tangent frame, absorption per lobe, transmittance,
//!   environment), to 1e-10;
//! - with V = 1 and a constant environment the shading is the environment times the lobe
//!   albedo, integrated independently of the tables; the directional light is eq. 9 exactly;
//! - Gerard's 8-bit layout decodes within half a code; the table over absorption holds
//!   Gerard's exponents in closed form for his own lobes; the traced shading is the `f32`
//!   shading bit for bit.

use core::f64::consts::PI;
use glam::{DMat3, DVec3};
use hairmath::absorption::Absorption;
use hairmath::azimuthal::CausticParams;
use hairmath::bcsdf::{Bcsdf, Marschner2003, Query};
use hairmath::geometry::{local_directions, V3};
use hairmath::lut::SharedTable;
use hairmath::models::gerard_sh::{
    local_of_tangent_frame, phase_index, project_phase, tangent_frame, trace_shade, viewer_at,
    AbsorbingPhaseTable, GerardSh, Lighting, PhaseQuadrature, PhaseTable, PhaseTextureRgba8,
    ShadedPoint, MAX_TABULATED_SIGMA_A,
};
use hairmath::models::{gerard_attenuation, Gerard, GerardLobe, GERARD_K_TRT, GERARD_K_TT};
use hairmath::params::{LobeShift, LobeWidth, MarschnerLobes, RefractiveIndex};
use hairmath::quadrature::gauss_legendre;
use hairmath::sh::{eval_sh_f64, project, rotate_with_blocks, rotation_blocks, ShRotation};

fn marschner(alpha_r_deg: f64, beta_r_deg: f64, sigma_a: [f64; 3]) -> Marschner2003 {
    Marschner2003 {
        lobes: MarschnerLobes {
            alpha_r: LobeShift::new(alpha_r_deg.to_radians()).unwrap(),
            beta_r: LobeWidth::new(beta_r_deg.to_radians()).unwrap(),
        },
        eta: RefractiveIndex::new(1.55).unwrap(),
        sigma_a: Absorption::new(sigma_a).unwrap(),
        caustic: Some(CausticParams::default()),
    }
}

/// Brown hair's absorption per unit radius (eumelanin 1.3).
const BROWN: [f64; 3] = [0.5447, 0.9061, 1.781];

fn clear_gerard(alpha_r_deg: f64, beta_r_deg: f64) -> Gerard<f64> {
    let source = marschner(alpha_r_deg, beta_r_deg, [0.0; 3]);
    Gerard::new(&source, GerardLobe::Printed, GERARD_K_TT, GERARD_K_TRT).unwrap()
}

fn max_abs(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |m, v| m.max(v.abs()))
}

#[test]
fn the_phase_projection_is_even_in_phi_and_converged() {
    let model = clear_gerard(-5.0, 7.5);
    let fine = PhaseQuadrature {
        n_z: 384,
        n_phi: 768,
    };
    for s in [0.0, 0.5, -0.9, 0.99] {
        let (coefficients, _) = project_phase(&model, s, 4, &PhaseQuadrature::default()).unwrap();
        let (reference, _) = project_phase(&model, s, 4, &fine).unwrap();
        let largest = max_abs(reference.iter().flatten().copied());
        let change = max_abs(
            coefficients
                .iter()
                .flatten()
                .zip(reference.iter().flatten())
                .map(|(a, b)| a - b),
        );
        // Measured: 7e-6 to 3.2e-5 of the largest coefficient (at the grazing 0.99).
        assert!(change < 5e-5 * largest, "s = {s}: {change:e} of {largest}");
        for lobe in &coefficients {
            for l in 1..=4usize {
                for m in 1..=l {
                    let odd = lobe[l * (l + 1) - m];
                    assert!(odd.abs() < 1e-13, "s = {s}, l = {l}, m = -{m}: {odd:e}");
                }
            }
        }
    }
}

/// `sqrt(int (S - S_L)^2 / int S^2)` per lobe and `L = 0..=4`, by the quadrature rule, with
/// `S_L` reconstructed from the coefficients at every node.
fn reconstruction_errors(model: &Gerard<f64>, s: f64) -> Vec<[f64; 3]> {
    let q = PhaseQuadrature::default();
    let (coefficients, _) = project_phase(model, s, 4, &q).unwrap();
    let (z_nodes, n_phi) = (gauss_legendre(q.n_z), q.n_phi);
    let mut squares = [[0.0; 3]; 5];
    let mut totals = [0.0; 3];
    for (z, wz) in z_nodes {
        let r = (1.0 - z * z).sqrt();
        for j in 0..n_phi {
            let phi = 2.0 * PI * (j as f64 + 0.5) / n_phi as f64;
            let t = DVec3::new(r * phi.cos(), r * phi.sin(), z);
            let weight = wz * 2.0 * PI / n_phi as f64;
            let y = eval_sh_f64(4, t).unwrap();
            let values = model.eval_lobes(&Query::far(local_of_tangent_frame(t), viewer_at(s)));
            for lobe in 0..3 {
                let v = values[lobe][0];
                totals[lobe] += weight * v * v;
                for (band, row) in squares.iter_mut().enumerate() {
                    let n = (band + 1) * (band + 1);
                    let reconstructed: f64 = coefficients[lobe][..n]
                        .iter()
                        .zip(&y)
                        .map(|(a, y)| a * y)
                        .sum();
                    row[lobe] += weight * (v - reconstructed).powi(2);
                }
            }
        }
    }
    squares
        .iter()
        .map(|row| core::array::from_fn(|lobe| (row[lobe] / totals[lobe]).sqrt()))
        .collect()
}

#[test]
fn the_truncated_phase_approaches_s_as_the_band_grows() {
    // Grazing views and the lowest roughness the g(beta) closed forms allow.
    for (beta_r, s) in [(7.5, 0.99), (7.5, -0.99), (2.0, 0.0), (2.0, 0.95)] {
        let errors = reconstruction_errors(&clear_gerard(-5.0, beta_r), s);
        println!("beta_R {beta_r}, sin theta_r {s}: {errors:.3?}");
        for lobe in 0..3 {
            for pair in errors.windows(2) {
                assert!(
                    pair[1][lobe] < pair[0][lobe],
                    "lobe {lobe}, beta_R {beta_r}, s {s}: {errors:?}"
                );
            }
            assert!(errors[0][lobe] <= 1.0 + 1e-9);
        }
    }
}

/// Tangents and viewers, the near-gimbal ones first: the tangent along and next to each axis,
/// the viewer along and next to the tangent.
fn configurations() -> Vec<(V3<f64>, V3<f64>)> {
    let unit = |x: f64, y: f64, z: f64| {
        let n = (x * x + y * y + z * z).sqrt();
        V3::new(x / n, y / n, z / n)
    };
    vec![
        (unit(0.0, 0.0, 1.0), unit(0.3, 0.2, 0.9)),
        (unit(0.0, 0.0, -1.0), unit(0.3, -0.2, 0.1)),
        (unit(1e-7, 0.0, 1.0), unit(1.0, 0.0, 0.0)),
        (unit(0.0, 1.0, 1e-7), unit(0.0, 1.0, 1e-7)),
        (unit(1.0, 0.0, 0.0), unit(1.0, 1e-9, 0.0)),
        (unit(0.3, -0.5, 0.8), unit(-0.2, 0.9, 0.1)),
        (unit(-0.6, 0.2, -0.7), unit(0.5, 0.5, -0.7)),
    ]
}

fn matrix(frame: &[V3<f64>; 3]) -> DMat3 {
    let column = |v: V3<f64>| DVec3::new(v.x, v.y, v.z);
    DMat3::from_cols(column(frame[0]), column(frame[1]), column(frame[2]))
}

fn rows(m: DMat3) -> [[f64; 3]; 3] {
    core::array::from_fn(|i| core::array::from_fn(|j| m.col(j)[i]))
}

#[test]
fn rotating_the_coefficients_equals_projecting_the_rotated_function() {
    let model = clear_gerard(-5.0, 7.5);
    for (tangent, wo) in configurations() {
        let frame = tangent_frame(tangent, wo);
        let m = matrix(&frame);
        let orthogonality = m.transpose() * m - DMat3::IDENTITY;
        let worst = max_abs((0..3).flat_map(|j| orthogonality.col(j).to_array()));
        assert!(
            (m.determinant() - 1.0).abs() < 1e-12 && worst < 1e-12,
            "{m:?}"
        );
        let (coefficients, _) = project_phase(
            &model,
            tangent.dot(frame[2]).clamp(-1.0, 1.0),
            4,
            &PhaseQuadrature {
                n_z: 64,
                n_phi: 128,
            },
        )
        .unwrap();
        let blocks = rotation_blocks(&rows(m), 4);
        let reference = ShRotation::new(m, 4).unwrap();
        for a in &coefficients {
            let mut rotated = vec![0.0; a.len()];
            rotate_with_blocks(&blocks, a, &mut rotated);
            assert_eq!(
                rotated,
                reference.apply(a).unwrap(),
                "the same blocks as ShRotation"
            );
            // The band-limited function of the coefficients, carried by the rotation:
            // g(w) = f(M^T w), projected exactly.
            let f = |t: DVec3| {
                a.iter()
                    .zip(eval_sh_f64(4, t).unwrap())
                    .map(|(c, y)| c * y)
                    .sum::<f64>()
            };
            let projected = project(4, |w| f(m.transpose() * w)).unwrap();
            let largest = max_abs(a.iter().copied());
            let error = max_abs(rotated.iter().zip(&projected).map(|(r, p)| r - p));
            assert!(
                error < 1e-12 * largest.max(1.0),
                "{tangent:?}, {wo:?}: {error:e}"
            );
        }
    }
}

/// Brown hair's shading with 33 table samples (sin theta_r = k / 16) and the default
/// projection.
fn shading(bias: f64) -> GerardSh<f64, 15> {
    let source = marschner(-5.0, 7.5, BROWN);
    let q = PhaseQuadrature::default();
    GerardSh::new(
        &source,
        GerardLobe::Printed,
        [GERARD_K_TT, GERARD_K_TRT],
        bias,
        33,
        &q,
    )
    .unwrap()
}

/// A band-limited test function's coefficients (bands `l <= lmax`, deterministic).
fn coefficients(lmax: usize, seed: f64) -> Vec<f64> {
    (0..(lmax + 1) * (lmax + 1))
        .map(|k| ((k as f64 + 1.0) * seed).sin() / (1.0 + k as f64).sqrt())
        .collect()
}

fn reconstruct(c: &[f64], w: DVec3) -> f64 {
    let lmax = (c.len() as f64).sqrt() as usize - 1;
    c.iter()
        .zip(eval_sh_f64(lmax, w).unwrap())
        .map(|(a, y)| a * y)
        .sum()
}

#[test]
fn the_triple_product_equals_quadrature_of_the_reconstructed_product() {
    let shade = shading(0.0);
    let absorption = shade_absorption();
    let v = coefficients(2, 0.7);
    let environment = [
        coefficients(2, 1.3),
        coefficients(2, 2.1),
        coefficients(3, 0.4),
    ];
    for (tangent, wo) in configurations() {
        let point = ShadedPoint {
            tangent,
            wo,
            transmittance: &v,
        };
        let lighting = Lighting {
            environment: [&environment[0], &environment[1], &environment[2]],
            light: V3::new(0.0, 0.0, 1.0),
            light_radiance: [0.0; 3],
        };
        let shaded = shade.shade(&point, &lighting).unwrap();
        // The phase function in the tangent frame, from the table at sin theta_r, reconstructed
        // with the absorption of each lobe; the product integrated over world directions by a
        // rule exact for its band limit (4 + 2 + 3 = 9).
        let frame = tangent_frame(tangent, wo);
        let m = matrix(&frame);
        let s = wo.dot(frame[2]);
        let lobes: Vec<Vec<f64>> = (0..3)
            .map(|lobe| {
                let table: &SharedTable<1, 15> = shade.phase().lobes().unwrap().lobe(lobe).unwrap();
                let stored = table.lookup_f64([s]);
                let mut full = vec![0.0; 25];
                for l in 0..=4 {
                    for mm in 0..=l {
                        full[l * (l + 1) + mm] = stored[phase_index(l, mm)];
                    }
                }
                full
            })
            .collect();
        for channel in 0..3 {
            let weights = [1.0, absorption[0][channel], absorption[1][channel]];
            let integrand = |w: DVec3| {
                let t = m.transpose() * w;
                let phase: f64 = lobes
                    .iter()
                    .zip(weights)
                    .map(|(a, k)| k * reconstruct(a, t))
                    .sum();
                phase * reconstruct(&v, w) * reconstruct(&environment[channel], w)
            };
            let exact = project(5, integrand).unwrap()[0] * (4.0 * PI).sqrt();
            let error = (shaded[channel] - exact).abs();
            assert!(
                error < 1e-10 * exact.abs().max(1e-3),
                "{tangent:?} {wo:?} channel {channel}: {} vs {exact}",
                shaded[channel]
            );
        }
    }
}

/// `e^(-k sigma_a)` of TT and TRT per channel: Gerard's eq. 14 with his exponents.
fn shade_absorption() -> [[f64; 3]; 2] {
    [GERARD_K_TT, GERARD_K_TRT].map(|k| BROWN.map(|s| gerard_attenuation(k, s)))
}

#[test]
fn with_v_one_and_a_constant_environment_the_shading_is_the_albedo() {
    let shade = shading(0.0);
    let model = Gerard::new(
        &marschner(-5.0, 7.5, BROWN),
        GerardLobe::Printed,
        GERARD_K_TT,
        GERARD_K_TRT,
    )
    .unwrap();
    let norm = (4.0 * PI).sqrt();
    let v = [norm, 0.0, 0.0, 0.0];
    let radiance = [0.8, 1.0, 1.3];
    let environment = radiance.map(|l| [l * norm]);
    // Viewers at table samples (33 samples over [-1, 1]: sin theta_r = k / 16), so that the
    // table's interpolation adds nothing.
    for k in [-15, -8, 0, 5, 12] {
        let s = k as f64 / 16.0;
        let tangent = V3::new(0.0, 0.0, 1.0);
        let wo = V3::new((1.0 - s * s).sqrt(), 0.0, s);
        let point = ShadedPoint {
            tangent,
            wo,
            transmittance: &v,
        };
        let lighting = Lighting {
            environment: [&environment[0], &environment[1], &environment[2]],
            light: V3::new(0.0, 0.0, 1.0),
            light_radiance: [0.0; 3],
        };
        let shaded = shade.shade(&point, &lighting).unwrap();
        // The albedo int S(wi, wo) dwi of the model itself, by a finer rule in another frame
        // (Gauss-Legendre in the local frame's z, not the tangent's).
        let (nodes, n_phi) = (gauss_legendre(512), 1024);
        let mut albedo = [0.0; 3];
        let local_wo = V3::new(s, (1.0 - s * s).sqrt(), 0.0);
        for (z, wz) in nodes {
            let r = (1.0 - z * z).sqrt();
            for j in 0..n_phi {
                let phi = 2.0 * PI * (j as f64 + 0.5) / n_phi as f64;
                let wi = V3::new(r * phi.cos(), r * phi.sin(), z);
                let value = model.eval(&Query::far(wi, local_wo));
                for c in 0..3 {
                    albedo[c] += wz * 2.0 * PI / n_phi as f64 * value[c];
                }
            }
        }
        for c in 0..3 {
            let expected = radiance[c] * albedo[c];
            let error = (shaded[c] - expected).abs() / expected;
            println!(
                "sin theta_r {s}: channel {c}: {} against {expected} ({error:.1e})",
                shaded[c]
            );
            assert!(
                error < 2e-4,
                "sin theta_r {s}, channel {c}: {} against {expected}",
                shaded[c]
            );
        }
    }
}

#[test]
fn the_directional_light_is_equation_9() {
    let model = Gerard::new(
        &marschner(-5.0, 7.5, BROWN),
        GerardLobe::Printed,
        GERARD_K_TT,
        GERARD_K_TRT,
    )
    .unwrap();
    let norm = (4.0 * PI).sqrt();
    // V = 1 everywhere plus a band-1 term: V(wl) known in closed form.
    let v = [0.8 * norm, 0.0, 0.3, 0.0];
    let zero = [0.0];
    for bias in [0.0, 0.25] {
        let shade = shading(bias);
        // A viewer along the tangent has no azimuth, where the model's S is not continuous:
        // frames that differ by rounding give different values there.
        let defined = configurations()
            .into_iter()
            .filter(|(t, wo)| t.dot(*wo).abs() < 1.0 - 1e-9);
        for (tangent, wo) in defined {
            let light = V3::new(0.36, -0.48, 0.8);
            let point = ShadedPoint {
                tangent,
                wo,
                transmittance: &v,
            };
            let lighting = Lighting {
                environment: [&zero, &zero, &zero],
                light,
                light_radiance: [2.0, 1.0, 0.5],
            };
            let shaded = shade.shade(&point, &lighting).unwrap();
            // Y_10 = sqrt(3 / (4 pi)) z.
            let visible = 0.8 + 0.3 * (3.0 / (4.0 * PI)).sqrt() * light.z;
            let visible = ((visible - bias) / (1.0 - bias)).max(0.0);
            let [wi, wo_local] = local_directions(tangent, light, wo);
            let s = model.eval(&Query::far(wi, wo_local));
            for c in 0..3 {
                let expected = lighting.light_radiance[c] * visible * s[c];
                assert!(
                    (shaded[c] - expected).abs() <= 1e-12 * expected.abs().max(1e-12),
                    "{tangent:?} {wo:?} bias {bias} channel {c}: {} vs {expected}",
                    shaded[c]
                );
            }
        }
    }
}

#[test]
fn f32_shading_follows_f64() {
    let shade = shading(0.1);
    let lanes = shade.instantiate::<f32>();
    let v64 = coefficients(2, 0.7);
    let v32: Vec<f32> = v64.iter().map(|&x| x as f32).collect();
    let e64 = [
        coefficients(2, 1.3),
        coefficients(2, 2.1),
        coefficients(2, 0.4),
    ];
    let e32 = e64
        .clone()
        .map(|c| c.iter().map(|&x| x as f32).collect::<Vec<f32>>());
    for (tangent, wo) in configurations() {
        let light = V3::new(0.0, 0.6, 0.8);
        let a = shade
            .shade(
                &ShadedPoint {
                    tangent,
                    wo,
                    transmittance: &v64,
                },
                &Lighting {
                    environment: [&e64[0], &e64[1], &e64[2]],
                    light,
                    light_radiance: [1.0; 3],
                },
            )
            .unwrap();
        let f = |v: V3<f64>| V3::new(v.x as f32, v.y as f32, v.z as f32);
        let b = lanes
            .shade(
                &ShadedPoint {
                    tangent: f(tangent),
                    wo: f(wo),
                    transmittance: &v32,
                },
                &Lighting {
                    environment: [&e32[0], &e32[1], &e32[2]],
                    light: f(light),
                    light_radiance: [1.0; 3],
                },
            )
            .unwrap();
        let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for c in 0..3 {
            assert!(
                (f64::from(b[c]) - a[c]).abs() < 1e-3 * scale + 1e-6,
                "{a:?} {b:?}"
            );
        }
    }
}

#[test]
fn gerards_rgba8_layout_decodes_within_half_a_code() {
    let q = PhaseQuadrature { n_z: 48, n_phi: 96 };
    let tables = PhaseTable::<3>::bake(&clear_gerard(-5.0, 7.5), 128, &q).unwrap();
    let texture = tables.to_rgba8();
    assert_eq!((texture.width, texture.texels.len()), (128, 128 * 3));
    // The lobes are even in phi: Y_1-1's channel holds 0, exactly.
    assert!(texture.texels.iter().all(|t| t[1] == 128));
    let decoded = PhaseTable::<3>::from_rgba8(&texture).unwrap();
    for lobe in 0..3 {
        let a = tables.lobe(lobe).unwrap().table().data();
        let b = decoded.lobe(lobe).unwrap().table().data();
        let scales = texture.scales[lobe];
        for (k, (x, y)) in a.iter().zip(b).enumerate() {
            let scale = scales[[0, 2, 3][k % 3]];
            assert!(
                (x - y).abs() <= scale / 254.0 * 1.0001,
                "lobe {lobe} value {k}: {x} {y}"
            );
        }
        // Each channel's largest value is stored at code 1 or 255: exact up to rounding.
        assert!(scales.iter().any(|&s| s > 0.0));
    }
    let broken = |f: fn(&mut PhaseTextureRgba8)| {
        let mut t = texture.clone();
        f(&mut t);
        PhaseTable::<3>::from_rgba8(&t).is_err()
    };
    assert!(broken(|t| t.width = 1));
    assert!(broken(|t| {
        t.texels.pop();
    }));
    assert!(broken(|t| t.scales[1][2] = -1.0));
    assert!(broken(|t| t.scales[0][0] = f32::NAN));
}

#[test]
fn the_table_over_absorption_follows_gerards_exponents_in_closed_form() {
    // Gerard's own lobes attenuate by exactly e^(-k sigma_a) = u^k: the table over u must hold
    // a_R + a_TT u^k_TT + a_TRT u^k_TRT, up to linear interpolation in u.
    let q = PhaseQuadrature { n_z: 48, n_phi: 96 };
    let model_at = |sigma_a: f64| {
        let source = marschner(-5.0, 7.5, [sigma_a; 3]);
        Gerard::new(&source, GerardLobe::Printed, GERARD_K_TT, GERARD_K_TRT)
    };
    let (samples, transmissions) = (9, 33);
    let table = AbsorbingPhaseTable::<6>::bake(model_at, [samples, transmissions], &q).unwrap();
    let lobes = PhaseTable::<6>::bake(&clear_gerard(-5.0, 7.5), samples, &q).unwrap();
    for k in 0..samples {
        let s = -1.0 + 2.0 * k as f64 / (samples - 1) as f64;
        let a: Vec<[f64; 6]> = (0..3)
            .map(|p| lobes.lobe(p).unwrap().lookup_f64([s]))
            .collect();
        let largest = max_abs(a.iter().flatten().copied());
        for (sigma_a, tolerance) in [(0.0f64, 1e-6), (0.3, 4e-3), (1.1, 4e-3), (4.0, 4e-3)] {
            let u = (-sigma_a).exp();
            let got = table.table().lookup_f64([s, u]);
            for c in 0..6 {
                let expected = a[0][c]
                    + a[1][c] * gerard_attenuation(GERARD_K_TT, sigma_a)
                    + a[2][c] * gerard_attenuation(GERARD_K_TRT, sigma_a);
                assert!(
                    (got[c] - expected).abs() <= tolerance * largest,
                    "s {s} sigma_a {sigma_a} coefficient {c}: {} {expected}",
                    got[c]
                );
            }
        }
    }
    let row = vec![0.0f32; samples * 6];
    assert!(AbsorbingPhaseTable::<6>::from_rows(samples, vec![row.clone()]).is_err());
    assert!(
        AbsorbingPhaseTable::<6>::from_rows(samples, vec![row.clone(), row[1..].to_vec()]).is_err()
    );
    assert!(AbsorbingPhaseTable::<6>::from_rows(samples, vec![row.clone(), row]).is_ok());
    assert!(AbsorbingPhaseTable::<4>::bake(model_at, [9, 9], &q).is_err());
    assert_eq!(
        AbsorbingPhaseTable::<6>::sigma_a_of_row(0, 5),
        MAX_TABULATED_SIGMA_A
    );
    assert_eq!(AbsorbingPhaseTable::<6>::sigma_a_of_row(4, 5), 0.0);
}

#[test]
fn the_traced_shading_is_the_f32_shading_bit_for_bit() {
    let shade = shading(0.1);
    let environment = [
        coefficients(3, 1.3),
        coefficients(3, 2.1),
        coefficients(3, 0.4),
    ];
    let graph = trace_shade(&shade, 2, &environment).unwrap();
    let lanes = shade.instantiate::<f32>();
    let e32 = environment
        .clone()
        .map(|c| c.iter().map(|&x| x as f32).collect::<Vec<f32>>());
    let v32: Vec<f32> = coefficients(2, 0.7).iter().map(|&x| x as f32).collect();
    for (tangent, wo) in configurations() {
        let f = |v: V3<f64>| V3::new(v.x as f32, v.y as f32, v.z as f32);
        let (tangent, wo, light) = (f(tangent), f(wo), V3::new(0.0f32, 0.6, 0.8));
        let expected = lanes
            .shade(
                &ShadedPoint {
                    tangent,
                    wo,
                    transmittance: &v32,
                },
                &Lighting {
                    environment: [&e32[0], &e32[1], &e32[2]],
                    light,
                    light_radiance: [1.0, 2.0, 0.5],
                },
            )
            .unwrap();
        let mut inputs = vec![
            tangent.x, tangent.y, tangent.z, wo.x, wo.y, wo.z, light.x, light.y, light.z, 1.0, 2.0,
            0.5,
        ];
        inputs.extend_from_slice(&v32);
        let got = graph.eval_f32(&inputs);
        assert_eq!(
            got.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            expected.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            "{got:?} {expected:?}"
        );
    }
    assert!(trace_shade(&shade, 6, &environment).is_err());
    let uneven = [
        coefficients(3, 1.0),
        coefficients(2, 1.0),
        coefficients(3, 1.0),
    ];
    assert!(trace_shade(&shade, 2, &uneven).is_err());
    let too_many = [
        coefficients(6, 1.0),
        coefficients(6, 1.0),
        coefficients(6, 1.0),
    ];
    assert!(trace_shade(&shade, 2, &too_many).is_err());
}
