use hairmath::bcsdf::*;
use std::time::Instant;
fn main() {
    for &bn in &[0.05, 0.1, 0.2, 0.3, 0.5, 1.0] {
        let p = ChiangParams::new(0.3, bn, 0.03, 1.55, [0.0, 0.5, 10.0]).unwrap();
        let hair = ChiangHair::<f64>::new(&p);
        // reference grid
        let mut refs = vec![];
        let t = Instant::now();
        let mut maxerr_est: f64 = 0.0;
        for &th in &[0.0f64, 0.5, 1.2, 1.5] {
            let (so, co) = (th.sin(), th.cos());
            for k in 0..64 {
                let phi = -std::f64::consts::PI + (k as f64 + 0.5) * 2.0 * std::f64::consts::PI / 64.0;
                let (v, e) = hair.far_field_azimuthal_reference(so, co, phi, 1e-11);
                let (v2, _) = hair.far_field_azimuthal_reference(so, co, phi, 1e-13);
                let mut d: f64 = 0.0; let mut m: f64 = 0.0;
                for pp in 0..4 { for c in 0..3 { d = d.max((v[pp][c]-v2[pp][c]).abs()); m = m.max(v2[pp][c].abs()); } }
                maxerr_est = maxerr_est.max(d / m);
                let _ = e;
                refs.push((so, co, phi, v2));
            }
        }
        let tref = t.elapsed().as_secs_f64() / refs.len() as f64 / 2.0;
        print!("bn {bn}: ref refinement {maxerr_est:.1e} ({:.0} us/eval) |", tref * 1e6);
        for &n in &[8usize, 16, 32, 64, 128] {
            let ff = ChiangFarField::new(hair, &FarFieldRule::gauss_legendre(n).unwrap());
            // peak per (theta, p, c)
            let mut worst: f64 = 0.0; let mut sum = 0.0; let mut cnt = 0.0;
            for chunk in refs.chunks(64) {
                let mut peak = [[0.0f64; 3]; 4];
                for r in chunk { for pp in 0..4 { for c in 0..3 { peak[pp][c] = peak[pp][c].max(r.3[pp][c]); } } }
                for r in chunk {
                    let (a, _) = ff.azimuthal(r.0, r.1, r.2);
                    for pp in 0..3 { for c in 0..2 { if peak[pp][c] > 1e-12 { let e = (a[pp][c]-r.3[pp][c]).abs()/peak[pp][c]; worst = worst.max(e); sum += e; cnt += 1.0; } } }
                }
            }
            print!(" n{n}: {worst:.1e}/{:.1e}", sum / cnt);
        }
        println!();
    }
}
