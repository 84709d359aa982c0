//! Table fetches in generic code ([`Real::sample_table`], [`SharedTable::sample`]): traced to
//! `textureSampleLevel` (naga validates the WGSL) and interpreted bit for bit like the `f32`
//! lookup; `f64` against `f32` within rounding, SIMD lanes against the scalar lookup,
//! clamp-to-edge, 1D/2D/3D tables, the fetch count. Then the models that read tables
//! (Nguyen-Donnelly, Gerard): traced through the model contract, bit for bit, fetches counted.

use super::*;
use hairmath::absorption::Absorption;
use hairmath::azimuthal::CausticParams;
use hairmath::bcsdf::Marschner2003;
use hairmath::lut::{Axis, SharedTable, Table, TableMeta};
use hairmath::models::{
    Gerard, GerardLobe, NguyenDonnelly, GERARD_ABSORPTION_K_TRT, GERARD_ABSORPTION_K_TT,
};
use hairmath::params::{LobeShift, LobeWidth, MarschnerLobes, RefractiveIndex};
use hairmath::real::{Node, NO_COORDINATE};
use std::sync::Arc;
use wide::{f32x16, f32x8};

/// A table over `axes` whose channel `c` at grid point `x` is `f(c, x)`, of kind `kind`.
fn table_of(
    kind: &str,
    axes: Vec<Axis>,
    channels: usize,
    f: impl Fn(usize, &[f64]) -> f64,
) -> Table {
    let points: usize = axes.iter().map(Axis::size).product();
    let mut data = Vec::with_capacity(points * channels);
    for flat in 0..points {
        let mut rest = flat;
        let x: Vec<f64> = axes
            .iter()
            .map(|a| {
                let v = a.sample(rest % a.size());
                rest /= a.size();
                v
            })
            .collect();
        data.extend((0..channels).map(|c| f(c, &x) as f32));
    }
    let names = (0..channels).map(|c| format!("c{c}")).collect();
    let meta = TableMeta {
        kind: kind.into(),
        ..TableMeta::default()
    };
    Table::new(axes, names, data)
        .unwrap()
        .with_meta(meta)
        .unwrap()
}

/// A wiggly field (not multilinear, so interpolation rounds), different per channel.
fn wiggle(c: usize, x: &[f64]) -> f64 {
    let s: f64 = x
        .iter()
        .enumerate()
        .map(|(d, v)| (d as f64 + 1.3) * v)
        .sum();
    (1.0 + c as f64) * (2.0 + (3.0 * s + c as f64).sin()) + x[0] * x[0]
}

/// 1D: 9 samples over [-1, 2], 2 channels.
fn table_1d() -> SharedTable<1, 2> {
    let axes = vec![Axis::new("x", -1.0, 2.0, 9).unwrap()];
    SharedTable::new(table_of("one-d", axes, 2, wiggle)).unwrap()
}
/// 2D: 7 x 5 samples, 7 channels (two textures in WGSL, as Nguyen-Donnelly's N).
fn table_2d() -> SharedTable<2, 7> {
    let axes = vec![
        Axis::new("cos_phi", -1.0, 1.0, 7).unwrap(),
        Axis::new("cos_theta_d", 0.0, 1.0, 5).unwrap(),
    ];
    SharedTable::new(table_of("two-d", axes, 7, wiggle)).unwrap()
}
/// 3D: 5 x 4 x 3 samples, 3 channels.
fn table_3d() -> SharedTable<3, 3> {
    let axes = vec![
        Axis::new("phi", 0.0, PI, 5).unwrap(),
        Axis::new("theta_o", 0.0, FRAC_PI_2, 4).unwrap(),
        Axis::new("beta_n", 0.1, 0.9, 3).unwrap(),
    ];
    SharedTable::new(table_of("", axes, 3, wiggle)).unwrap()
}

