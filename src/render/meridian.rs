//! The reference radiance by great circles: the integral over the sphere of
//! `L_env(w) V(x, w) S(w, wo)` with `V` integrated in closed form along each circle of a pencil
//! ([`crate::strands::pencil`]), so that the strands' thin shadows are measured exactly along
//! the circles and only sampled across them.
//!
//! The pencil's pole is orthogonal to the tangent: the strands near the shading point run
//! nearly parallel to its own, so they cross the circles instead of running along them (a pole
//! along the tangent, measured, converged several times slower). With the pencil's angles
//! `(psi, u)`, `dw = |sin u| du dpsi`; across the circles the rule is the midpoint rule in
//! `psi`. Along circle `j`, `V` is piecewise constant, its breakpoints the ends of the arcs
//! that cross the cylinders. `S`, the costly factor, is sampled on a coarser pencil
//! ([`MeridianRule::scattering_circles`] circles of [`MeridianRule::samples`] angles
//! `u = (k + 1/2) 2 pi / samples`) and interpolated by cubics across the circles and then along
//! them; the sky is evaluated exactly, its step at the horizon a breakpoint. The integrand
//! without `V` is integrated on each panel between consecutive breakpoints (samples, horizon,
//! `|sin u|`'s kinks) by its cubic at the 4 Gauss-Legendre nodes, whose antiderivative gives
//! the integral up to every arc's end.
//!
//! Measured (`examples/reference_convergence.rs`): the error falls about 4 times per doubling
//! of the circles, where a rule of points falls as `N^(-1/2)`.

use super::camera::Hit;
use super::lighting::{DirectionalLight, Sky, UP};
use super::shading::{accumulate, scattered};
use crate::bcsdf::Bcsdf;
use crate::error::ParamError;
use crate::quadrature::gauss_legendre;
use crate::strands::occluders::Occluders;
use crate::strands::pencil::{CircleSpan, Crossing, GreatCircle, Pencil};
use core::f64::consts::{PI, TAU};

/// Nodes of the Gauss-Legendre rule on each panel: exact for the cubic the panel's
/// antiderivative is built from (the Legendre coefficients `P_0..P_3`).
const PANEL_NODES: usize = 4;

/// How finely the reference by great circles integrates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeridianRule {
    /// Circles of the pencil along which `V` is integrated (at least 1).
    pub circles: usize,
    /// Circles along which `S` is sampled (at least 4), interpolated by cubics across them.
    pub scattering_circles: usize,
    /// Samples of `S` per circle (at least 8), interpolated by cubics along it; the integrand
    /// is integrated by a 4-point rule between consecutive samples.
    pub samples: usize,
}

impl MeridianRule {
    /// The rule, checked.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the field outside its domain.
    pub fn new(
        circles: usize,
        scattering_circles: usize,
        samples: usize,
    ) -> Result<Self, ParamError> {
        ParamError::check("circles", circles as f64, "must be at least 1", |n| {
            n >= 1.0
        })?;
        ParamError::check(
            "scattering circles",
            scattering_circles as f64,
            "must be at least 4",
            |n| n >= 4.0,
        )?;
        ParamError::check("samples", samples as f64, "must be at least 8", |n| {
            n >= 8.0
        })?;
        Ok(Self {
            circles,
            scattering_circles,
            samples,
        })
    }

    /// `circles` circles for `V` and the default's proportions for `S`: on `circles / 8`
    /// circles (at least 4) of `circles / 16` samples (at least 8).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if `circles` is 0.
    pub fn with_circles(circles: usize) -> Result<Self, ParamError> {
        Self::new(circles, (circles / 8).max(4), (circles / 16).max(8))
    }

    /// Half as many of each (within the domain), for a convergence check.
    pub fn halved(&self) -> Self {
        Self {
            circles: (self.circles / 2).max(1),
            scattering_circles: (self.scattering_circles / 2).max(4),
            samples: (self.samples / 2).max(8),
        }
    }
}

impl Default for MeridianRule {
    /// 2048 circles for `V`; `S` on 256 circles of 128 samples (32768 evaluations).
    fn default() -> Self {
        Self {
            circles: 2048,
            scattering_circles: 256,
            samples: 128,
        }
    }
}

/// A change of `V` along a circle: at angle `u`, a cylinder of transmission `transmission`
/// starts (`enters`) or stops occluding.
#[derive(Clone, Copy, Debug)]
struct Event {
    u: f64,
    transmission: f64,
    enters: bool,
}

/// The transmittance along a circle as it is swept: the product of the transmissions of the
/// cylinders crossed, those of transmission 0 counted apart so that leaving one restores it.
struct Sweep {
    product: f64,
    opaque: usize,
}

