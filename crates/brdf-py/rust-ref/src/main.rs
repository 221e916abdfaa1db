//! The Rust side of brdf-py's bit-for-bit tests and of its benchmark, independent of the
//! binding: it calls `brdf_core` directly on raw little-endian arrays.
//!
//! ```text
//! brdf-py-ref g f32|f64 SIGMA IN OUT      IN: θi[n] θr[n] (radians); OUT: GM GS G Blinn [n each]
//! brdf-py-ref dots f32|f64 SIGMA IN OUT   IN: n·i[n] n·o[n] i·o[n]; OUT: G Blinn [n each]
//! brdf-py-ref vectors f32|f64 SIGMA IN OUT IN: wi[n][3] wo[n][3] normal[n][3]; OUT: G [n]
//!                                          (ModifiedG::g_vectors; NaN where it gives None)
//! brdf-py-ref smith f32|f64 WIDTH IN OUT  IN: cos_i[n] cos_o[n]; OUT: Beckmann sep, corr, GGX sep, corr
//! brdf-py-ref eval f32|f64 MODEL IN OUT [KEY=NUMBER…]  IN: wi[n][3] wo[n][3] (normalised here); OUT: rgb[n][3]
//! brdf-py-ref bench IN REPS               IN: θi[n] θr[n] f64; prints the best ns per element
//!                                          of brdf_core::batch::g_modified (σ = 0.3)
//! ```

use brdf_core::batch;
use brdf_core::catalogue;
use brdf_core::masking::{self, ModifiedG};
use brdf_core::microfacet::{Beckmann, Isotropic, TrowbridgeReitz};
use brdf_core::models::Brdf;
use brdf_core::{Dots, Real, Vec3};
use std::process::ExitCode;