/// Coordinates over each axis and beyond it by a third of its range at both ends, the ends
/// themselves and a sample point included.
fn coordinate_args<const D: usize, const C: usize>(t: &SharedTable<D, C>) -> Vec<Arg> {
    t.table()
        .axes()
        .iter()
        .map(|a| {
            let pad = (a.max() - a.min()) / 3.0;
            let special: &'static [f64] = Box::leak(
                vec![a.min(), a.max(), a.sample(1), a.min() - pad, a.max() + pad]
                    .into_boxed_slice(),
            );
            arg(a.min() - pad, a.max() + pad, special)
        })
        .collect()
}

/// Marschner's hair with brown absorption and the caustic treatment.
fn marschner_hair(alpha_r_deg: f64, beta_r_deg: f64, sigma_a: [f64; 3]) -> Marschner2003 {
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

/// Gerard's model in its four variants (lobe x exponents) for a few hairs: their uniforms are
/// the rows' first values (one table for all: it depends on eta and the caustics only).
fn gerard_variants() -> Vec<Gerard<f64>> {
    let mut out = Vec::new();
    for (a, b, s) in [
        (-5.0, 7.5, [0.545, 0.906, 1.781]),
        (10.0, 1.0, [0.0; 3]),
        (-22.5, 45.0, [10.0, 0.0, 3.0]),
    ] {
        for lobe in [GerardLobe::Printed, GerardLobe::Normalised] {
            for k in [
                [4.0, 5.5],
                [GERARD_ABSORPTION_K_TT[3], GERARD_ABSORPTION_K_TRT[3]],
            ] {
                out.push(Gerard::new(&marschner_hair(a, b, s), lobe, k[0], k[1]).unwrap());
            }
        }
    }
    out
}

traced_tests! {
    models_nguyen_donnelly [
        "NguyenDonnelly::eval", "NguyenDonnelly::eval_lobes", "NguyenDonnelly::lobe_names",
        "NguyenDonnelly::with_uniforms"
    ] {
        let model = NguyenDonnelly::new(marschner_hair(-5.0, 7.5, [0.545, 0.906, 1.781]));
        // Through the library's shader entry point: (uniforms, wi, wo) -> vec3.
        let graph = trace_eval(&model);
        // The M texture and the N textures (7 channels: two textures), one fetch each.
        assert_eq!((graph.count_fetches(), graph.count_texture_samples()), (2, 3));
        assert_eq!(graph.tables().len(), 2);
        let wgsl = graph.to_wgsl("nguyen_donnelly");
        for text in [
            "struct NguyenDonnellyUniforms {",
            "var lut0_nguyen_m: texture_2d<f32>;",
            "var lut1_nguyen_n_0: texture_2d<f32>;",
            "var lut1_nguyen_n_1: texture_2d<f32>;",
            "uniforms.min_cos2_theta_d",
        ] {
            assert!(wgsl.contains(text), "missing {text:?} in\n{wgsl}");
        }
        let inputs = rows(|g| [vec![g.pick(&arg(1e-12, 1e-3, &[1e-12]))], g.pair()].concat());
        check("NguyenDonnelly::eval", &inputs, &graph, |row| {
            let m = model.with_uniforms::<f32>(UniformBlock::from_values(&row[..1]));
            m.eval(&query_of(&row[1..])).to_vec()
        });
        model_case!("NguyenDonnelly::eval_lobes", model, query_parameters(false), ResultType::Scalars, inputs, |m, x| {
            [m.eval_lobes(&query_of(x)).concat(), consts(&[m.lobe_names().len() as f64])].concat()
        });
    }
    models_gerard [
        "Gerard::eval", "Gerard::eval_lobes", "Gerard::lobe_names", "Gerard::with_uniforms",
        "sum_lobes"
    ] {
        let variants = gerard_variants();
        let model = variants[0].clone();
        let graph = trace_eval(&model);
        assert_eq!((graph.count_fetches(), graph.count_texture_samples()), (1, 1));
        let wgsl = graph.to_wgsl("gerard");
        for text in ["struct GerardUniforms {", "var lut0_gerard: texture_2d<f32>;", "uniforms.k_trt"] {
            assert!(wgsl.contains(text), "missing {text:?} in\n{wgsl}");
        }
        let width = model.uniforms().to_values().len();
        let inputs = rows(|g| {
            let u = variants[g.below(variants.len())].uniforms().to_values();
            [u, g.pair()].concat()
        });
        check("Gerard::eval", &inputs, &graph, |row| {
            let m = model.with_uniforms::<f32>(UniformBlock::from_values(&row[..width]));
            m.eval(&query_of(&row[width..])).to_vec()
        });
        model_case!("Gerard::eval_lobes", model, query_parameters(false), ResultType::Scalars, inputs, |m, x| {
            [m.eval_lobes(&query_of(x)).concat(), consts(&[m.lobe_names().len() as f64])].concat()
        });
    }

    lut_shared_table_sample ["SharedTable::sample"] {
        let (t1, t2, t3) = (table_1d(), table_2d(), table_3d());
        case!("SharedTable::sample(1D)", scalars(&coordinate_args(&t1)), |x| {
            t1.sample(arr(x)).to_vec()
        });
        case!("SharedTable::sample(2D, 7 channels)", scalars(&coordinate_args(&t2)), |x| {
            t2.sample(arr(x)).to_vec()
        });
        case!("SharedTable::sample(3D)", scalars(&coordinate_args(&t3)), |x| {
            t3.sample(arr(x)).to_vec()
        });
        // Coordinates computed in the graph, and a NaN coordinate (read as the axis minimum).
        let mut rows = scalars(&[SIN, SIN]);
        rows.push(vec![f32::NAN, 0.5]);
        rows.push(vec![0.5, f32::NAN]);
        case!("SharedTable::sample(computed coordinates)", rows, |x| {
            let c = t2.sample([x[0] * x[1], (x[0] + x[1]).abs()]);
            let d = t1.sample([c[6] - c[0]]);
            vec![c[3] * d[1], d[0]]
        });
    }
}

/// The `f32` lookup of `t` at `coords` through the generic entry point.
fn via_real<const D: usize, const C: usize>(t: &SharedTable<D, C>, coords: [f32; D]) -> [f32; C] {
    <f32 as Real>::sample_table(t, coords)
}

#[test]
fn f32_is_lookup_into_bit_for_bit() {
    let t = table_2d();
    let mut g = Gen(0x7ab1e);
    for _ in 0..500 {
        let c = [
            (g.uniform() * 3.0 - 1.5) as f32,
            (g.uniform() * 1.6 - 0.3) as f32,
        ];
        let mut want = [0.0f32; 7];
        t.table().lookup_into(&c, &mut want).unwrap();
        assert_eq!(
            via_real(&t, c).map(f32::to_bits),
            want.map(f32::to_bits),
            "{c:?}"
        );
    }
}

#[test]
fn f64_agrees_with_f32_within_rounding() {
    let (t1, t2, t3) = (table_1d(), table_2d(), table_3d());
    let mut g = Gen(0xf64);
    let mut worst = 0.0f64;
    for _ in 0..2000 {
        let u = [g.uniform(), g.uniform(), g.uniform()];
        let on = |t: &Table, d: usize| {
            let a = &t.axes()[d];
            (a.min() - 0.2 + u[d] * (a.max() - a.min() + 0.4)) as f32
        };
        // The same f32 coordinate in both precisions: only the arithmetic differs.
        let c1 = [on(t1.table(), 0)];
        let c2 = [on(t2.table(), 0), on(t2.table(), 1)];
        let c3 = [on(t3.table(), 0), on(t3.table(), 1), on(t3.table(), 2)];
        let pairs: Vec<(Vec<f64>, Vec<f32>, f32)> = vec![
            (
                t1.sample(c1.map(f64::from)).to_vec(),
                t1.sample(c1).to_vec(),
                t1.table().channel_max().into_iter().fold(0.0, f32::max),
            ),
            (
                t2.sample(c2.map(f64::from)).to_vec(),
                t2.sample(c2).to_vec(),
                t2.table().channel_max().into_iter().fold(0.0, f32::max),
            ),
            (
                t3.sample(c3.map(f64::from)).to_vec(),
                t3.sample(c3).to_vec(),
                t3.table().channel_max().into_iter().fold(0.0, f32::max),
            ),
        ];
        for (wide, single, scale) in pairs {
            for (a, b) in wide.iter().zip(&single) {
                let rel = (a - f64::from(*b)).abs() / f64::from(scale);
                worst = worst.max(rel);
            }
        }
    }
    // Weights rounded to f32 (a few ulp each) times samples up to the table's maximum.
    assert!(
        worst < 2e-6,
        "largest f64 - f32 difference {worst:e} of the table maximum"
    );
    assert!(
        worst > 0.0,
        "f64 should interpolate in f64, not repeat the f32 lookup"
    );
}

#[test]
fn simd_lanes_are_the_scalar_lookup() {
    let t = table_3d();
    let mut g = Gen(0x51d);
    for _ in 0..64 {
        let c: [[f32; 16]; 3] = core::array::from_fn(|d| {
            let a = &t.table().axes()[d];
            core::array::from_fn(|_| {
                (a.min() - 0.5 + g.uniform() * (a.max() - a.min() + 1.0)) as f32
            })
        });
        let wide16 = t.sample(c.map(f32x16::from)).map(|v| v.to_array());
        let lo: [[f32; 8]; 3] = c.map(|l| arr(&l[..8]));
        let wide8 = t.sample(lo.map(f32x8::from)).map(|v| v.to_array());
        for k in 0..16 {
            let scalar = t.sample([c[0][k], c[1][k], c[2][k]]);
            for ch in 0..3 {
                assert_eq!(wide16[ch][k].to_bits(), scalar[ch].to_bits(), "lane {k}");
                if k < 8 {
                    assert_eq!(wide8[ch][k].to_bits(), scalar[ch].to_bits(), "lane {k}");
                }
            }
        }
    }
}

#[test]
fn lookups_clamp_to_the_edge_and_hit_the_samples() {
    let t = table_2d();
    let (a0, a1) = (&t.table().axes()[0], &t.table().axes()[1]);
    let stored = |i: usize, j: usize| -> Vec<f32> {
        (0..7)
            .map(|ch| t.table().get(&[i, j], ch).unwrap())
            .collect()
    };
    // At every sample: the stored value, to the rounding of the weights.
    for i in 0..a0.size() {
        for j in 0..a1.size() {
            let c = [a0.sample(i), a1.sample(j)];
            let (single, double) = (t.sample(c.map(|v| v as f32)), t.sample(c));
            for ((s, d), v) in single.iter().zip(double).zip(stored(i, j)) {
                assert!((s - v).abs() <= 4e-7 * v.abs(), "({i}, {j}): {s} vs {v}");
                assert!((d - f64::from(v)).abs() <= 1e-12 * f64::from(v).abs());
            }
        }
    }
    // At the corners and beyond them: exactly the corner sample, in both precisions; a NaN
    // coordinate reads the axis minimum.
    let (n0, n1) = (a0.size() - 1, a1.size() - 1);
    for (i, x0) in [
        (0, a0.min()),
        (0, a0.min() - 5.0),
        (n0, a0.max()),
        (n0, a0.max() + 0.1),
    ] {
        for (j, x1) in [
            (0, a1.min()),
            (0, -1e30),
            (n1, a1.max()),
            (n1, f64::INFINITY),
        ] {
            let want = stored(i, j);
            assert_eq!(
                t.sample([x0 as f32, x1 as f32]).to_vec(),
                want,
                "({x0}, {x1})"
            );
            let wide: Vec<f64> = want.iter().map(|&v| f64::from(v)).collect();
            assert_eq!(t.sample([x0, x1]).to_vec(), wide, "({x0}, {x1})");
            if i == 0 {
                assert_eq!(t.sample([f32::NAN, x1 as f32]).to_vec(), want);
                assert_eq!(t.sample([f64::NAN, x1]).to_vec(), wide);
            }
        }
    }
}

#[test]
fn multilinear_fields_are_reproduced_in_one_two_and_three_dimensions() {
    // Dyadic grids and coefficients: the samples are exact in f32, so f64 interpolation
    // reproduces the multilinear field to f64 rounding.
    let field = |_: usize, x: &[f64]| {
        let mut v = 0.5;
        for (d, xd) in x.iter().enumerate() {
            v += 0.25 * (d as f64 + 1.0) * xd;
        }
        if x.len() > 1 {
            v += 0.125 * x[0] * x[1];
        }
        if x.len() > 2 {
            v -= 0.0625 * x[0] * x[1] * x[2];
        }
        v
    };
    let axis = |k: usize| Axis::new("a", -2.0 + k as f64, 2.0 + k as f64, 9).unwrap();
    let t1: SharedTable<1, 1> = SharedTable::new(table_of("a", vec![axis(0)], 1, field)).unwrap();
    let t2: SharedTable<2, 1> =
        SharedTable::new(table_of("b", vec![axis(0), axis(1)], 1, field)).unwrap();
    let t3: SharedTable<3, 1> =
        SharedTable::new(table_of("c", vec![axis(0), axis(1), axis(2)], 1, field)).unwrap();
    let mut g = Gen(0x111);
    for _ in 0..500 {
        let x: [f64; 3] = core::array::from_fn(|k| -2.0 + k as f64 + 4.0 * g.uniform());
        assert!((t1.sample([x[0]])[0] - field(0, &x[..1])).abs() < 1e-14);
        assert!((t2.sample([x[0], x[1]])[0] - field(0, &x[..2])).abs() < 1e-14);
        assert!((t3.sample(x)[0] - field(0, &x)).abs() < 1e-14);
        let x32 = x.map(|v| v as f32);
        let want = field(0, &x32.map(f64::from));
        assert!((f64::from(t3.sample(x32)[0]) - want).abs() < 1e-5 * want.abs().max(1.0));
    }
}

#[test]
fn the_shape_is_checked_when_a_table_is_wrapped() {
    let t = table_2d().table().clone();
    assert!(SharedTable::<2, 7>::new(t.clone()).is_ok());
    assert!(SharedTable::<2, 6>::new(t.clone()).is_err());
    assert!(SharedTable::<3, 7>::new(t.clone()).is_err());
    let message = SharedTable::<1, 7>::new(t).unwrap_err().to_string();
    assert!(message.contains("2 axes and 7 channels"), "{message}");
}

#[test]
fn fetches_are_counted_and_tables_kept_once() {
    let (t2, t3) = (table_2d(), table_3d());
    // A second wrapper of the same Arc is the same table; an equal copy is another one.
    let alias = SharedTable::<2, 7>::from_arc(Arc::clone(t2.arc())).unwrap();
    let copy = SharedTable::<3, 3>::new(t3.table().clone()).unwrap();
    let graph = trace(3, |x| {
        let a = t2.sample([x[0], x[1]]); // fetch 1: channels 0 (texture 0) and 5 (texture 1)
        let b = alias.sample([x[0], x[1]]); // the same fetch
        let c = t2.sample([x[1], x[0]]); // fetch 2: channel 2 only
        let d = t3.sample([x[0], x[1], x[2]]); // fetch 3
        let e = copy.sample([x[2], x[1], x[0]]); // fetch 4, another table
        let _dead = t3.sample([x[2], x[2], x[2]]); // not used: not counted
        vec![a[0] + b[5], c[2] * d[1], e[0]]
    });
    assert_eq!(graph.tables().len(), 3);
    assert!(Arc::ptr_eq(&graph.tables()[0], t2.arc()));
    assert_eq!(graph.count_fetches(), 4);
    // Fetch 1 reads two of the 7-channel table's textures.
    assert_eq!(graph.count_texture_samples(), 5);
    let fetch_nodes = graph
        .nodes()
        .iter()
        .filter(|n| matches!(n, Node::Fetch { .. }))
        .count();
    assert_eq!(
        fetch_nodes,
        7 + 7 + 3 + 3 + 3,
        "one node per channel, shared by the alias"
    );
    assert!(graph.nodes().iter().any(|n| matches!(
        n,
        Node::Fetch { coords, .. } if coords[2] == NO_COORDINATE
    )));
    // The interpreter reads the tables the graph keeps.
    let x = [0.3f32, 0.7, 0.2];
    let want = {
        let (a, c) = (t2.sample([x[0], x[1]]), t2.sample([x[1], x[0]]));
        let (d, e) = (t3.sample([x[0], x[1], x[2]]), t3.sample([x[2], x[1], x[0]]));
        vec![a[0] + a[5], c[2] * d[1], e[0]]
    };
    assert_eq!(graph.eval_f32(&x), want);
    assert_eq!(trace(1, |x| vec![x[0] + x[0]]).count_fetches(), 0);
}

#[test]
fn fetches_print_as_texture_samples() {
    let (t1, t2, t3) = (table_1d(), table_2d(), table_3d());
    let graph = trace(3, |x| {
        let a = t2.sample([x[0], x[1]]);
        let b = t1.sample([x[2]]);
        let c = t3.sample([x[0], x[1], x[2]]);
        vec![a[3] + a[4] + a[6], b[1], c[2]]
    });
    let wgsl = graph.to_wgsl("fetch");
    validate_wgsl(&wgsl).unwrap_or_else(|e| panic!("{wgsl}\n{e}"));
    for text in [
        "@group(0) @binding(0) var lut0_two_d_0: texture_2d<f32>;",
        "@group(0) @binding(1) var lut0_two_d_1: texture_2d<f32>;",
        "@group(0) @binding(2) var lut1_one_d: texture_2d<f32>;",
        "@group(0) @binding(3) var lut2: texture_3d<f32>;",
        "@group(0) @binding(4) var lut_sampler: sampler;",
        "// lut0_two_d_1: 7 x 5 texels (cos_phi in [-1, 1] along x, cos_theta_d in [0, 1] along y); x, y, z = c4, c5, c6",
        "let u = clamp((x - lo) / (hi - lo), 0.0, 1.0);",
        "return (u * (n - 1.0) + 0.5) / n;",
        "textureSampleLevel(lut0_two_d_0, lut_sampler, vec2<f32>(lut_coordinate(x0, (-1.0f), 1.0f, 7.0f), lut_coordinate(x1, 0.0f, 1.0f, 5.0f)), 0.0)",
        "textureSampleLevel(lut1_one_d, lut_sampler, vec2<f32>(lut_coordinate(x2, (-1.0f), 2.0f, 9.0f), 0.5f), 0.0)",
        "vec3<f32>(lut_coordinate(x0, 0.0f, 3.1415927f, 5.0f)",
    ] {
        assert!(wgsl.contains(text), "missing {text:?} in\n{wgsl}");
    }
    // One sample per texture and fetch: channels 4 and 6 share texture 1's sample.
    assert_eq!(wgsl.matches("textureSampleLevel(").count(), 4, "{wgsl}");
    assert_eq!(graph.count_texture_samples(), 4);
    assert!(wgsl.contains(".w;") && wgsl.contains(".z;"), "{wgsl}");
}

#[test]
fn a_fetch_outside_a_trace_panics_with_a_message() {
    let t = table_1d();
    let mut escaped = None;
    let _ = trace(1, |x| {
        escaped = Some(x[0]);
        vec![x[0]]
    });
    let x = escaped.unwrap();
    let caught = std::panic::catch_unwind(move || t.sample([x])).unwrap_err();
    let text = caught
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| caught.downcast_ref::<String>().cloned())
        .unwrap_or_default();
    assert!(text.contains("outside hairmath::real::trace"), "{text}");
}