impl Sweep {
    fn apply(&mut self, event: &Event) {
        match (event.transmission == 0.0, event.enters) {
            (true, true) => self.opaque += 1,
            (true, false) => self.opaque -= 1,
            (false, true) => self.product *= event.transmission,
            (false, false) => self.product /= event.transmission,
        }
    }

    fn value(&self) -> f64 {
        if self.opaque > 0 {
            0.0
        } else {
            self.product
        }
    }
}

/// The weights of the cubic through four equally spaced nodes at `-1, 0, 1, 2` (Lagrange's
/// form), at `t`.
fn cubic_weights(t: f64) -> [f64; 4] {
    [
        -t * (t - 1.0) * (t - 2.0) / 6.0,
        (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0,
        -(t + 1.0) * t * (t - 2.0) / 2.0,
        (t + 1.0) * t * (t - 1.0) / 6.0,
    ]
}

/// The periodic index and weights of the cubic through the four nodes around `position` (in
/// units of the spacing, nodes at the integers).
fn periodic_cubic(position: f64) -> (isize, [f64; 4]) {
    let k = position.floor();
    (k as isize - 1, cubic_weights(position - k))
}

/// `S` sampled at `samples` angles `u_k = (k + 1/2) 2 pi / samples` of each of the pencil's
/// `circles` circles `psi_c = (c + 1/2) pi / circles`: a smooth function on the sphere but for
/// its step at the tangent, interpolated by cubics across and along the circles.
struct ScatteringGrid {
    values: Vec<[f64; 3]>,
    circles: usize,
    samples: usize,
}

impl ScatteringGrid {
    /// The value at sample `k` of circle `c` for any integers: circle `c + circles` is circle
    /// `c` run backwards (`d(u, psi + pi) = d(-u, psi)`).
    fn value(&self, c: isize, k: isize) -> [f64; 3] {
        let (n, m) = (self.circles as isize, self.samples as isize);
        let (turns, c) = (c.div_euclid(n), c.rem_euclid(n));
        let k = if turns % 2 == 0 { k } else { -1 - k };
        self.values[c as usize * self.samples + k.rem_euclid(m) as usize]
    }

    /// The samples along the circle at angle `psi`, interpolated across the circles.
    fn along(&self, psi: f64) -> Samples {
        let (first, weights) = periodic_cubic(psi * self.circles as f64 / PI - 0.5);
        let values = (0..self.samples as isize)
            .map(|k| {
                let mut out = [0.0; 3];
                for (i, w) in (0..).zip(weights) {
                    accumulate(&mut out, w, [1.0; 3], self.value(first + i, k));
                }
                out
            })
            .collect();
        Samples { values }
    }
}

/// `S` at the angles `u_k` of one circle, interpolated by periodic cubics along it.
struct Samples {
    values: Vec<[f64; 3]>,
}

impl Samples {
    fn spacing(&self) -> f64 {
        TAU / self.values.len() as f64
    }

    fn at(&self, u: f64) -> [f64; 3] {
        let m = self.values.len() as isize;
        let (first, weights) = periodic_cubic(u / self.spacing() - 0.5);
        let mut out = [0.0; 3];
        for (i, w) in (0..).zip(weights) {
            accumulate(
                &mut out,
                w,
                [1.0; 3],
                self.values[(first + i).rem_euclid(m) as usize],
            );
        }
        out
    }

    /// The angles in `[0, 2 pi]` between which the interpolant is one cubic.
    fn breakpoints(&self) -> impl Iterator<Item = f64> + '_ {
        let h = self.spacing();
        (0..self.values.len())
            .map(move |k| (k as f64 + 0.5) * h)
            .chain([0.0, TAU])
    }
}

