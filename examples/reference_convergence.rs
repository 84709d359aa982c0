//! How fast the reference render converges with its directions per pixel: the reference of
//! the README's groom (curly 1000 x 32, opacity 0.7, the default sky, no directional light)
//! at 2048, 8192 and 32768 directions of the Fibonacci rule, each measured against the rule
//! with 131072, once with the strands occluding and once without (the same hits, `V = 1`).
//! Without occlusion the integrand is smooth and the rule converges fast; with it, `V` is a
//! pattern of thin strands finer than the rule's spacing and the error falls as about
//! `N^(-1/2)`.
//!
//! Run: `cargo run --release --example reference_convergence [SIZE]` (default 24 pixels per
//! side; about 15 minutes on two cores).

use hairmath::bcsdf::{ChiangFarField, FarFieldRule};
use hairmath::params::HairParams;
use hairmath::quadrature::SphereRule;
use hairmath::render::shading::reference_radiance;
use hairmath::render::{
    first_hits, image_error, render, Camera, DirectionalLight, Hit, Image, Sky,
};
use hairmath::strands::groom::{groom, GroomKind, GroomSettings};
use hairmath::strands::occluders::{Occluders, Opacity};

const DIRECTIONS: [usize; 4] = [2048, 8192, 32768, 131072];

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
    let covered = hits.iter().filter(|h| h.is_some()).count();
    println!("curly groom 1000 x 32, {size} x {size}, {covered} pixels covered");
    for (label, occluders) in [("occluded", &occluding), ("unoccluded", &transparent)] {
        let images = DIRECTIONS
            .iter()
            .map(|&n| {
                let rule = SphereRule::fibonacci(n)?;
                let shade = |hit: &Hit| {
                    Ok(reference_radiance(
                        hit,
                        occluders,
                        &far_field,
                        (&sky, &light),
                        &rule,
                    ))
                };
                render(size, &hits, shade, &|_, _| {})
            })
            .collect::<Result<Vec<Image>, _>>()?;
        let finest = &images[DIRECTIONS.len() - 1];
        for (n, image) in DIRECTIONS.iter().zip(&images).take(DIRECTIONS.len() - 1) {
            let e = image_error(image, finest)?;
            println!(
                "{label}: {n} directions against {}: relative error {:.2e}",
                DIRECTIONS[DIRECTIONS.len() - 1],
                e.relative_error
            );
        }
    }
    Ok(())
}
