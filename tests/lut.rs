//! Lookup tables: interpolation, clamping, bit-for-bit regeneration, file formats, and the
//! error of lookup against direct evaluation.

use core::f64::consts::{FRAC_PI_2, PI};
use std::path::PathBuf;

use hairmath::absorption::Absorption;
use hairmath::azimuthal::{marschner_np, CausticParams};
use hairmath::lut::{
    axis_cell, bake, error_vs_resolution, json_description, lookup_error, quantize_rgba8,
    raw_bytes, read_raw, write_raw, Axis, Baker, FarFieldN, GerardN, LutError, NguyenM, NguyenN,
    Table,
};
use hairmath::params::{AzimuthalRoughness, LobeShift, LobeWidth, RefractiveIndex};
use hairmath::ParamError;

/// A valid index (the bakers take validated parameters).
fn eta(v: f64) -> RefractiveIndex {
    RefractiveIndex::new(v).unwrap()
}

/// A valid absorption.
fn sigma_a(rgb: [f64; 3]) -> Absorption {
    Absorption::new(rgb).unwrap()
}

/// A valid azimuthal roughness.
fn beta_n(v: f64) -> AzimuthalRoughness {
    AzimuthalRoughness::new(v).unwrap()
}

/// The far-field baker of index 1.55 on [lo, hi] in beta_n.
fn far_field(rgb: [f64; 3], lo: f64, hi: f64, rel_tol: f64) -> Result<FarFieldN, ParamError> {
    FarFieldN::new(eta(1.55), sigma_a(rgb), beta_n(lo), beta_n(hi), rel_tol)
}

fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hairmath-lut-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A table of `f(coords)` on the given axes, one channel per function.
type Field<'a> = &'a dyn Fn(&[f64]) -> f64;

/// Bakers with the resolutions to measure them at.
type Plan = Vec<(Box<dyn Baker>, Vec<Vec<usize>>)>;

fn table_of(axes: Vec<Axis>, f: &[Field]) -> Table {
    let n: Vec<usize> = axes.iter().map(Axis::size).collect();
    let points: usize = n.iter().product();
    let mut data = Vec::new();
    for flat in 0..points {
        let mut rest = flat;
        let coords: Vec<f64> = axes
            .iter()
            .map(|a| {
                let x = a.sample(rest % a.size());
                rest /= a.size();
                x
            })
            .collect();
        data.extend(f.iter().map(|g| g(&coords) as f32));
    }
    let names = (0..f.len()).map(|i| format!("c{i}")).collect();
    Table::new(axes, names, data).unwrap()
}

#[test]
fn interpolation_is_exact_for_multilinear_functions() {
    let lin1 = |c: &[f64]| 0.5 + 2.0 * c[0];
    let t1 = table_of(vec![Axis::new("x", -1.0, 3.0, 5).unwrap()], &[&lin1]);
    let bilinear = |c: &[f64]| 1.0 + 0.25 * c[0] - 0.5 * c[1] + 0.125 * c[0] * c[1];
    let t2 = table_of(
        vec![
            Axis::new("x", 0.0, 2.0, 7).unwrap(),
            Axis::new("y", -1.0, 1.0, 4).unwrap(),
        ],
        &[&bilinear, &|c: &[f64]| c[1]],
    );
    let trilinear = |c: &[f64]| 0.3 + c[0] - 0.2 * c[1] + 0.7 * c[2] + 0.1 * c[0] * c[1] * c[2];
    let t3 = table_of(
        vec![
            Axis::new("x", 0.0, 1.0, 3).unwrap(),
            Axis::new("y", 0.0, 2.0, 5).unwrap(),
            Axis::new("z", -1.0, 0.0, 2).unwrap(),
        ],
        &[&trilinear],
    );
    for k in 0..200 {
        let u = (k as f64 * 0.618_033_988_7).fract();
        let v = (k as f64 * 0.754_877_666).fract();
        let w = (k as f64 * 0.569_840_29).fract();
        let x1 = -1.0 + 4.0 * u;
        let got = t1.lookup(&[x1 as f32]).unwrap()[0];
        assert!((f64::from(got) - lin1(&[x1])).abs() < 2e-6, "1D at {x1}");
        let c2 = [2.0 * u, -1.0 + 2.0 * v];
        let got = t2.lookup(&[c2[0] as f32, c2[1] as f32]).unwrap();
        assert!(
            (f64::from(got[0]) - bilinear(&c2)).abs() < 2e-6,
            "2D at {c2:?}"
        );
        assert!((f64::from(got[1]) - c2[1]).abs() < 2e-6);
        let c3 = [u, 2.0 * v, w - 1.0];
        let got = t3
            .lookup(&[c3[0] as f32, c3[1] as f32, c3[2] as f32])
            .unwrap()[0];
        assert!(
            (f64::from(got) - trilinear(&c3)).abs() < 2e-6,
            "3D at {c3:?}"
        );
    }
    // At the samples the lookup returns the stored value exactly.
    for j in 0..4 {
        for i in 0..7 {
            let a = &t2.axes();
            let c = [a[0].sample(i) as f32, a[1].sample(j) as f32];
            assert_eq!(
                t2.lookup(&c).unwrap()[0],
                t2.get(&[i, j], 0).unwrap(),
                "{i} {j}"
            );
        }
    }
}