/// The reference radiance at `hit` ([`super::shading::reference_radiance`]'s integral) by
/// `rule` (module documentation), plus the light's `L V(wl) S(wl, wo)` with `V` by one ray.
///
/// # Errors
/// [`ParamError::BadVector`] if the hit's tangent is zero or not finite.
pub fn meridian_radiance(
    hit: &Hit,
    occluders: &Occluders,
    model: &dyn Bcsdf<f64>,
    (sky, light): (&Sky, &DirectionalLight),
    rule: &MeridianRule,
) -> Result<[f64; 3], ParamError> {
    let tangent = hit.tangent.as_dvec3();
    let pole = tangent
        .try_normalize()
        .ok_or(ParamError::BadVector {
            name: "tangent",
            x: tangent.x,
            y: tangent.y,
            z: tangent.z,
            allowed: "must be finite and non-zero",
        })?
        .any_orthonormal_vector();
    let pencil = Pencil::new(hit.point, pole, rule.circles)?;
    let coarse = Pencil::new(hit.point, pole, rule.scattering_circles)?;
    let grid = ScatteringGrid {
        values: (0..coarse.circles())
            .flat_map(|c| {
                let circle = coarse.circle(c);
                (0..rule.samples).map(move |k| {
                    let u = (k as f64 + 0.5) * TAU / rule.samples as f64;
                    scattered(model, hit.tangent, circle.direction(u))
                })
            })
            .collect(),
        circles: coarse.circles(),
        samples: rule.samples,
    };
    let crossings = circles_crossing(&pencil, occluders, hit.strand);
    let gauss = gauss_legendre(PANEL_NODES);
    let mut out = [0.0; 3];
    let mut events = Vec::new();
    for (j, cylinders) in crossings.per_circle.iter().enumerate() {
        let circle = pencil.circle(j);
        events.clear();
        let base = arcs(
            &circle,
            cylinders.iter().chain(&crossings.every_circle),
            occluders,
            &mut events,
        );
        let samples = grid.along(pencil.psi(j));
        let integrand = Antiderivative::new(&circle, &samples, sky, &gauss);
        let along = integrand.with_visibility(base, &mut events);
        accumulate(&mut out, PI / rule.circles as f64, [1.0; 3], along);
    }
    let visible =
        f64::from(occluders.transmittance(hit.point, light.direction.as_vec3(), Some(hit.strand)));
    let s = scattered(model, hit.tangent, light.direction);
    accumulate(&mut out, visible, light.radiance, s);
    Ok(out)
}

/// The cylinders each circle of a pencil may cross: other strands' that are not transparent.
struct CircleCylinders {
    per_circle: Vec<Vec<u32>>,
    every_circle: Vec<u32>,
}

fn circles_crossing(pencil: &Pencil, occluders: &Occluders, own_strand: u32) -> CircleCylinders {
    let n = pencil.circles();
    let mut out = CircleCylinders {
        per_circle: vec![Vec::new(); n],
        every_circle: Vec::new(),
    };
    for (i, cylinder) in occluders.cylinders().iter().enumerate() {
        if cylinder.strand == own_strand || cylinder.transmission >= 1.0 {
            continue;
        }
        let index = u32::try_from(i).expect("cylinder counts fit in u32");
        match pencil.circles_meeting(cylinder) {
            CircleSpan::All => out.every_circle.push(index),
            CircleSpan::Range { first, count } => {
                for k in 0..count {
                    out.per_circle[(first + k) % n].push(index);
                }
            }
        }
    }
    out
}

/// Pushes the events of the arcs along which `circle` crosses `cylinders` (indices into
/// `occluders`), each arc within `[0, 2 pi]`, and returns the product of the transmissions of
/// the cylinders every ray crosses.
fn arcs<'a>(
    circle: &GreatCircle,
    cylinders: impl Iterator<Item = &'a u32>,
    occluders: &Occluders,
    events: &mut Vec<Event>,
) -> f64 {
    let mut everywhere = 1.0;
    for &i in cylinders {
        let cylinder = &occluders.cylinders()[i as usize];
        let transmission = f64::from(cylinder.transmission);
        match circle.crossing(cylinder) {
            Crossing::None => {}
            Crossing::All => everywhere *= transmission,
            Crossing::Arc { start, end } => {
                let start_in_turn = start.rem_euclid(TAU);
                let end_in_turn = start_in_turn + (end - start);
                let mut push = |from: f64, to: f64| {
                    events.push(Event {
                        u: from,
                        transmission,
                        enters: true,
                    });
                    events.push(Event {
                        u: to,
                        transmission,
                        enters: false,
                    });
                };
                if end_in_turn > TAU {
                    push(start_in_turn, TAU);
                    push(0.0, end_in_turn - TAU);
                } else {
                    push(start_in_turn, end_in_turn);
                }
            }
        }
    }
    everywhere
}

/// The two angles of `circle` on the horizon (where [`Sky`] steps), in `[0, 2 pi)`.
fn horizon_crossings(circle: &GreatCircle) -> [f64; 2] {
    let u = (-circle.pole.dot(UP)).atan2(circle.across.dot(UP));
    [u, u + PI].map(|u| u.rem_euclid(TAU))
}

