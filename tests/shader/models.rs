//! Every model's emitted shader runs on a WebGPU device (llvmpipe in CI) and gives what the
//! CPU gives: a few thousand (wi, wo[, h]) rows, the hard cases of docs/ARCHITECTURE.md among them,
//! evaluated by the compute entry point and compared with the `f32` evaluation row by row
//! under a bound derived from the WGSL accuracy rules ([`crate::error_bound`]). The world-space
//! companion is checked against the local function; SPIR-V passes `spirv-val`.

use crate::error_bound::{gpu_error_bound, AccuracyRules};
use crate::gpu::{device, textures_of};
use hairmath::shader::{example_shaders, Language, ModelShader, WORLD_FUNCTION};
use rand::{Rng, SeedableRng};

/// Random rows after the hard ones.
const RANDOM_ROWS: usize = 4000;

/// A unit vector from its components (normalised in f64, rounded to f32).
fn unit(v: [f64; 3]) -> [f32; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| (c / n) as f32)
}

/// The local direction of inclination `theta` (from the normal plane) and azimuth `phi`.
fn direction(theta: f64, phi: f64) -> [f32; 3] {
    unit([
        theta.sin(),
        theta.cos() * phi.cos(),
        theta.cos() * phi.sin(),
    ])
}

/// The hard pairs of docs/ARCHITECTURE.md: along the tangent, grazing, wi = wo, wi = -wo, phi = 0 and
/// phi = pi, theta_d near +-90 degrees.
fn hard_pairs() -> Vec<([f32; 3], [f32; 3])> {
    let grazing = std::f64::consts::FRAC_PI_2 - 1e-4;
    let mut pairs = vec![
        ([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
        ([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]),
        ([-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        (direction(grazing, 0.3), direction(-grazing, 0.3)),
        (
            direction(grazing, 0.0),
            direction(grazing, std::f64::consts::PI),
        ),
    ];
    for &(ti, to) in &[(0.0, 0.0), (0.4, -0.2), (-1.2, 1.1), (1.5, -1.5)] {
        for &phi in &[0.0, std::f64::consts::PI, -std::f64::consts::PI, 1e-6, 2.0] {
            let wi = direction(ti, 0.7);
            let wo = direction(to, 0.7 + phi);
            pairs.push((wi, wo));
            pairs.push((wi, wi));
            pairs.push((wi, wi.map(|c| -c)));
        }
    }
    pairs
}

/// Rows of `stride` f32: the hard pairs and random unit pairs, then h (hard values and
/// random ones) when the model takes it.
fn rows(stride: usize) -> Vec<f32> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(0x5eed);
    let mut pairs = hard_pairs();
    while pairs.len() < hard_pairs().len() + RANDOM_ROWS {
        let mut v = || unit([0; 3].map(|_| rng.random_range(-1.0..1.0)));
        pairs.push((v(), v()));
    }
    let hard_h = [0.0_f32, 1.0, -1.0, 0.999_999, -0.5];
    pairs
        .iter()
        .enumerate()
        .flat_map(|(k, (wi, wo))| {
            let mut row = [&wi[..], &wo[..]].concat();
            if stride > 6 {
                let h = if k % 2 == 0 {
                    hard_h[k / 2 % hard_h.len()]
                } else {
                    ((k as f64 * 0.618_034).fract() * 2.0 - 1.0) as f32
                };
                row.push(h);
            }
            row
        })
        .collect()
}

/// What one model's comparison measured.
struct Measured {
    rows: usize,
    worst_difference: f64,
    worst_ratio: f64,
    infinite_bounds: usize,
}

/// Runs `shader`'s compute entry point on the device over `queries` and compares every value
/// with the traced graph's `f32` evaluation (bit for bit the `f32` code) under the bound.
fn compare_on_device(shader: &ModelShader, queries: &[f32]) -> Result<Measured, String> {
    let device = device().ok_or("no adapter")?;
    let compute = shader.compute().map_err(|e| e.to_string())?;
    let stride = compute.stride().expect("the compute form has a stride");
    let wgsl = compute.wgsl().map_err(|e| e.to_string())?;
    let gpu = device
        .run(
            &wgsl,
            "hair_main",
            queries,
            stride,
            &textures_of(&shader.module),
        )
        .map_err(|e| e.to_string())?;
    let rules = AccuracyRules::wgsl_on_llvmpipe();
    let mut measured = Measured {
        rows: queries.len() / stride,
        worst_difference: 0.0,
        worst_ratio: 0.0,
        infinite_bounds: 0,
    };
    let mut failures = Vec::new();
    for (k, row) in queries.chunks(stride).enumerate() {
        let cpu = shader.graph.eval_f32(row);
        let bound = gpu_error_bound(&shader.graph, row, &rules);
        for c in 0..3 {
            let (g, e) = (gpu[3 * k + c], cpu[c]);
            let difference = (f64::from(g) - f64::from(e)).abs();
            measured.worst_difference = measured.worst_difference.max(difference);
            if !bound[c].is_finite() {
                measured.infinite_bounds += 1;
                continue;
            }
            if difference.is_nan() || difference > bound[c] {
                failures.push(format!(
                    "row {k} {row:?} channel {c}: GPU {g:e}, CPU {e:e}, bound {:e}",
                    bound[c]
                ));
            } else if bound[c] > 0.0 {
                measured.worst_ratio = measured.worst_ratio.max(difference / bound[c]);
            }
        }
    }
    if failures.is_empty() {
        Ok(measured)
    } else {
        Err(format!(
            "{}: {} values outside the bound:\n{}",
            shader.model,
            failures.len(),
            failures[..failures.len().min(6)].join("\n")
        ))
    }
}

#[test]
fn every_model_shader_computes_on_the_device_what_the_cpu_computes() {
    if device().is_none() {
        return;
    }
    let shaders = example_shaders().expect("every model with a shader form emits");
    let mut report = vec![format!(
        "{:<16} {:>6} {:>14} {:>12} {:>9}",
        "model", "rows", "worst |diff|", "diff/bound", "inf bound"
    )];
    let mut errors = Vec::new();
    for shader in &shaders {
        let queries = rows(shader.module.argument_scalars());
        match compare_on_device(shader, &queries) {
            Ok(m) => {
                report.push(format!(
                    "{:<16} {:>6} {:>14.3e} {:>12.3e} {:>9}",
                    shader.model, m.rows, m.worst_difference, m.worst_ratio, m.infinite_bounds
                ));
                if m.infinite_bounds * 20 > m.rows * 3 {
                    errors.push(format!(
                        "{}: {} of {} values have no finite bound",
                        shader.model,
                        m.infinite_bounds,
                        m.rows * 3
                    ));
                }
            }
            Err(e) => errors.push(e),
        }
    }
    eprintln!("GPU (llvmpipe) against CPU f32:\n{}", report.join("\n"));
    assert!(errors.is_empty(), "{}", errors.join("\n\n"));
}

/// `w` in the frame of the tangent +X as [`hairmath::geometry::fibre_frame`] builds it:
/// normal (0, 0, -1), binormal (0, 1, 0), so local = (w.x, -w.z, w.y), exactly (up to the
/// sign of zeros).
fn local_of_x_frame(w: &[f32]) -> [f32; 3] {
    [w[0], -w[2], w[1]]
}

#[test]
fn the_world_space_function_is_the_local_one_in_the_fibre_frame() {
    let Some(device) = device() else { return };
    let shaders = example_shaders().expect("every model with a shader form emits");
    for shader in shaders
        .iter()
        .filter(|s| ["karis", "chiang"].contains(&s.model))
    {
        let stride = shader.module.argument_scalars();
        let local_rows = rows(stride);
        // The world rows: tangent +X, then the directions whose local form is the local row's.
        let world_rows: Vec<f32> = local_rows
            .chunks(stride)
            .flat_map(|r| {
                let unrotate = |l: &[f32]| [l[0], l[2], -l[1]];
                let (wi, wo) = (unrotate(&r[..3]), unrotate(&r[3..6]));
                assert_eq!(local_of_x_frame(&wi), [r[0], r[1], r[2]]);
                [&[1.0, 0.0, 0.0][..], &wi, &wo, &r[6..]].concat()
            })
            .collect();
        let world = shader
            .module
            .with_compute_entry_of(WORLD_FUNCTION, stride + 3)
            .and_then(|m| m.wgsl())
            .unwrap();
        let local = shader.compute().and_then(|m| m.wgsl()).unwrap();
        let t = textures_of(&shader.module);
        let a = device
            .run(&world, "hair_main", &world_rows, stride + 3, &t)
            .unwrap();
        let b = device
            .run(&local, "hair_main", &local_rows, stride, &t)
            .unwrap();
        assert_eq!(a.len(), b.len());
        // Both are within the bound of the CPU value of the same local directions (the frame
        // of +X rotates them exactly, up to the sign of zeros).
        let rules = AccuracyRules::wgsl_on_llvmpipe();
        for (k, row) in local_rows.chunks(stride).enumerate() {
            let bound = gpu_error_bound(&shader.graph, row, &rules);
            for c in 0..3 {
                let d = (f64::from(a[3 * k + c]) - f64::from(b[3 * k + c])).abs();
                assert!(
                    !d.is_nan() && d <= 2.0 * bound[c],
                    "{} row {k} {row:?}: world {} local {} bound {}",
                    shader.model,
                    a[3 * k + c],
                    b[3 * k + c],
                    bound[c]
                );
            }
        }
    }
}

#[test]
fn every_model_spirv_passes_spirv_val() {
    let shaders = example_shaders().expect("every model with a shader form emits");
    for shader in &shaders {
        let bytes = shader.write(Language::Spirv).unwrap();
        match crate::tools::spirv_validate(&bytes) {
            Ok(crate::tools::Validated::Passed) => {}
            Ok(crate::tools::Validated::Skipped(why)) => {
                eprintln!("spirv-val skipped: {why}");
                return;
            }
            Err(e) => panic!("{}: spirv-val rejects it:\n{e}", shader.model),
        }
    }
}
