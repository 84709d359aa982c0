//! Trace tests of the real-time models' closed forms (`hairmath::models`).

use super::*;
use hairmath::models::{
    d_karis, gerard_attenuation, gerard_eq8_trt_corrected, gerard_eq8_trt_printed, gerard_hg_g,
    h_tt_karis, hg_g_normalised, inverse_eta_prime_karis, offset_attenuation,
    scaled_eta_prime_karis, tt_gaussian, EtaPrimeCoefficients, ExpCosCoefficients, HTtCoefficients,
    Transmitted, GERARD_K_TRT, GERARD_K_TT, KARIS_D_TRT_TABLE, KARIS_D_TT_TABLE,
    KARIS_ETA_PRIME_TABLE, KARIS_H_TT_TABLE, REFIT_D_TRT_TABLE, REFIT_D_TT_TABLE,
    REFIT_ETA_PRIME_TABLE, REFIT_H_TT_TABLE,
};
use std::f64::consts::FRAC_PI_4;

/// Absorption exponents k: none, Gerard's 4 and 11/2, and the largest the fits search (16).
const K: Arg = arg(0.0, 16.0, &[0.0, GERARD_K_TT, GERARD_K_TRT, 16.0]);
/// `a = 1/eta'` of Karis' h_TT: 0 (grazing), 1/1.55, and just below 1 (eta' near 1).
const INVERSE_ETA_PRIME: Arg = arg(0.0, 0.9999, &[0.0, 1.0 / 1.55, 0.9999]);
/// Heights and sharpnesses of Frostbite's TT Gaussians (the fitted tables span a in
/// [0.16, 0.68] and b in [0.0055, 1.47]); b = 0 is the flat limit.
const GAUSSIAN_A: Arg = arg(0.0, 1.0, &[0.0, 0.678, 1.0]);
const GAUSSIAN_B: Arg = arg(0.0, 2.0, &[0.0, 0.0055, 1.47]);

/// h, sigma_a, sin theta, cos theta, eta of Frostbite's single-offset attenuation: every
/// combination of h = -1, 0, 1, sigma_a = 0, 10, grazing and normal incidence, eta = 1.0001
/// and 2.5 first, then random rows (one argument in four a special value, the offsets
/// Frostbite and the refits use included).
fn offset_rows() -> Vec<Vec<f32>> {
    let mut first = Vec::new();
    for h in [-1.0, 0.0, 1.0] {
        for sigma_a in [0.0, 10.0] {
            for [sin, cos] in [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]] {
                for eta in [1.0001, 2.5] {
                    first.push(vec![h, sigma_a, sin, cos, eta]);
                }
            }
        }
    }
    let offsets = [
        Transmitted::Tt.published_offset(),
        Transmitted::Trt.published_offset(),
        Transmitted::Tt.refit_offset(),
        Transmitted::Trt.refit_offset(),
    ];
    listed_then(first, |g| {
        let h = match g.below(4) {
            0 => offsets[g.below(offsets.len())],
            _ => g.pick(&SIN),
        };
        [
            vec![h, g.pick(&SIGMA_A)],
            g.sin_cos().to_vec(),
            vec![g.pick(&ETA)],
        ]
        .concat()
    })
}

traced_tests! {
    lobe_hg_g_of_beta ["gerard_hg_g", "hg_g_normalised"] {
        // Widths inside and outside the closed forms' domain [1, 45] degrees (clamped).
        const WIDTHS: Arg = arg(0.0, 1.2, &[0.0, 0.017453292, FRAC_PI_4, 1e-6, 3.0]);
        case!("gerard_hg_g", scalars(&[WIDTHS]), |x| vec![gerard_hg_g(x[0])]);
        case!("hg_g_normalised", scalars(&[WIDTHS]), |x| vec![hg_g_normalised(x[0])]);
    }
    gerard_absorption ["gerard_attenuation", "gerard_eq8_trt_printed", "gerard_eq8_trt_corrected"] {
        // sigma_a = 0 (no absorption) and 10 (underflow to 0 for the largest k).
        case!("gerard_attenuation", scalars(&[K, SIGMA_A]), |x| {
            vec![gerard_attenuation(x[0], x[1])]
        });
        // eta = 1.0001, where the printed exponent is most negative.
        case!("gerard_eq8_trt", scalars(&[ETA]), |x| {
            vec![gerard_eq8_trt_printed(x[0]), gerard_eq8_trt_corrected(x[0])]
        });
    }

    // Karis' coefficients are named tables, read as the models read them: one trace per set.
    karis_eta_prime ["scaled_eta_prime_karis", "inverse_eta_prime_karis"] {
        // cos theta_d in [0, 1], grazing (0) and normal (1) included.
        for (name, table) in [("published", &KARIS_ETA_PRIME_TABLE), ("refit", &REFIT_ETA_PRIME_TABLE)] {
            case!(format!("karis eta' ({name})"), scalars(&[UNIT]), |x| {
                let c = EtaPrimeCoefficients::named(table);
                vec![scaled_eta_prime_karis(x[0], c), inverse_eta_prime_karis(x[0], c)]
            });
        }
    }
    karis_d ["d_karis"] {
        // phi = 0 and +-pi, the lobes' peaks.
        for (name, table) in [
            ("published TT", &KARIS_D_TT_TABLE),
            ("published TRT", &KARIS_D_TRT_TABLE),
            ("refit TT", &REFIT_D_TT_TABLE),
            ("refit TRT", &REFIT_D_TRT_TABLE),
        ] {
            case!(format!("d_karis ({name})"), scalars(&[ANGLE]), |x| {
                vec![d_karis(x[0], ExpCosCoefficients::named(table))]
            });
        }
    }
    karis_h_tt ["h_tt_karis"] {
        for (name, table) in [("published", &KARIS_H_TT_TABLE), ("refit", &REFIT_H_TT_TABLE)] {
            case!(format!("h_tt_karis ({name})"), scalars(&[INVERSE_ETA_PRIME, ANGLE]), |x| {
                vec![h_tt_karis(x[0], x[1], HTtCoefficients::named(table))]
            });
            // As a shader chains them: a = 1/eta' from cos theta_d (grazing gives a = 0), with
            // literal coefficients this time.
            let (eta_prime, c) = (EtaPrimeCoefficients::PUBLISHED, HTtCoefficients::PUBLISHED);
            case!(format!("h_tt_karis of eta' ({name})"), scalars(&[UNIT, ANGLE]), |x| {
                let a = inverse_eta_prime_karis(x[0], eta_prime.to_real());
                vec![h_tt_karis(a, x[1], c.to_real())]
            });
        }
    }

    frostbite_tt_gaussian ["tt_gaussian"] {
        // phi = 0 and +-pi (the peak).
        case!("tt_gaussian", scalars(&[ANGLE, GAUSSIAN_A, GAUSSIAN_B]), |x| {
            vec![tt_gaussian(x[0], x[1], x[2])]
        });
    }
    frostbite_offset_attenuation ["offset_attenuation"] {
        // The lobe is a per-shader constant: one trace per lobe.
        for path in [Transmitted::Tt, Transmitted::Trt] {
            case!(format!("offset_attenuation({})", path.name()), offset_rows(), |x| {
                vec![offset_attenuation(path, x[0], x[1], x[2], x[3], x[4])]
            });
        }
    }
}