/// The antiderivative `G(u)` of the integrand without `V`, `g(u) = |sin u| L_env(d(u)) S(u)`,
/// along one circle: on each panel between consecutive breakpoints of `g` (the samples' cubics,
/// `|sin u|` at 0 and pi, the horizon), `g` is replaced by the cubic of its values at the
/// 4-point Gauss-Legendre nodes, whose integral from the panel's start is a polynomial.
struct Antiderivative {
    /// The panels' ends, increasing, from 0 to 2 pi.
    ends: Vec<f64>,
    /// `G` at each panel's start.
    before: Vec<[f64; 3]>,
    /// The Legendre coefficients of `g` on each panel, per channel.
    legendre: Vec<[[f64; 4]; 3]>,
}

impl Antiderivative {
    /// `gauss`: the [`PANEL_NODES`]-point Gauss-Legendre rule on `[-1, 1]`.
    fn new(circle: &GreatCircle, samples: &Samples, sky: &Sky, gauss: &[(f64, f64)]) -> Self {
        let mut ends: Vec<f64> = samples
            .breakpoints()
            .chain([PI])
            .chain(horizon_crossings(circle))
            .collect();
        ends.sort_by(f64::total_cmp);
        ends.dedup();
        let panels = ends.len() - 1;
        let mut out = Self {
            before: Vec::with_capacity(panels),
            legendre: Vec::with_capacity(panels),
            ends: Vec::new(),
        };
        let mut total = [0.0; 3];
        for pair in ends.windows(2) {
            let (mid, half) = (0.5 * (pair[1] + pair[0]), 0.5 * (pair[1] - pair[0]));
            let mut coefficients = [[0.0; 4]; 3];
            for &(x, w) in gauss {
                let u = mid + half * x;
                let radiance = sky.radiance(circle.direction(u));
                let (s, weight) = (samples.at(u), u.sin().abs());
                let p = legendre(x);
                for c in 0..3 {
                    let g = weight * radiance[c] * s[c];
                    for (k, p) in p.iter().enumerate() {
                        coefficients[c][k] += (2.0 * k as f64 + 1.0) / 2.0 * w * g * p;
                    }
                }
            }
            out.before.push(total);
            for c in 0..3 {
                total[c] += 2.0 * half * coefficients[c][0];
            }
            out.legendre.push(coefficients);
        }
        out.ends = ends;
        out
    }

    /// `G(u)` for `u` in `[0, 2 pi]`.
    fn at(&self, u: f64) -> [f64; 3] {
        let panel = self
            .ends
            .partition_point(|&e| e <= u)
            .clamp(1, self.legendre.len())
            - 1;
        let (a, b) = (self.ends[panel], self.ends[panel + 1]);
        let half = 0.5 * (b - a);
        let x = ((u - a) / half - 1.0).clamp(-1.0, 1.0);
        let p = legendre_integrals(x);
        let mut out = self.before[panel];
        for (out, coefficients) in out.iter_mut().zip(&self.legendre[panel]) {
            *out += half * coefficients.iter().zip(p).map(|(a, p)| a * p).sum::<f64>();
        }
        out
    }

    /// The integral of `g V` over the circle, `V` being `base` times the transmissions of the
    /// arcs open at `u` (`events`, sorted here).
    fn with_visibility(&self, base: f64, events: &mut [Event]) -> [f64; 3] {
        events.sort_by(|a, b| a.u.total_cmp(&b.u));
        let mut sweep = Sweep {
            product: base,
            opaque: 0,
        };
        let mut out = [0.0; 3];
        let (mut previous, mut g_previous) = (0.0, [0.0; 3]);
        for event in events.iter().chain(&[Event {
            u: TAU,
            transmission: 1.0,
            enters: true,
        }]) {
            if event.u > previous {
                let g = self.at(event.u);
                let visible = sweep.value();
                for c in 0..3 {
                    out[c] += visible * (g[c] - g_previous[c]);
                }
                (previous, g_previous) = (event.u, g);
            }
            sweep.apply(event);
        }
        out
    }
}

/// The Legendre polynomials `P_0..P_3` at `x`.
fn legendre(x: f64) -> [f64; 4] {
    [
        1.0,
        x,
        0.5 * (3.0 * x * x - 1.0),
        0.5 * x * (5.0 * x * x - 3.0),
    ]
}

/// The integrals from -1 to `x` of `P_0..P_3`: `x + 1` and `(P_(k+1)(x) - P_(k-1)(x)) / (2k + 1)`.
fn legendre_integrals(x: f64) -> [f64; 4] {
    let p4 = (35.0 * x.powi(4) - 30.0 * x * x + 3.0) / 8.0;
    let p = legendre(x);
    [
        x + 1.0,
        (p[2] - p[0]) / 3.0,
        (p[3] - p[1]) / 5.0,
        (p4 - p[2]) / 7.0,
    ]
}
