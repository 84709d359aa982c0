//! Cost of the transmittance bakers (`hairmath::strands::transmittance`) per vertex: the fast
//! baker and the exact baker at 1,024 and 16,384 directions, on the vertices of the first 8
//! strands (256 vertices) of a 3,000-strand curly groom of 32 points per strand, opacity 0.5,
//! bands l <= 2; and the fixed costs of a bake (the hierarchy, the extinction grid). Criterion's
//! throughput is in vertices; every output is consumed through `black_box`.
//!
//! Whole-groom timings (the README's table) come from `hairmath bake`, which prints them.
//!
//! Run: `cargo bench --bench bake`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use hairmath::strands::density::ExtinctionGrid;
use hairmath::strands::groom::{groom, GroomKind, GroomSettings};
use hairmath::strands::occluders::{Occluders, Opacity};
use hairmath::strands::transmittance::{bake, BakeSettings, Baker, FastSettings};
use hairmath::strands::Strands;

fn groom_under_test() -> Strands {
    groom(&GroomSettings::new(GroomKind::Curly, 3000, 32, 1)).expect("valid settings")
}

fn bench_bakers(c: &mut Criterion) {
    let strands = groom_under_test();
    let vertices = 0..strands.strand_points(7).expect("a strand").end;
    let mut g = c.benchmark_group("bake_per_vertex");
    g.sample_size(10);
    g.throughput(Throughput::Elements(vertices.len() as u64));
    let bakers = [
        ("fast", Baker::Fast(FastSettings::default())),
        ("exact", Baker::Exact { directions: 1024 }),
        ("exact", Baker::Exact { directions: 16_384 }),
    ];
    for (name, baker) in bakers {
        let settings = BakeSettings {
            lmax: 2,
            opacity: Opacity::Uniform(0.5),
            baker,
        };
        let parameter = match baker {
            Baker::Exact { directions } => directions.to_string(),
            Baker::Fast(f) => format!("{} cells", 2 * f.bands * f.bands),
        };
        g.bench_with_input(BenchmarkId::new(name, parameter), &settings, |b, s| {
            b.iter(|| {
                let baked = bake(&strands, vertices.clone(), s, &|_, _| {}).expect("valid");
                black_box(baked.coefficients)
            })
        });
    }
    g.finish();
}

fn bench_fixed_costs(c: &mut Criterion) {
    let strands = groom_under_test();
    let mut g = c.benchmark_group("bake_setup");
    g.sample_size(10);
    g.bench_function("hierarchy", |b| {
        b.iter(|| black_box(Occluders::new(&strands, Opacity::Uniform(0.5))))
    });
    let occluders = Occluders::new(&strands, Opacity::Uniform(0.5));
    let (lo, hi) = strands.points().iter().fold(
        (
            glam::Vec3::splat(f32::INFINITY),
            glam::Vec3::splat(f32::NEG_INFINITY),
        ),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    g.bench_function("extinction_grid", |b| {
        b.iter(|| {
            let cells = FastSettings::default().grid_cells;
            black_box(ExtinctionGrid::new(occluders.cylinders(), lo, hi, cells).expect("valid"))
        })
    });
    g.finish();
}

criterion_group!(benches, bench_bakers, bench_fixed_costs);
criterion_main!(benches);
