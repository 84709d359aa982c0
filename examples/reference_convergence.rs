//! How fast the reference render converges: the reference of the README's groom (curly
//! 1000 x 32, opacity 0.7, the default sky, no directional light) by great circles
//! ([`hairmath::render::meridian`], `MeridianRule::with_circles`) at 256 to 2048 circles,
//! each measured against 4096; and the Fibonacci rule (points) at 2048 to 32768 directions
//! against the same finest rule, once with the strands occluding and once
//! without (the same hits, `V = 1`). The points' error with occlusion falls as about
//! `N^(-1/2)` (`V` is a pattern of thin strands finer than their spacing); the circles
//! integrate `V` exactly along each circle. Without occlusion, both rules integrate the same
//! smooth integrand: their agreement checks one against the other.
//!
//! Run: `cargo run --release --example reference_convergence [SIZE]` (default 24 pixels per
//! side).

use hairmath::bcsdf::{ChiangFarField, FarFieldRule};
use hairmath::params::HairParams;
use hairmath::quadrature::SphereRule;
use hairmath::render::shading::reference_radiance;
use hairmath::render::{
    first_hits, image_error, meridian_radiance, render, Camera, DirectionalLight, Hit, Image,
    MeridianRule, Sky,
};
use hairmath::strands::groom::{groom, GroomKind, GroomSettings};
use hairmath::strands::occluders::{Occluders, Opacity};
use std::time::Instant;

const CIRCLES: [usize; 5] = [256, 512, 1024, 2048, 4096];
const POINTS: [usize; 3] = [2048, 8192, 32768];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let size = std::env::args()
        .nth(1)
        .map(|a| a.parse::<usize>())
        .transpose()?
        .unwrap_or(24);
    let strands = groom(&GroomSettings::new(GroomKind::Curly, 1000, 32, 0))?;
    let occluding = Occluders::new(&strands, Opacity::Uniform(0.7));
    let hits = first_hits(&occluding, &Camera::framing(&strands, size)?);
    let transparent = Occluders::new(&strands, Opacity::Uniform(0.0));
    let far_field =
        ChiangFarField::with_rule(&HairParams::default(), &FarFieldRule::gauss_legendre(64)?);
    let sky = Sky::default();
    let light = DirectionalLight {
        radiance: [0.0; 3],
        ..DirectionalLight::default()
    };
    let lights = (&sky, &light);
    let covered = hits.iter().filter(|h| h.is_some()).count();
    println!("curly groom 1000 x 32, {size} x {size}, {covered} pixels covered");
    for (label, occluders) in [("occluded", &occluding), ("unoccluded", &transparent)] {
        let timed = |name: String, image: Result<Image, _>, start: Instant| {
            println!("{label}: {name}: {:.1} s", start.elapsed().as_secs_f64());
            image
        };
        let circles = CIRCLES
            .iter()
            .map(|&circles| {
                let rule = MeridianRule::with_circles(circles)?;
                let shade =
                    |hit: &Hit| meridian_radiance(hit, occluders, &far_field, lights, &rule);
                let start = Instant::now();
                let image = render(size, &hits, shade, &|_, _| {});
                timed(format!("circles {circles}"), image, start)
            })
            .collect::<Result<Vec<Image>, _>>()?;
        let points = POINTS
            .iter()
            .map(|&n| {
                let rule = SphereRule::fibonacci(n)?;
                let shade = |hit: &Hit| {
                    Ok(reference_radiance(
                        hit, occluders, &far_field, lights, &rule,
                    ))
                };
                let start = Instant::now();
                let image = render(size, &hits, shade, &|_, _| {});
                timed(format!("points {n}"), image, start)
            })
            .collect::<Result<Vec<Image>, _>>()?;
        let (finest, coarser) = circles.split_last().expect("rules");
        let n = CIRCLES[CIRCLES.len() - 1];
        for (circles, image) in CIRCLES.iter().zip(coarser) {
            let e = image_error(image, finest)?;
            println!(
                "{label}: circles {circles} against {n}: relative error {:.2e}, worst pixel {:.2e}",
                e.relative_error,
                worst_pixel(image, finest)
            );
        }
        for (n_points, image) in POINTS.iter().zip(&points) {
            let e = image_error(image, finest)?;
            println!(
                "{label}: points {n_points} against circles {n}: relative error {:.2e}, worst pixel {:.2e}",
                e.relative_error,
                worst_pixel(image, finest)
            );
        }
    }
    Ok(())
}

/// The largest relative difference of a covered pixel's channel from the reference's.
fn worst_pixel(image: &Image, reference: &Image) -> f64 {
    image
        .pixels
        .iter()
        .zip(&reference.pixels)
        .zip(&reference.covered)
        .filter(|(_, &covered)| covered)
        .flat_map(|((a, b), _)| (0..3).map(move |c| (a[c] - b[c]).abs() / b[c].abs()))
        .fold(0.0, f64::max)
}