/// An element type read and written as raw little-endian bytes.
trait Elem: Real {
    const SIZE: usize;
    fn read(b: &[u8]) -> Self;
    fn write(self, out: &mut Vec<u8>);
}
impl Elem for f32 {
    const SIZE: usize = 4;
    fn read(b: &[u8]) -> Self {
        f32::from_le_bytes([b[0], b[1], b[2], b[3]])
    }
    fn write(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}
impl Elem for f64 {
    const SIZE: usize = 8;
    fn read(b: &[u8]) -> Self {
        let mut a = [0u8; 8];
        a.copy_from_slice(&b[..8]);
        f64::from_le_bytes(a)
    }
    fn write(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

fn read<T: Elem>(path: &str) -> Result<Vec<T>, String> {
    let b = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    Ok(b.chunks_exact(T::SIZE).map(T::read).collect())
}

fn write<T: Elem>(path: &str, cols: &[Vec<T>]) -> Result<(), String> {
    let mut out = Vec::new();
    for c in cols {
        for &x in c {
            x.write(&mut out);
        }
    }
    std::fs::write(path, out).map_err(|e| format!("{path}: {e}"))
}

fn num(s: &str) -> Result<f64, String> {
    s.parse().map_err(|_| format!("`{s}` is not a number"))
}

fn g<T: Elem>(a: &[String]) -> Result<(), String> {
    let x = read::<T>(&a[1])?;
    let n = x.len() / 2;
    let (ti, tr) = x.split_at(n);
    let g = ModifiedG::<T>::new(T::from_f64(num(&a[0])?)).map_err(|e| e.to_string())?;
    let mut cols: Vec<Vec<T>> = (0..4).map(|_| Vec::with_capacity(n)).collect();
    for k in 0..n {
        let t = g.terms(ti[k], tr[k]);
        cols[0].push(t.gm);
        cols[1].push(t.gs);
        cols[2].push(t.g);
        cols[3].push(masking::g_blinn(ti[k], tr[k]));
    }
    write(&a[2], &cols)
}

fn dots<T: Elem>(a: &[String]) -> Result<(), String> {
    let x = read::<T>(&a[1])?;
    let n = x.len() / 3;
    let g = ModifiedG::<T>::new(T::from_f64(num(&a[0])?)).map_err(|e| e.to_string())?;
    let mut cols: Vec<Vec<T>> = (0..2).map(|_| Vec::with_capacity(n)).collect();
    for k in 0..n {
        let d = Dots::new(x[k], x[n + k], x[2 * n + k]);
        cols[0].push(g.g_dots(d));
        cols[1].push(masking::g_blinn_dots(d));
    }
    write(&a[2], &cols)
}

fn vectors<T: Elem>(a: &[String]) -> Result<(), String> {
    let x = read::<T>(&a[1])?;
    let n = x.len() / 9;
    let g = ModifiedG::<T>::new(T::from_f64(num(&a[0])?)).map_err(|e| e.to_string())?;
    let v = |k: usize| Vec3::new(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
    let col: Vec<T> = (0..n)
        .map(|k| g.g_vectors(v(k), v(n + k), v(2 * n + k)).unwrap_or(T::NAN))
        .collect();
    write(&a[2], &[col])
}

fn smith<T: Elem>(a: &[String]) -> Result<(), String> {
    let x = read::<T>(&a[1])?;
    let n = x.len() / 2;
    let w = T::from_f64(num(&a[0])?);
    let fs: [fn(T, T, T) -> T; 4] = [
        Beckmann::<T>::g_separable_cos,
        Beckmann::<T>::g_correlated_cos,
        TrowbridgeReitz::<T>::g_separable_cos,
        TrowbridgeReitz::<T>::g_correlated_cos,
    ];
    let cols: Vec<Vec<T>> = fs
        .iter()
        .map(|f| (0..n).map(|k| f(x[k], x[n + k], w)).collect())
        .collect();
    write(&a[2], &cols)
}

fn eval<T: Elem>(a: &[String]) -> Result<(), String> {
    let spec = catalogue::find(&a[0]).ok_or("unknown model")?;
    let mut flat: Vec<T> = spec.defaults::<T>()[..spec.slots()].to_vec();
    for kv in &a[3..] {
        let (k, v) = kv.split_once('=').ok_or("expected KEY=NUMBER")?;
        if let Some((at, p)) = spec.param_by_name(k) {
            flat[at..at + p.width()].fill(T::from_f64(num(v)?));
        }
    }
    let m = spec.build::<T>(&flat).map_err(|e| e.to_string())?;
    let x = read::<T>(&a[1])?;
    let n = x.len() / 6;
    let v = |k: usize| Vec3::new(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
    let mut out = Vec::with_capacity(3 * n);
    for k in 0..n {
        match (v(k).normalize(), v(n + k).normalize()) {
            (Some(wi), Some(wo)) => {
                let c = m.eval(wi, wo);
                out.extend_from_slice(&[c.r, c.g, c.b]);
            }
            _ => out.extend_from_slice(&[T::NAN; 3]),
        }
    }
    write(&a[2], &[out])
}

fn bench(a: &[String]) -> Result<(), String> {
    let x = read::<f64>(&a[0])?;
    let reps: usize = a[1].parse().map_err(|_| "REPS")?;
    let n = x.len() / 2;
    let (ti, tr) = x.split_at(n);
    let g = ModifiedG::<f64>::new(0.3).map_err(|e| e.to_string())?;
    let mut out = vec![0.0; n];
    let mut best = f64::INFINITY;
    for _ in 0..reps {
        let t0 = std::time::Instant::now();
        batch::g_modified(&g, ti, tr, &mut out).map_err(|e| e.to_string())?;
        best = best.min(t0.elapsed().as_secs_f64());
        std::hint::black_box(&out);
    }
    println!("{}", best * 1e9 / n as f64);
    Ok(())
}

fn main() -> ExitCode {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let typed = |f32f: fn(&[String]) -> Result<(), String>,
                 f64f: fn(&[String]) -> Result<(), String>| {
        match a.get(1).map(String::as_str) {
            Some("f32") if a.len() >= 5 => f32f(&a[2..]),
            Some("f64") if a.len() >= 5 => f64f(&a[2..]),
            _ => Err("expected f32|f64 and three arguments".into()),
        }
    };
    let r = match a.first().map(String::as_str) {
        Some("g") => typed(g::<f32>, g::<f64>),
        Some("dots") => typed(dots::<f32>, dots::<f64>),
        Some("vectors") => typed(vectors::<f32>, vectors::<f64>),
        Some("smith") => typed(smith::<f32>, smith::<f64>),
        Some("eval") => typed(eval::<f32>, eval::<f64>),
        Some("bench") if a.len() == 3 => bench(&a[1..]),
        _ => Err("usage: see the module documentation".into()),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("brdf-py-ref: {e}");
            ExitCode::FAILURE
        }
    }
}