#[test]
fn lookup_clamps_to_the_edges() {
    let t = table_of(
        vec![
            Axis::new("x", 0.0, 1.0, 4).unwrap(),
            Axis::new("y", 0.0, 1.0, 3).unwrap(),
        ],
        &[&|c: &[f64]| c[0] + 10.0 * c[1]],
    );
    let at = |x: f32, y: f32| t.lookup(&[x, y]).unwrap()[0];
    assert_eq!(at(-5.0, -1.0), at(0.0, 0.0));
    assert_eq!(at(7.0, 2.0), at(1.0, 1.0));
    assert_eq!(at(1.0, 1.0), 11.0);
    assert_eq!(at(f32::INFINITY, f32::NEG_INFINITY), 1.0);
    // A NaN coordinate is refused by the checked lookup (issue 17, item 6: it gave the axis'
    // minimum, a number from no input).
    let nan = t.lookup(&[f32::NAN, 0.5]).unwrap_err().to_string();
    assert!(nan.contains("axis x is NaN"), "{nan}");
    // The generic weights: the last cell is used at max, with f = 1.
    assert_eq!(axis_cell(1.0f64, 0.0, 1.0, 4), (2.0, 1.0));
    assert_eq!(axis_cell(-3.0f32, 0.0, 1.0, 4), (0.0, 0.0));
    let (i, f) = axis_cell(0.5f64, 0.0, 1.0, 3);
    assert_eq!((i, f), (1.0, 0.0));
}

#[test]
fn invalid_shapes_and_parameters_are_typed_errors() {
    assert!(matches!(
        Axis::new("x", 0.0, 1.0, 1),
        Err(LutError::Axis { size: 1, .. })
    ));
    assert!(matches!(
        Axis::new("x", 1.0, 1.0, 4),
        Err(LutError::Axis { .. })
    ));
    assert!(matches!(
        Axis::new("x", 0.0, f64::NAN, 4),
        Err(LutError::Axis { .. })
    ));
    let axis = Axis::new("x", 0.0, 1.0, 4).unwrap();
    assert!(matches!(
        Table::new(vec![axis.clone()], vec!["a".into()], vec![0.0; 3]),
        Err(LutError::Shape(_))
    ));
    assert!(matches!(
        Table::new(vec![], vec!["a".into()], vec![]),
        Err(LutError::Shape(_))
    ));
    assert!(matches!(
        Table::new(vec![axis.clone(); 4], vec!["a".into()], vec![0.0; 256]),
        Err(LutError::Shape(_))
    ));
    let t = Table::new(vec![axis], vec!["a".into()], vec![0.0; 4]).unwrap();
    assert!(matches!(t.lookup(&[0.0, 0.0]), Err(LutError::Shape(_))));
    assert!(t.get(&[4], 0).is_none() && t.get(&[0], 1).is_none());
    assert!(matches!(quantize_rgba8(&t, &[0]), Err(LutError::Shape(_))));

    let gerard = GerardN::new(eta(1.55), FRAC_PI_2, None).unwrap();
    assert!(matches!(bake(&gerard, &[8]), Err(LutError::Shape(_))));
    assert!(matches!(bake(&gerard, &[8, 1]), Err(LutError::Axis { .. })));
    assert!(matches!(
        bake(&gerard, &[usize::MAX, 2]),
        Err(LutError::Axis { .. })
    ));
    assert!(matches!(
        bake(&gerard, &[65536, 65536]),
        Err(LutError::Shape(_))
    ));
    // The bakers take validated parameters: an invalid index, absorption or lobe width is
    // rejected by its type, with the same error wherever it enters.
    assert!(matches!(
        RefractiveIndex::new(1.0),
        Err(ParamError::OutOfRange { name: "eta", .. })
    ));
    assert!(matches!(
        GerardN::new(eta(1.55), 2.0, None),
        Err(ParamError::OutOfRange {
            name: "theta_d_max",
            ..
        })
    ));
    assert!(matches!(
        Absorption::new([0.1, -1.0, 0.0]),
        Err(ParamError::OutOfRange {
            name: "sigma_a",
            ..
        })
    ));
    assert!(matches!(
        LobeWidth::new(0.0),
        Err(ParamError::OutOfRange { name: "beta_r", .. })
    ));
    assert!(LobeShift::new(0.0).is_ok());
    assert!(matches!(
        far_field([0.0; 3], 0.5, 0.4, 1e-6),
        Err(ParamError::OutOfRange {
            name: "beta_n_max",
            ..
        })
    ));
    assert!(matches!(
        far_field([0.0; 3], 0.2, 0.8, 0.0),
        Err(ParamError::OutOfRange {
            name: "rel_tol",
            ..
        })
    ));
    // A LutError wraps a ParamError.
    let e: LutError = RefractiveIndex::new(f64::NAN).unwrap_err().into();
    assert!(e.to_string().contains("eta"));
}

