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
    let samples = samples.max(2);
    let phi: Vec<f64> = (0..samples)
        .map(|k| core::f64::consts::PI * (2.0 * k as f64 / (samples - 1) as f64 - 1.0))
        .collect();
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
