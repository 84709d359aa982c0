//! What the render tests share: the lights, the far field, the channel-wise relative error, and
//! a lone strand's albedo under a constant sky by an independent product Gauss rule.

use glam::{DVec3, Vec3};
use hairmath::bcsdf::{Bcsdf, ChiangFarField, FarFieldRule, Query};
use hairmath::geometry::{local_directions, V3};
use hairmath::params::HairParams;
use hairmath::quadrature::SphereRule;
use hairmath::render::{DirectionalLight, Sky};

/// The sky of radiance `radiance` in every direction.
pub fn constant_sky(radiance: f64) -> Sky {
    Sky {
        zenith: [radiance; 3],
        horizon: [radiance; 3],
        ground: [radiance; 3],
        sun_radiance: [0.0; 3],
        ..Sky::default()
    }
}

/// A directional light that gives no light.
pub fn dark() -> DirectionalLight {
    DirectionalLight {
        direction: DVec3::Y,
        radiance: [0.0; 3],
    }
}

/// The default hair's far field with `nodes` Gauss-Legendre nodes.
pub fn far_field(nodes: usize) -> ChiangFarField<f64> {
    ChiangFarField::with_rule(
        &HairParams::default(),
        &FarFieldRule::gauss_legendre(nodes).unwrap(),
    )
}

/// The largest relative difference of a channel of `a` from `b`'s.
pub fn relative(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3)
        .map(|c| (a[c] - b[c]).abs() / b[c].abs())
        .fold(0.0, f64::max)
}

/// The radiance a strand of tangent `tangent` sends to `wo = +Z` under a sky of radiance
/// `radiance`, unoccluded: `radiance` times the integral of `S(w, +Z)` over the sphere, by a
/// product Gauss rule (64 x 8 in theta, 512 in phi) in the fibre's frame.
pub fn albedo_radiance(model: &dyn Bcsdf<f64>, tangent: Vec3, radiance: f64) -> [f64; 3] {
    let t = V3::new(
        f64::from(tangent.x),
        f64::from(tangent.y),
        f64::from(tangent.z),
    );
    let wo = V3::new(0.0, 0.0, 1.0);
    let mut out = [0.0; 3];
    for &(w, weight) in &SphereRule::new(64, 8, 512).nodes {
        let [wi, wo] = local_directions(t, w, wo);
        let s = model.eval(&Query::far(wi, wo));
        for c in 0..3 {
            out[c] += radiance * weight * s[c];
        }
    }
    out
}
