use brdf_lut::generate::{sheen_e_reference, sheen_grid};
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let n: usize = a.get(1).and_then(|s| s.parse().ok()).unwrap_or(1024);
    let t0: f64 = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(3e-6);
    let t1: f64 = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(3e-6);
    let t = std::time::Instant::now();
    let g = sheen_grid(n, [t0, t1]);
    eprintln!(
        "{:?} nodes {} patches {} evals/node {} bound {:?}",
        t.elapsed(),
        g.nodes,
        g.patches,
        g.evals / g.nodes as u64,
        g.bound
    );
    let mut worst = [0f64; 2];
    let mut s = 12345u64;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 33) as usize % n
    };
    let mut pts: Vec<(usize, usize)> = (0..300).map(|_| (rnd(), rnd())).collect();
    for k in [0, 1, 2, n / 2, n - 1] {
        for l in [0, 9, 10, 11, n / 2, n - 1] {
            pts.push((k, l));
            pts.push((l, k));
        }
    }
    for (i, j) in pts {
        let (mu, r) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
        let (rv, _) = sheen_e_reference(mu, r, 2e-8);
        for c in 0..2 {
            let d = (g.values[c][j * n + i] - rv[c]).abs();
            if d > worst[c] {
                worst[c] = d;
                if d > 3e-6 {
                    eprintln!("ch{c} i{i} j{j} mu {mu} r {r} d {d:.2e} ref {}", rv[c]);
                }
            }
        }
    }
    eprintln!("worst {:?}", worst);
}
