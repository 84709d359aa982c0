//! Trace tests of Gerard's spherical-harmonic shading (`hairmath::models::gerard_sh`): the
//! tangent frame, hard cases first (the viewer along the tangent, the tangent along each
//! axis); and the whole shading at bands l <= 1 (Gerard's phase tables, fetched as a texture)
//! with the transmittance and the environment at l <= 2, bit for bit in `f32`.

use super::*;
use hairmath::absorption::Absorption;
use hairmath::azimuthal::CausticParams;
use hairmath::bcsdf::Marschner2003;
use hairmath::models::gerard_sh::{
    tangent_frame, GerardSh, Lighting, PhaseQuadrature, ShadedPoint,
};
use hairmath::models::{GerardLobe, GERARD_K_TRT, GERARD_K_TT};
use hairmath::params::{LobeShift, LobeWidth, MarschnerLobes, RefractiveIndex};

/// Tangent and viewer: along each other, opposite, the tangent on each axis.
const FRAMES: &[[f64; 6]] = &[
    [0.0, 0.0, 1.0, 0.0, 0.0, 1.0],
    [0.0, 0.0, 1.0, 0.0, 0.0, -1.0],
    [1.0, 0.0, 0.0, 0.6, 0.8, 0.0],
    [0.0, 1.0, 0.0, 0.0, 0.6, 0.8],
    [0.0, 0.0, -1.0, 0.8, 0.0, 0.6],
];

fn v3<R: Real>(x: &[R]) -> V3<R> {
    V3::new(x[0], x[1], x[2])
}

fn shading() -> GerardSh<f64, 3> {
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
    GerardSh::new(&source, GerardLobe::Printed, k, 0.1, 17, &quadrature).unwrap()
}

traced_tests! {
    gerard_sh_tangent_frame ["tangent_frame"] {
        let first = FRAMES.iter().map(|f| f.to_vec()).collect();
        let inputs = listed_then(first, |g| [g.sphere(), g.sphere()].concat());
        case!("tangent_frame", inputs, |x| {
            tangent_frame(v3(&x[0..3]), v3(&x[3..6]))
                .iter()
                .flat_map(|v| [v.x, v.y, v.z])
                .collect()
        });
    }
    gerard_sh_shade ["GerardSh::shade", "GerardSh::instantiate", "GerardSh::with_uniforms"] {
        let shade = shading();
        let first = FRAMES
            .iter()
            .map(|f| [&f[..], &[1.0; 9], &[0.5; 27], &[0.0, 0.0, 1.0], &[1.0, 2.0, 3.0]].concat())
            .collect();
        let inputs = listed_then(first, |g| {
            let (tangent, wo, light) = (g.sphere(), g.sphere(), g.sphere());
            let (v, e) = (g.coefficients(9), g.coefficients(27));
            [&tangent[..], &wo, &v, &e, &light, &[g.uniform(), 1.0, 2.0 * g.uniform()]].concat()
        });
        case!("GerardSh::shade", inputs, |x| {
            let point = ShadedPoint {
                tangent: v3(&x[0..3]),
                wo: v3(&x[3..6]),
                transmittance: &x[6..15],
            };
            let lighting = Lighting {
                environment: [&x[15..24], &x[24..33], &x[33..42]],
                light: v3(&x[42..45]),
                light_radiance: [x[45], x[46], x[47]],
            };
            shade.instantiate().shade(&point, &lighting).unwrap().to_vec()
        });
    }
}
