//! Trace tests of the composed model (`hairmath::models::ComposedHair`): for compositions
//! that together use every factor (each longitudinal lobe, the far field's loop, Karis' R,
//! each distribution, each attenuation, the lobe tables, dropped lobes and the residual), the
//! traced graph interpreted in `f32` against the `f32` model bit for bit over the uniforms of
//! several hairs and the hard direction pairs.

use super::*;
use hairmath::models::{
    Attenuation, Azimuthal, ComposedHair, ComposedUniforms, Composition, Constants, Distribution,
    LobeFactors, LobeTableSize, Longitudinal, MarschnerTableSize,
};

/// (beta_m, beta_n, alpha, eta, sigma_a): brown, smooth and clear with the index near 1,
/// roughest and opaque with a large tilt, mixed absorption below the table's beta_n.
const COMPOSED_MATERIALS: &[(f64, f64, f64, f64, [f64; 3])] = &[
    (0.3, 0.3, 0.0349, 1.55, [0.545, 0.906, 1.781]),
    (0.0137, 0.01, 0.0, 1.0001, [0.0; 3]),
    (1.0, 1.0, -1.5, 2.4, [10.0; 3]),
    (0.1, 0.05, 1.5, 1.55, [0.0, 1.0, 10.0]),
];

/// Compositions that together use every factor.
pub fn compositions() -> Vec<Composition> {
    let f = |longitudinal, azimuthal| {
        Some(LobeFactors {
            longitudinal,
            azimuthal,
        })
    };
    let separable = |distribution, attenuation| Azimuthal::Separable {
        distribution,
        attenuation,
    };
    let (published, refit) = (Constants::Published, Constants::Refit);
    let table = LobeTableSize {
        phi: 8,
        theta_o: 4,
        beta_n: 3,
    };
    let marschner_table = MarschnerTableSize { phi: 8, theta_d: 4 };
    vec![
        Composition {
            r: f(Longitudinal::Deon, Azimuthal::FarField),
            tt: f(Longitudinal::SineGaussian, Azimuthal::FarField),
            trt: f(Longitudinal::ThetaHGaussian, Azimuthal::FarField),
            residual: true,
            far_field_nodes: 3,
            table,
            marschner_table,
        },
        Composition {
            r: f(Longitudinal::SineGaussian, Azimuthal::KarisReflection),
            tt: f(
                Longitudinal::ThetaHGaussian,
                separable(Distribution::FrostbiteTable, Attenuation::Offset(published)),
            ),
            trt: f(
                Longitudinal::Deon,
                separable(
                    Distribution::FrostbiteScaled,
                    Attenuation::Exponential(refit),
                ),
            ),
            residual: false,
            far_field_nodes: 1,
            table,
            marschner_table,
        },
        Composition {
            r: f(
                Longitudinal::ThetaHGaussian,
                Azimuthal::Table { absorption: None },
            ),
            tt: f(
                Longitudinal::Deon,
                Azimuthal::Table {
                    absorption: Some(Attenuation::Offset(refit)),
                },
            ),
            trt: f(
                Longitudinal::SineGaussian,
                Azimuthal::Table {
                    absorption: Some(Attenuation::Exponential(published)),
                },
            ),
            residual: false,
            far_field_nodes: 1,
            table,
            marschner_table,
        },
        Composition {
            r: f(Longitudinal::HenyeyGreenstein, Azimuthal::KarisReflection),
            tt: f(
                Longitudinal::SineGaussian,
                separable(Distribution::Karis(refit), Attenuation::Offset(refit)),
            ),
            trt: f(
                Longitudinal::ThetaHGaussian,
                separable(
                    Distribution::Karis(published),
                    Attenuation::Exponential(published),
                ),
            ),
            residual: false,
            far_field_nodes: 1,
            table,
            marschner_table,
        },
        Composition {
            r: None,
            tt: None,
            trt: f(
                Longitudinal::HenyeyGreenstein,
                Azimuthal::Table {
                    absorption: Some(Attenuation::Offset(published)),
                },
            ),
            residual: false,
            far_field_nodes: 1,
            table,
            marschner_table,
        },
        Composition {
            r: f(Longitudinal::DeonReduced, Azimuthal::NguyenDonnellyTable),
            tt: f(
                Longitudinal::SineGaussian,
                Azimuthal::GerardTable {
                    absorption: Some(Attenuation::Exponential(refit)),
                },
            ),
            trt: f(Longitudinal::DeonReduced, Azimuthal::NguyenDonnellyTable),
            residual: false,
            far_field_nodes: 1,
            table,
            marschner_table,
        },
        Composition {
            r: f(
                Longitudinal::ThetaHGaussian,
                Azimuthal::GerardTable { absorption: None },
            ),
            tt: f(Longitudinal::Deon, Azimuthal::NguyenDonnellyTable),
            trt: f(
                Longitudinal::Deon,
                Azimuthal::GerardTable {
                    absorption: Some(Attenuation::Offset(published)),
                },
            ),
            residual: false,
            far_field_nodes: 1,
            table,
            marschner_table,
        },
    ]
}

fn composed_model(k: usize, composition: Composition) -> ComposedHair<f64> {
    let (beta_m, beta_n, alpha, eta, sigma_a) = COMPOSED_MATERIALS[k];
    let values = HairValues {
        beta_m,
        beta_n,
        alpha,
        eta,
        sigma_a,
    };
    ComposedHair::new(&HairParams::try_from(values).unwrap(), composition).unwrap()
}

traced_tests! {
    composed_models [
        "ComposedHair::eval", "ComposedHair::eval_lobes", "ComposedHair::lobe_names",
        "ComposedHair::with_uniforms"
    ] {
        let width = ComposedUniforms::<f64>::fields().iter().map(|f| f.width).sum::<usize>();
        for (c, composition) in compositions().into_iter().enumerate() {
            let model = composed_model(0, composition);
            let graph = trace_eval(&model);
            let rows = material_rows(COMPOSED_MATERIALS.len(), |k| {
                composed_model(k, composition).uniforms().to_values()
            });
            check(&format!("ComposedHair::eval ({c})"), &rows, &graph, |row| {
                let m = model.with_uniforms::<f32>(UniformBlock::from_values(&row[..width]));
                m.eval(&query_of(&row[width..])).to_vec()
            });
            model_case!(
                format!("ComposedHair::eval_lobes ({c})"),
                model,
                query_parameters(false),
                ResultType::Scalars,
                material_rows(COMPOSED_MATERIALS.len(), |k| {
                    composed_model(k, composition).uniforms().to_values()
                }),
                |m, x| {
                    let flags = [m.lobe_names().len() as f64, f64::from(u8::from(m.uses_offset()))];
                    [m.eval_lobes(&query_of(x)).concat(), consts(&flags)].concat()
                }
            );
        }
    }
}
