//! Trace tests of the real-time models' closed forms (`hairmath::models`).

use super::*;
use hairmath::models::{
    gerard_attenuation, gerard_eq8_trt_corrected, gerard_eq8_trt_printed, gerard_hg_g,
    hg_g_normalised, GERARD_K_TRT, GERARD_K_TT,
};
use std::f64::consts::FRAC_PI_4;

/// Absorption exponents k: none, Gerard's 4 and 11/2, and the largest the fits search (16).
const K: Arg = arg(0.0, 16.0, &[0.0, GERARD_K_TT, GERARD_K_TRT, 16.0]);

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
}
