//! The three shadings of a hit point seen from `wo = +Z` (module documentation of
//! [`crate::render`]): the reference, Gerard's and a classic model given Gerard's inputs.

use super::camera::Hit;
use super::lighting::{DirectionalLight, Sky};
use crate::bcsdf::{Bcsdf, Query};
use crate::error::ParamError;
use crate::geometry::{local_directions, V3};
use crate::models::gerard_sh::{GerardSh, Lighting, ShadedPoint};
use crate::quadrature::SphereRule;
use crate::sh::eval_sh_f64_into;
use crate::strands::occluders::Occluders;
use crate::strands::transmittance::Transmittance;
use glam::{DVec3, Vec3};

/// `S(w, +Z)` of `model` at a hit of tangent `tangent` (world-space directions).
pub(super) fn scattered(model: &dyn Bcsdf<f64>, tangent: Vec3, w: DVec3) -> [f64; 3] {
    let t = V3::new(
        f64::from(tangent.x),
        f64::from(tangent.y),
        f64::from(tangent.z),
    );
    let wo = V3::new(0.0, 0.0, 1.0);
    let [wi, wo] = local_directions(t, V3::new(w.x, w.y, w.z), wo);
    model.eval(&Query::far(wi, wo))
}

/// Adds `scale * a * b` to `out`, channel by channel.
pub(super) fn accumulate(out: &mut [f64; 3], scale: f64, a: [f64; 3], b: [f64; 3]) {
    for c in 0..3 {
        out[c] += scale * a[c] * b[c];
    }
}

/// The reference radiance at `hit`: the integral over the sphere of `L_env V S` with the exact
/// `V` (rays through `occluders`, the hit's own strand excluded) and `model` as `S`, by `rule`,
/// plus the light's `L V(wl) S(wl, wo)`.
pub fn reference_radiance(
    hit: &Hit,
    occluders: &Occluders,
    model: &dyn Bcsdf<f64>,
    (sky, light): (&Sky, &DirectionalLight),
    rule: &SphereRule,
) -> [f64; 3] {
    let visible =
        |w: DVec3| f64::from(occluders.transmittance(hit.point, w.as_vec3(), Some(hit.strand)));
    let mut out = [0.0; 3];
    for &(w, weight) in &rule.nodes {
        let w = DVec3::new(w.x, w.y, w.z);
        let v = visible(w);
        if v > 0.0 {
            accumulate(
                &mut out,
                weight * v,
                sky.radiance(w),
                scattered(model, hit.tangent, w),
            );
        }
    }
    let v = visible(light.direction);
    accumulate(
        &mut out,
        v,
        light.radiance,
        scattered(model, hit.tangent, light.direction),
    );
    out
}

/// The transmittance's coefficients at `hit` for bands `l <= lmax`: those of the segment's two
/// points interpolated linearly along it (`baked` must hold both points).
///
/// # Errors
/// [`ParamError::OutOfRange`] if `lmax` exceeds the bake's or `baked` does not hold the
/// segment's points.
pub fn interpolated_transmittance(
    hit: &Hit,
    baked: &Transmittance,
    lmax: usize,
) -> Result<Vec<f64>, ParamError> {
    ParamError::check(
        "transmittance lmax",
        lmax as f64,
        "must be at most the bake's",
        |l| l <= baked.lmax as f64,
    )?;
    let start = hit.start as usize;
    ParamError::check(
        "segment point",
        start as f64,
        "must be baked with its successor",
        |_| baked.vertices.start <= start && start + 1 < baked.vertices.end,
    )?;
    let k = start - baked.vertices.start;
    let (a, b) = (baked.vertex(k), baked.vertex(k + 1));
    let t = f64::from(hit.along);
    Ok(a.iter()
        .zip(b)
        .take((lmax + 1) * (lmax + 1))
        .map(|(&a, &b)| (1.0 - t) * f64::from(a) + t * f64::from(b))
        .collect())
}