fn small_bakers() -> Vec<(Box<dyn Baker>, Vec<usize>)> {
    vec![
        (Box::new(NguyenM::default()), vec![9, 7]),
        (
            Box::new(NguyenN::new(
                eta(1.55),
                sigma_a([0.2, 0.4, 0.8]),
                Some(CausticParams::default()),
            )),
            vec![9, 7],
        ),
        (
            Box::new(GerardN::new(eta(1.55), FRAC_PI_2, Some(CausticParams::default())).unwrap()),
            vec![9, 7],
        ),
        (
            Box::new(far_field([0.3, 0.6, 1.2], 0.2, 0.8, 1e-6).unwrap()),
            vec![5, 3, 2],
        ),
    ]
}

#[test]
fn baked_tables_regenerate_bit_for_bit() {
    let dir = scratch_dir("regen");
    for (baker, sizes) in small_bakers() {
        let a = bake(baker.as_ref(), &sizes).unwrap();
        let b = bake(baker.as_ref(), &sizes).unwrap();
        assert!(a.data().iter().all(|v| v.is_finite()), "{}", baker.kind());
        let path = dir.join(format!("{}.f32", baker.kind()));
        let json_path = write_raw(&a, &path).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(bytes, raw_bytes(&b), "{}", baker.kind());
        assert_eq!(
            std::fs::read_to_string(&json_path).unwrap(),
            json_description(&b, &format!("{}.f32", baker.kind()))
        );
        let back = read_raw(&path).unwrap();
        assert_eq!(back.len(), a.data().len());
        assert!(back
            .iter()
            .zip(a.data())
            .all(|(x, y)| x.to_bits() == y.to_bits()));
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The committed golden table: a 9 x 5 Gerard LUT. Regenerate with `HAIRMATH_BLESS=1`.
#[test]
fn golden_gerard_table_matches() {
    let baker = GerardN::new(eta(1.55), FRAC_PI_2, Some(CausticParams::default())).unwrap();
    let table = bake(&baker, &[9, 5]).unwrap();
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let path = dir.join("gerard_9x5.f32");
    if std::env::var_os("HAIRMATH_BLESS").is_some() {
        std::fs::create_dir_all(&dir).unwrap();
        write_raw(&table, &path).unwrap();
    }
    let golden = std::fs::read(&path).expect("tests/data/gerard_9x5.f32 (HAIRMATH_BLESS=1)");
    assert_eq!(golden, raw_bytes(&table));
    let json = std::fs::read_to_string(dir.join("gerard_9x5.f32.json")).unwrap();
    assert_eq!(json, json_description(&table, "gerard_9x5.f32"));
}

#[test]
fn json_description_names_everything() {
    let baker = NguyenN::new(eta(1.55), sigma_a([0.2, 0.4, 0.8]), None);
    let table = bake(&baker, &[4, 3]).unwrap();
    let json = json_description(&table, "n.f32");
    for needle in [
        "\"format\": \"hairmath-lut\"",
        "\"kind\": \"nguyen-n\"",
        "\"data\": \"n.f32\"",
        "\"encoding\": \"f32le\"",
        "{\"name\": \"cos_phi\", \"min\": -1.0, \"max\": 1.0, \"size\": 4}",
        "{\"name\": \"cos_theta_d\", \"min\": 0.0, \"max\": 1.0, \"size\": 3}",
        "\"channels\": [\"N_TT_r\", \"N_TT_g\", \"N_TT_b\", \"N_R\", \"N_TRT_r\", \"N_TRT_g\", \"N_TRT_b\"]",
        "\"eta\": 1.55",
        "\"sigma_a\": [0.2, 0.4, 0.8]",
        "\"caustic\": false",
        "\"generator\": \"hairmath ",
        "\"png_scale\": [",
    ] {
        assert!(json.contains(needle), "missing {needle} in\n{json}");
    }
    // Balanced braces and brackets, outside strings.
    let (mut depth, mut in_string, mut escaped) = (0i32, false, false);
    for ch in json.chars() {
        match (in_string, escaped, ch) {
            (true, true, _) => escaped = false,
            (true, false, '\\') => escaped = true,
            (true, false, '"') | (false, _, '"') => in_string = !in_string,
            (false, _, '{' | '[') => depth += 1,
            (false, _, '}' | ']') => {
                depth -= 1;
                assert!(depth >= 0);
            }
            _ => {}
        }
    }
    assert_eq!(depth, 0);
    assert!(!in_string);
}

#[test]
fn eight_bit_quantisation_uses_the_scale() {
    let table = bake(&NguyenM::default(), &[16, 16]).unwrap();
    let scale = table.png_scale();
    assert_eq!(scale[3], 1.0);
    let (w, h, px) = quantize_rgba8(&table, &[0, 1, 2, 3]).unwrap();
    assert_eq!((w, h, px.len()), (16, 16, 16 * 16 * 4));
    for (texel, p) in table.data().chunks_exact(4).zip(px.chunks_exact(4)) {
        for c in 0..4 {
            let decoded = f32::from(p[c]) / 255.0 * scale[c];
            assert!((decoded - texel[c]).abs() <= scale[c] / 510.0 + 1e-6);
        }
    }
    // Missing channels: colour 0, alpha 255.
    let (_, _, px) = quantize_rgba8(&table, &[3]).unwrap();
    assert_eq!((px[1], px[2], px[3]), (0, 0, 255));
}

#[test]
fn marschner_n_is_even_in_phi_and_finite_at_grazing() {
    // The N textures index by cos phi and Gerard's and the far-field tables by phi in [0, pi]:
    // this is exact only if N_p(-phi) = N_p(phi).
    let caustic = CausticParams::default();
    for &sin_d in &[0.0, 0.3, 0.8, 1.0] {
        for k in 0..=40 {
            let phi = PI * k as f64 / 40.0;
            for p in 0..3 {
                let a = marschner_np(path(p), phi, sin_d, 1.55, [0.3, 0.5, 0.9], Some(&caustic));
                let b = marschner_np(path(p), -phi, sin_d, 1.55, [0.3, 0.5, 0.9], Some(&caustic));
                for c in 0..3 {
                    assert!(a[c].is_finite());
                    assert!(
                        (a[c] - b[c]).abs() <= 1e-9 * (1.0 + a[c].abs()),
                        "p {p} phi {phi} sin_d {sin_d}: {} {}",
                        a[c],
                        b[c]
                    );
                }
            }
        }
    }
    let far = far_field([0.3, 0.6, 1.2], 0.2, 0.8, 1e-7).unwrap();
    let mut a = [0.0; 12];
    let mut b = [0.0; 12];
    for &(phi, theta_o) in &[(0.3, 0.2), (2.0, 1.0), (3.0, 0.7)] {
        far.eval(&[phi, theta_o, 0.3], &mut a);
        // The table clamps phi to [0, pi]; evaluate -phi and -theta_o through the model.
        let hair = hairmath::bcsdf::ChiangHair::<f64>::new(&hairmath::params::HairParams {
            beta_n: beta_n(0.3),
            alpha: hairmath::params::CuticleTilt::new(0.0).unwrap(),
            eta: eta(1.55),
            sigma_a: sigma_a([0.3, 0.6, 1.2]),
            ..Default::default()
        });
        let (an, _) = hair.far_field_azimuthal_reference(-theta_o.sin(), theta_o.cos(), -phi, 1e-7);
        for p in 0..4 {
            for c in 0..3 {
                b[3 * p + c] = an[p][c];
            }
        }
        for c in 0..12 {
            assert!(
                (a[c] - b[c]).abs() <= 1e-6 * (1.0 + a[c]),
                "{phi} {theta_o} {c}"
            );
        }
    }
}

#[test]
fn error_decreases_with_resolution() {
    let bakers: Plan = vec![
        (
            Box::new(NguyenM::default()),
            vec![vec![16, 16], vec![64, 64], vec![256, 256]],
        ),
        (
            Box::new(GerardN::new(eta(1.55), 1.4, Some(CausticParams::default())).unwrap()),
            vec![vec![16, 8], vec![64, 32], vec![256, 128]],
        ),
        (
            Box::new(NguyenN::new(
                eta(1.55),
                sigma_a([0.2, 0.4, 0.8]),
                Some(CausticParams::default()),
            )),
            vec![vec![16, 16], vec![64, 64], vec![256, 256]],
        ),
        (
            Box::new(far_field([0.3, 0.6, 1.2], 0.3, 0.6, 1e-5).unwrap()),
            vec![vec![6, 4, 2], vec![12, 8, 3]],
        ),
    ];
    for (baker, resolutions) in bakers {
        let stats = error_vs_resolution(baker.as_ref(), &resolutions, 200).unwrap();
        // The mean error falls at every step. The maximum need not: the N textures have kinks
        // (the two-index Fresnel factor's cut-offs, the caustic fade) whose position moves
        // with theta_d, so the worst off-grid point converges only at first order and
        // erratically; require the finest maximum to beat the coarsest.
        for pair in stats.windows(2) {
            assert!(
                pair[1].mean_rel < 0.75 * pair[0].mean_rel,
                "{}: {:?}",
                baker.kind(),
                stats
            );
        }
        let (first, last) = (&stats[0], &stats[stats.len() - 1]);
        assert!(
            last.max_rel < first.max_rel,
            "{}: {:?}",
            baker.kind(),
            stats
        );
    }
}

/// Prints the error of lookup against direct evaluation for each table kind and resolution
/// (the figures quoted in the README). `cargo test --test lut -- --ignored --nocapture`.
#[test]
#[ignore]
fn print_error_tables() {
    let caustic = Some(CausticParams::default());
    let bakers: Plan = vec![
        (
            Box::new(NguyenM::default()),
            vec![vec![32, 32], vec![64, 64], vec![128, 128], vec![256, 256]],
        ),
        (
            Box::new(NguyenN::new(eta(1.55), sigma_a([0.2, 0.4, 0.8]), caustic)),
            vec![vec![32, 32], vec![64, 64], vec![128, 128], vec![256, 256]],
        ),
        (
            Box::new(GerardN::new(eta(1.55), FRAC_PI_2, caustic).unwrap()),
            vec![vec![32, 16], vec![64, 32], vec![128, 64], vec![256, 128]],
        ),
        (
            Box::new(far_field([0.3, 0.6, 1.2], 0.2, 0.8, 1e-6).unwrap()),
            vec![vec![8, 4, 3], vec![16, 8, 4], vec![32, 16, 8]],
        ),
    ];
    println!("| kind | size | max abs | mean abs | max rel | mean rel | worst channel |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    for (baker, resolutions) in bakers {
        let channels = baker.channels();
        for s in error_vs_resolution(baker.as_ref(), &resolutions, 1000).unwrap() {
            println!(
                "| {} | {:?} | {:.2e} | {:.2e} | {:.2e} | {:.2e} | {} |",
                baker.kind(),
                s.sizes,
                s.max_abs,
                s.mean_abs,
                s.max_rel,
                s.mean_rel,
                channels[s.worst_channel]
            );
        }
    }
    // lookup_error is also usable on a given table.
    let t = bake(&NguyenM::default(), &[8, 8]).unwrap();
    assert!(lookup_error(&NguyenM::default(), &t, 10).is_ok());
}

/// Marschner's path with `p` internal segments (valid in these tests by construction).
fn path(p: u32) -> hairmath::azimuthal::MarschnerPath {
    hairmath::azimuthal::MarschnerPath::from_p(p).expect("p <= 3")
}
