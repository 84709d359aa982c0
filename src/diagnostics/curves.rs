//! Lobe curves: a model's S against the relative azimuth at fixed inclinations, the data of
//! the lobe plots of `hairmath report --plots`.

use crate::bcsdf::{Bcsdf, Query};
use crate::geometry::local_direction;

/// S of one model against phi at one inclination: `theta_i = theta`, `theta_o = -theta`
/// (the specular cone of R and the forward direction of TT pass through these pairs), wo at
/// azimuth 0 and wi at azimuth `phi`, far-field queries (h = 0).
#[derive(Clone, Debug, PartialEq)]
pub struct LobeCurve {
    /// The inclination theta, in degrees.
    pub theta_deg: f64,
    /// The relative azimuths phi (radians), from -pi to pi.
    pub phi: Vec<f64>,
    /// S per azimuth, per channel.
    pub value: Vec<[f64; 3]>,
}

/// [`LobeCurve`]s of `model` at each of `thetas_deg`, on `samples` azimuths evenly spaced
/// from -pi to pi (both ends included; at least 2).
pub fn lobe_curves<M: Bcsdf<f64> + ?Sized>(
    model: &M,
    thetas_deg: &[f64],
    samples: usize,
) -> Vec<LobeCurve> {
    let phi = symmetric_grid(core::f64::consts::PI, samples);
    thetas_deg
        .iter()
        .map(|&theta_deg| {
            let theta = theta_deg.to_radians();
            let wo = local_direction(-theta.sin(), theta.cos(), 0.0);
            let value = phi
                .iter()
                .map(|&p| {
                    let wi = local_direction(theta.sin(), theta.cos(), p);
                    model.eval(&Query::far(wi, wo))
                })
                .collect();
            LobeCurve {
                theta_deg,
                phi: phi.clone(),
                value,
            }
        })
        .collect()
}

/// S of one model against the inclination of `wi` at one relative azimuth: `wo`
/// perpendicular to the fibre (`theta_o = 0`, azimuth 0), `wi` at `theta_i` from -90 to 90
/// degrees and azimuth `phi`, far-field queries (h = 0).
#[derive(Clone, Debug, PartialEq)]
pub struct ThetaCurve {
    /// The relative azimuth phi, in degrees.
    pub phi_deg: f64,
    /// The inclinations theta_i (radians), from -pi/2 to pi/2.
    pub theta: Vec<f64>,
    /// S per inclination, per channel.
    pub value: Vec<[f64; 3]>,
}

/// [`ThetaCurve`]s of `model` at each of `phis_deg`, on `samples` inclinations evenly spaced
/// from -pi/2 to pi/2 (both ends included; at least 2).
pub fn theta_curves<M: Bcsdf<f64> + ?Sized>(
    model: &M,
    phis_deg: &[f64],
    samples: usize,
) -> Vec<ThetaCurve> {
    let theta = symmetric_grid(core::f64::consts::FRAC_PI_2, samples);
    let wo = local_direction(0.0, 1.0, 0.0);
    phis_deg
        .iter()
        .map(|&phi_deg| {
            let phi = phi_deg.to_radians();
            let value = theta
                .iter()
                .map(|&t| model.eval(&Query::far(local_direction(t.sin(), t.cos(), phi), wo)))
                .collect();
            ThetaCurve {
                phi_deg,
                theta: theta.clone(),
                value,
            }
        })
        .collect()
}

/// `samples` (at least 2) values evenly spaced from `-half` to `half`, both ends included.
fn symmetric_grid(half: f64, samples: usize) -> Vec<f64> {
    let samples = samples.max(2);
    (0..samples)
        .map(|k| half * (2.0 * k as f64 / (samples - 1) as f64 - 1.0))
        .collect()
}