/// Gerard's radiance at `hit` ([`GerardSh::shade`]) with the transmittance coefficients
/// `transmittance` and the sky's coefficients per channel `sky`.
///
/// # Errors
/// As [`GerardSh::shade`].
pub fn gerard_radiance<const C: usize>(
    hit: &Hit,
    transmittance: &[f64],
    shading: &GerardSh<f64, C>,
    sky: &[Vec<f64>; 3],
    light: &DirectionalLight,
) -> Result<[f64; 3], ParamError> {
    let d = |v: Vec3| V3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z));
    let point = ShadedPoint {
        tangent: d(hit.tangent),
        wo: V3::new(0.0, 0.0, 1.0),
        transmittance,
    };
    let l = light.direction;
    let lighting = Lighting {
        environment: [&sky[0], &sky[1], &sky[2]],
        light: V3::new(l.x, l.y, l.z),
        light_radiance: light.radiance,
    };
    shading.shade(&point, &lighting)
}

/// A classic model (`S` any [`Bcsdf`]) lit as Gerard's shading is, from the same inputs: the
/// sky's radiance times `V` reconstructed from the transmittance's coefficients, integrated by
/// a [`SphereRule`], and the light times `V(wl)` with the bias of Gerard's eq. 10.
pub struct ClassicShading<'a> {
    model: &'a (dyn Bcsdf<f64> + Sync),
    rule: &'a SphereRule,
    sky: Vec<[f64; 3]>,
    basis: Vec<f64>,
    lmax: usize,
    stride: usize,
    bias: f64,
}

impl<'a> ClassicShading<'a> {
    /// The shading of `model` under `sky` by `rule`, `V` from coefficients of bands
    /// `l <= lmax`, the light's `V` with `bias`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if `lmax` exceeds the SH evaluator's limit or `bias` is
    /// outside `[0, 1)`.
    pub fn new(
        model: &'a (dyn Bcsdf<f64> + Sync),
        rule: &'a SphereRule,
        sky: &Sky,
        lmax: usize,
        bias: f64,
    ) -> Result<Self, ParamError> {
        let bias = ParamError::check("bias", bias, "must be in [0, 1)", |b| {
            (0.0..1.0).contains(&b)
        })?;
        let stride = (lmax + 1) * (lmax + 1);
        let mut basis = vec![0.0; stride * rule.nodes.len()];
        for ((w, _), row) in rule.nodes.iter().zip(basis.chunks_exact_mut(stride)) {
            eval_sh_f64_into(lmax, DVec3::new(w.x, w.y, w.z), row)?;
        }
        Ok(Self {
            model,
            rule,
            sky: rule
                .nodes
                .iter()
                .map(|(w, _)| sky.radiance(DVec3::new(w.x, w.y, w.z)))
                .collect(),
            basis,
            lmax,
            stride,
            bias,
        })
    }

    /// The radiance at `hit` with the transmittance coefficients `transmittance`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if `transmittance` does not hold the shading's bands.
    pub fn radiance(
        &self,
        hit: &Hit,
        transmittance: &[f64],
        light: &DirectionalLight,
    ) -> Result<[f64; 3], ParamError> {
        ParamError::check(
            "transmittance coefficients",
            transmittance.len() as f64,
            "must be (lmax + 1)^2 of the classic shading's lmax",
            |n| n == self.stride as f64,
        )?;
        let dot = |y: &[f64]| y.iter().zip(transmittance).map(|(y, c)| y * c).sum::<f64>();
        let mut out = [0.0; 3];
        let rows = self.basis.chunks_exact(self.stride);
        for ((&(w, weight), y), &l) in self.rule.nodes.iter().zip(rows).zip(&self.sky) {
            let s = scattered(self.model, hit.tangent, DVec3::new(w.x, w.y, w.z));
            accumulate(&mut out, weight * dot(y), l, s);
        }
        let mut y = vec![0.0; self.stride];
        let wl = light.direction;
        eval_sh_f64_into(self.lmax, wl, &mut y)?;
        let visible = ((dot(&y) - self.bias) / (1.0 - self.bias)).max(0.0);
        accumulate(
            &mut out,
            visible,
            light.radiance,
            scattered(self.model, hit.tangent, wl),
        );
        Ok(out)
    }
}
