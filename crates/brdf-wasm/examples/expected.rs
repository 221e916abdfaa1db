//! Writes the native (host) results that the Node and browser tests compare the
//! WebAssembly module with: `cargo run --release -p brdf-wasm --example expected -- OUT_DIR`.
//!
//! * `OUT_DIR/expected.json`: for every export, ≥ 1000 pseudo-random inputs (fixed seed) and
//!   the f32 results, as IEEE-754 bit patterns (u32) so that nothing is lost in JSON. The
//!   values are computed with brdf-core's API directly (not through this crate's export
//!   glue), so a wrong argument order or a wrong mapping in the exports shows up as a
//!   mismatch.
//! * `OUT_DIR/web-expected.json`: the web page's Fig. 6 curves and the lit-sphere pixels at
//!   fixed points for a few (model, parameters) settings.

use brdf_core::catalogue;
use brdf_core::fresnel::Fresnel;
use brdf_core::masking::{g_blinn, Convention, ModifiedG};
use brdf_core::microfacet::{from_cos, Beckmann, Distribution};
use brdf_core::models::{Brdf, GeometricTerm, TorranceSparrow};
use brdf_core::{Dots, Real, Vec3};
use brdf_lut::{DfgTable, GTable, GTable3};
use rand::{Rng as _, RngCore, SeedableRng};
use rand_pcg::Pcg64;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Rows per export.
const N: usize = 1000;

/// The pseudo-random inputs: the workspace's PCG generator (`rand_pcg`) from a fixed seed,
/// with the draws the groups use.
struct Rng(Pcg64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0.next_u64()
    }
    /// Uniform f32 in [lo, hi].
    fn f(&mut self, lo: f32, hi: f32) -> f32 {
        self.0.random_range(lo..=hi)
    }
    /// A unit direction, above the horizon with probability ~0.9.
    fn dir(&mut self) -> Vec3<f32> {
        let z = if self.next().is_multiple_of(10) {
            self.f(-0.3, 0.05)
        } else {
            self.f(0.0, 1.0)
        };
        let phi = self.f(0.0, 2.0 * core::f32::consts::PI);
        let s = Real::sqrt((1.0 - z * z).max(0.0));
        Vec3::new(s * Real::cos(phi), s * Real::sin(phi), z)
    }
}

/// One group of scalar calls: argument kinds ('u' = u32, 'f' = f32 bits) and rows.
struct Group {
    name: String,
    export: &'static str,
    types: &'static str,
    rows: Vec<Vec<u32>>,
    out: Vec<Vec<u32>>,
}

fn bits(x: f32) -> u32 {
    x.to_bits()
}

fn json_u32s(v: &[u32]) -> String {
    let mut s = String::from("[");
    for (k, x) in v.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        write!(s, "{x}").unwrap();
    }
    s.push(']');
    s
}

fn json_group(g: &Group) -> String {
    let rows: Vec<String> = g.rows.iter().map(|r| json_u32s(r)).collect();
    let out: Vec<String> = g.out.iter().map(|r| json_u32s(r)).collect();
    format!(
        "{{\"name\":\"{}\",\"export\":\"{}\",\"types\":\"{}\",\"rows\":[{}],\"out\":[{}]}}",
        g.name,
        g.export,
        g.types,
        rows.join(","),
        out.join(",")
    )
}

/// The in-plane G of each kind, from brdf-core directly (Smith: m = √2σ, docs/conventions.md §6).
fn native_g(kind: u32, sigma: f32, ti: f32, tr: f32) -> f32 {
    if !(sigma > 0.0 && sigma.is_finite()) || kind > 5 {
        return f32::NAN; // the exports' documented result for bad parameters
    }
    if ti.is_nan() || tr.is_nan() {
        return f32::NAN;
    }
    let ti_c = ti.clamp(0.0, core::f32::consts::FRAC_PI_2);
    let tr_c = tr.clamp(-core::f32::consts::FRAC_PI_2, core::f32::consts::FRAC_PI_2);
    let m = f32::from_f64(core::f64::consts::SQRT_2) * sigma;
    let smith = Beckmann::clamped(m, m);
    let (wi, wo) = (from_cos(Real::cos(ti_c)), from_cos(Real::cos(tr_c)));
    match kind {
        0 => 1.0,
        1 => g_blinn(ti, tr),
        2 => smith.g_separable(wi, wo),
        3 => smith.g_correlated(wi, wo),
        4 => ModifiedG::<f32>::new(sigma).unwrap().g(ti, tr),
        _ => ModifiedG::<f32>::new(sigma)
            .unwrap()
            .with_convention(Convention::Printed)
            .g(ti, tr),
    }
}

/// The dots as the exports receive them: n·wi, n·wo, wi·wo, with |wi + wo|² rebuilt from
/// wi·wo ([`Dots::new`]), as the exports do.
fn shader_dots(wi: Vec3<f32>, wo: Vec3<f32>) -> Dots<f32> {
    let d = Dots::from_local(wi, wo);
    Dots::new(d.n_i, d.n_o, d.i_o)
}

/// A near-mirror pair near the horizon: wi at cos θ ∈ [1e-6, 1e-2] (log-uniform), wo at
/// 0.5–2 times that cosine on the opposite azimuth, give or take 1e-3 rad.
fn grazing_mirror_pair(rng: &mut Rng) -> (Vec3<f32>, Vec3<f32>) {
    let dir = |c: f32, phi: f32| {
        let s = Real::sqrt(1.0 - c * c);
        Vec3::new(s * Real::cos(phi), s * Real::sin(phi), c)
    };
    let c = 10f32.powf(rng.f(-6.0, -2.0));
    let phi = rng.f(0.0, 2.0 * core::f32::consts::PI);
    let c2 = c * rng.f(0.5, 2.0);
    let phi2 = phi + core::f32::consts::PI + rng.f(-1e-3, 1e-3);
    (dir(c, phi), dir(c2, phi2))
}

/// G from dot products, from brdf-core directly (NaN in, NaN out, also for G = 1).
fn native_g_dots(kind: u32, sigma: f32, d: Dots<f32>) -> f32 {
    let Some(&t) = GeometricTerm::ALL.get(kind as usize) else {
        return f32::NAN;
    };
    let Ok(ts) = TorranceSparrow::<f32>::specular(sigma, t) else {
        return f32::NAN;
    };
    if t == GeometricTerm::None && (d.n_i.is_nan() || d.n_o.is_nan() || d.i_o.is_nan()) {
        return f32::NAN;
    }
    ts.g(d)
}

/// Model `name` with parameters `q` at (wi, wo), RGB, from brdf-core's constructors
/// directly; `None` when a constructor (or a choice index) rejects the parameters.
fn native_model(name: &str, q: &[f32], wi: Vec3<f32>, wo: Vec3<f32>) -> Option<[f32; 3]> {
    // The model catalogue of brdf-core (name → constructor), used directly: the exports'
    // glue (ids, pointers, slot counts, status codes) is what the comparison checks.
    let spec = catalogue::find(name).unwrap_or_else(|| panic!("no catalogue entry {name}"));
    let c = spec.build::<f32>(q).ok()?.eval(wi, wo);
    Some([c.r, c.g, c.b])
}

impl Group {
    /// An empty group of calls to `export` with argument kinds `types`.
    fn new(name: impl Into<String>, export: &'static str, types: &'static str) -> Self {
        Group {
            name: name.into(),
            export,
            types,
            rows: vec![],
            out: vec![],
        }
    }
}

fn main() {
    let out_dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/pkg").to_string()),
    );
    std::fs::create_dir_all(&out_dir).expect("create output directory");
    let mut rng = Rng(Pcg64::seed_from_u64(0x5EED_B4DF_2015_0184));
    let mut groups: Vec<Group> = Vec::new();
    // The groups in the order the random sequence is drawn: changing it changes every row.
    for kind in 0..6u32 {
        g_groups(&mut rng, kind, &mut groups);
        g_dots_groups(&mut rng, kind, &mut groups);
    }
    torrance_sparrow_groups(&mut rng, &mut groups);
    for (id, spec) in brdf_wasm::models::MODELS.iter().enumerate() {
        model_groups(&mut rng, id as u32, spec, &mut groups);
    }
    lut_groups(&mut rng, &mut groups);
    write_expected(&out_dir, &groups);
    write_web(&out_dir);
}

/// Writes `expected.json`: the LUT assets per slot and every group.
fn write_expected(out_dir: &std::path::Path, groups: &[Group]) {
    let body: Vec<String> = groups.iter().map(json_group).collect();
    let luts: Vec<String> = LUTS
        .iter()
        .map(|(slot, file)| format!("\"{slot}\":\"assets/{file}\""))
        .collect();
    let json = format!(
        "{{\"generator\":\"brdf-wasm/examples/expected.rs\",\"luts\":{{{}}},\"groups\":[\n{}\n]}}\n",
        luts.join(","),
        body.join(",\n")
    );
    let p = out_dir.join("expected.json");
    std::fs::write(&p, json).expect("write expected.json");
    let total: usize = groups.iter().map(|g| g.rows.len()).sum();
    println!(
        "wrote {} ({} groups, {total} rows)",
        p.display(),
        groups.len()
    );
}

/// G of `kind` from in-plane angles: random σ and angles after a few edge rows, then the
/// batch export with one σ for the whole array.
fn g_groups(rng: &mut Rng, kind: u32, groups: &mut Vec<Group>) {
    let r = core::f32::consts::FRAC_PI_2;
    let term = GeometricTerm::ALL[kind as usize].name();
    let mut g = Group::new(format!("g/{term}"), "brdf_g", "ufff");
    let edge: [[f32; 3]; 8] = [
        [0.3, 0.0, 0.0],
        [0.3, r, -r],
        [0.3, 2.0, -3.0],
        [0.3, -0.1, 0.4],
        [0.3, f32::NAN, 0.2],
        [0.0, 0.3, 0.3],
        [-1.0, 0.3, 0.3],
        [f32::INFINITY, 0.3, 0.3],
    ];
    let mut rows: Vec<[f32; 3]> = edge.to_vec();
    while rows.len() < N + edge.len() {
        rows.push([rng.f(0.05, 1.0), rng.f(0.0, r), rng.f(-r, r)]);
    }
    for [s, ti, tr] in rows {
        g.rows.push(vec![kind, bits(s), bits(ti), bits(tr)]);
        g.out.push(vec![bits(native_g(kind, s, ti, tr))]);
    }
    groups.push(g);

    let mut g = Group::new(format!("g_batch/{term}"), "brdf_g_batch", "ufff");
    let s = rng.f(0.05, 1.0);
    for _ in 0..N {
        let (ti, tr) = (rng.f(0.0, r), rng.f(-r, r));
        g.rows.push(vec![kind, bits(s), bits(ti), bits(tr)]);
        g.out.push(vec![bits(native_g(kind, s, ti, tr))]);
    }
    groups.push(g);
}

/// G of `kind` from dot products: a σ = 0 row, a NaN row, random rows; then the batch
/// export with one σ.
fn g_dots_groups(rng: &mut Rng, kind: u32, groups: &mut Vec<Group>) {
    let term = GeometricTerm::ALL[kind as usize].name();
    let mut g = Group::new(format!("g_dots/{term}"), "brdf_g_dots", "uffff");
    for k in 0..N + 2 {
        let s = if k == 0 { 0.0 } else { rng.f(0.05, 1.0) };
        let (wi, wo) = (rng.dir(), rng.dir());
        let mut d = shader_dots(wi, wo);
        if k == 1 {
            d.n_i = f32::NAN;
        }
        g.rows
            .push(vec![kind, bits(s), bits(d.n_i), bits(d.n_o), bits(d.i_o)]);
        g.out.push(vec![bits(native_g_dots(kind, s, d))]);
    }
    groups.push(g);

    let mut g = Group::new(format!("g_dots_batch/{term}"), "brdf_g_dots_batch", "uffff");
    let s = rng.f(0.05, 1.0);
    for _ in 0..N {
        let d = shader_dots(rng.dir(), rng.dir());
        g.rows
            .push(vec![kind, bits(s), bits(d.n_i), bits(d.n_o), bits(d.i_o)]);
        g.out.push(vec![bits(native_g_dots(kind, s, d))]);
    }
    groups.push(g);
}

/// The Torrance–Sparrow shader-form exports: three dots, and three dots with n·h. The
/// second group mixes random pairs with near-mirror pairs near the horizon (cos θ from
/// 1e-6 to 1e-2), where n·h is what keeps the value exact; n·h = normalize(wi + wo).z in
/// f32, as a shader computes it.
fn torrance_sparrow_groups(rng: &mut Rng, groups: &mut Vec<Group>) {
    for (name, export, types) in [
        ("torrance_sparrow", "brdf_torrance_sparrow", "fufffff"),
        (
            "torrance_sparrow_nh",
            "brdf_torrance_sparrow_nh",
            "fuffffffff",
        ),
    ] {
        let with_nh = types.len() == 10;
        let mut g = Group::new(name, export, types);
        for k in 0..N {
            let s = rng.f(0.05, 1.0);
            let kind = (rng.next() % 6) as u32;
            let (r0, ks, albedo) = (rng.f(0.0, 1.0), rng.f(0.0, 2.0), rng.f(0.0, 1.0));
            let (wi, wo) = if with_nh && k % 2 == 1 {
                grazing_mirror_pair(rng)
            } else {
                (rng.dir(), rng.dir())
            };
            let d = shader_dots(wi, wo);
            let h = wi.add(wo);
            let n_h = h.z / Real::sqrt(h.dot(h));
            let ts = TorranceSparrow::<f32>::new(
                s,
                GeometricTerm::ALL[kind as usize],
                Fresnel::schlick(r0).unwrap(),
                ks,
                albedo,
            )
            .unwrap();
            let mut row = vec![bits(s), kind, bits(r0), bits(ks), bits(albedo)];
            row.extend([bits(d.n_i), bits(d.n_o), bits(d.i_o)]);
            let v = if with_nh {
                row.push(bits(n_h));
                ts.eval_dots(Dots::with_n_h(d.n_i, d.n_o, d.i_o, n_h))
            } else {
                ts.eval_dots(d)
            };
            g.rows.push(row);
            g.out.push(vec![bits(v)]);
        }
        groups.push(g);
    }
}

/// Random parameters of a model in its slider ranges (integer ones integral).
fn random_params(rng: &mut Rng, spec: &catalogue::ModelSpec) -> Vec<f32> {
    (0..spec.slots())
        .map(|k| {
            let p = spec.slot(k).expect("slot").param;
            let (lo, hi) = (p.ui.0 as f32, p.ui.1 as f32);
            if p.step == 1.0 {
                (rng.next() % (hi as u64 + 1 - lo as u64)) as f32 + lo
            } else {
                rng.f(lo, hi)
            }
        })
        .collect()
}

/// A row of the model exports: model id, parameters (the model's slots), wi, wo.
fn model_row(id: u32, q: &[f32], wi: Vec3<f32>, wo: Vec3<f32>) -> Vec<u32> {
    let mut row = vec![id];
    row.extend(q.iter().map(|x| bits(*x)));
    row.extend([wi.x, wi.y, wi.z, wo.x, wo.y, wo.z].map(bits));
    row
}

/// Model `id` through brdf_eval (random parameters, the first row with a NaN one, which must
/// be rejected; out: status, r, g, b) and brdf_eval_batch (the defaults for every row).
fn model_groups(rng: &mut Rng, id: u32, spec: &catalogue::ModelSpec, groups: &mut Vec<Group>) {
    let mut g = Group::new(format!("model/{}", spec.name), "brdf_eval", "u");
    for k in 0..N + 1 {
        let mut q = random_params(rng, spec);
        if k == 0 {
            q[0] = f32::NAN; // must be rejected
        }
        let (wi, wo) = (rng.dir(), rng.dir());
        g.rows.push(model_row(id, &q, wi, wo));
        let res = if q.iter().any(|x| !x.is_finite()) {
            None
        } else {
            native_model(spec.name, &q, wi, wo)
        };
        g.out.push(match res {
            Some(v) => vec![0, bits(v[0]), bits(v[1]), bits(v[2])],
            None => vec![brdf_wasm::status::BAD_PARAM as u32],
        });
    }
    groups.push(g);

    let q: Vec<f32> = spec.defaults::<f32>()[..spec.slots()].to_vec();
    let mut g = Group::new(format!("model_batch/{}", spec.name), "brdf_eval_batch", "u");
    for _ in 0..N {
        let (wi, wo) = (rng.dir(), rng.dir());
        g.rows.push(model_row(id, &q, wi, wo));
        let v = native_model(spec.name, &q, wi, wo).expect("defaults are valid");
        g.out.push(vec![0, bits(v[0]), bits(v[1]), bits(v[2])]);
    }
    groups.push(g);
}

/// The default assets per LUT slot of the module (see src/lut.rs).
const LUTS: [(u32, &str); 3] = [
    (0, "g_modified.blut"),
    (1, "g_modified_sigma0.3.blut"),
    (2, "dfg_ggx.blut"),
];

fn asset(file: &str) -> Vec<u8> {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(file);
    std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e} (run `cargo xtask lut`)", p.display()))
}

/// LUT queries, answered by brdf-core's no_std view over the same asset bytes.
fn lut_groups(rng: &mut Rng, groups: &mut Vec<Group>) {
    let r = core::f32::consts::FRAC_PI_2;
    let g3_bytes = asset(LUTS[0].1);
    let g3 = GTable3::parse(&g3_bytes).expect("valid G table");
    let g2_bytes = asset(LUTS[1].1);
    let g2 = GTable::parse(&g2_bytes).expect("valid per-sigma G table");
    let dfg_bytes = asset(LUTS[2].1);
    let dfg = DfgTable::parse(&dfg_bytes).expect("valid DFG table");

    let mut g = Group::new("lut/g_modified", "brdf_g_lut", "fff");
    let edge: [[f32; 3]; 4] = [
        [0.3, f32::NAN, 0.1],
        [f32::NAN, 0.3, 0.1],
        [0.01, 0.3, 0.1],
        [3.0, 2.0, -2.0],
    ];
    let mut rows = edge.to_vec();
    while rows.len() < N + edge.len() {
        rows.push([rng.f(0.05, 1.0), rng.f(0.0, r), rng.f(-r, r)]);
    }
    for [s, ti, tr] in rows {
        g.rows.push(vec![bits(s), bits(ti), bits(tr)]);
        g.out.push(vec![bits(g3.g(ti, tr, s))]);
    }
    groups.push(g);

    let mut g = Group::new("lut_batch/g_modified", "brdf_g_lut_batch", "fff");
    let s = rng.f(0.05, 1.0);
    for _ in 0..N {
        let (ti, tr) = (rng.f(0.0, r), rng.f(-r, r));
        g.rows.push(vec![bits(s), bits(ti), bits(tr)]);
        g.out.push(vec![bits(g3.g(ti, tr, s))]);
    }
    groups.push(g);

    let mut g = Group::new("lut/g_modified_sigma0.3", "brdf_g_lut_fixed", "ff");
    for _ in 0..N {
        let (ti, tr) = (rng.f(0.0, r), rng.f(-r, r));
        g.rows.push(vec![bits(ti), bits(tr)]);
        g.out.push(vec![bits(g2.g(ti, tr))]);
    }
    groups.push(g);

    for (name, export) in [
        ("lut/dfg_ggx", "brdf_dfg"),
        ("lut_batch/dfg_ggx", "brdf_dfg_batch"),
    ] {
        let mut g = Group::new(name, export, "ff");
        for k in 0..N {
            let (mu, rough) = if k == 0 {
                (-0.5, 2.0) // clamped to the table's ranges
            } else {
                (rng.f(0.0, 1.0), rng.f(0.0, 1.0))
            };
            let (a, b) = dfg.ab(mu, rough);
            g.rows.push(vec![bits(mu), bits(rough)]);
            g.out.push(vec![0, bits(a), bits(b)]);
        }
        groups.push(g);
    }
}

/// Fig. 6 curves (θi = 30°, σ = 0.3, θr = −90°…90° in 1° steps) and sphere pixels.
fn write_web(out_dir: &std::path::Path) {
    let mut s = String::from("{\"curves\":{");
    write_curves(&mut s);
    // The page's status line names the module's model count: the native catalogue's.
    write!(s, "}},\"models\":{}", catalogue::MODELS.len()).unwrap();
    s.push_str(",\"size\":256,\"spheres\":[");
    write_spheres(&mut s);
    s.push_str("]}\n");
    let p = out_dir.join("web-expected.json");
    std::fs::write(&p, s).expect("write web-expected.json");
    println!("wrote {}", p.display());
}

/// The Fig. 6 curves: Blinn's, the modified and Smith's G directly, then the modified G
/// from the default table over σ.
fn write_curves(s: &mut String) {
    let sigma = 0.3f32;
    let ti = (30.0f64 * core::f64::consts::PI / 180.0) as f32;
    let tr: Vec<f32> = (-90..=90)
        .map(|d| (d as f64 * core::f64::consts::PI / 180.0) as f32)
        .collect();
    for (k, (name, kind)) in [("blinn", 1u32), ("modified", 4), ("smith", 2)]
        .iter()
        .enumerate()
    {
        let v: Vec<u32> = tr
            .iter()
            .map(|&t| bits(native_g(*kind, sigma, ti, t)))
            .collect();
        if k > 0 {
            s.push(',');
        }
        write!(s, "\"{name}\":{}", json_u32s(&v)).unwrap();
    }
    let g3_bytes = asset(LUTS[0].1);
    let g3 = GTable3::parse(&g3_bytes).expect("valid G table");
    let v: Vec<u32> = tr.iter().map(|&t| bits(g3.g(ti, t, sigma))).collect();
    write!(s, ",\"modified_lut\":{}", json_u32s(&v)).unwrap();
}

/// (model id, parameters): the page's default, then settings reached by moving sliders.
fn web_settings() -> Vec<(u32, Vec<f64>)> {
    let settings: Vec<(&str, Vec<f64>)> = vec![
        ("torrance-sparrow", vec![0.3, 4.0, 0.04, 1.0, 0.5]),
        ("torrance-sparrow", vec![0.12, 2.0, 0.5, 0.8, 0.2]),
        ("ward", vec![0.2, 0.2, 0.3, 0.3, 0.3, 0.3, 0.08, 0.4]),
        (
            "ashikhmin-shirley",
            vec![0.4, 0.4, 0.4, 0.3, 0.1, 0.1, 200.0, 20.0],
        ),
        (
            "standard",
            vec![
                0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.3, 0.2, 0.5, 0.5, 0.5, 30.0, 0.0,
            ],
        ),
        ("ggx", vec![0.95, 0.64, 0.54, 0.25, 1.0, 0.0]),
        (
            "ggx-anisotropic",
            vec![0.95, 0.64, 0.54, 0.05, 0.5, 1.0, 0.0],
        ),
    ];
    settings
        .into_iter()
        .map(|(name, q)| {
            let id = brdf_wasm::models::MODELS
                .iter()
                .position(|m| m.name == name)
                .expect("model exists") as u32;
            (id, q)
        })
        .collect()
}

/// The lit-sphere pixels of every web setting at fixed points of a 256² image.
fn write_spheres(s: &mut String) {
    use brdf_wasm::render::pixel;
    let size = 256u32;
    let points: Vec<(u32, u32)> = (0..41)
        .flat_map(|i| (0..41).map(move |j| (3 + 6 * i, 3 + 6 * j)))
        .filter(|(i, j)| i % 30 == 3 || j % 30 == 3 || (i + j) % 48 == 6)
        .collect();
    for (k, (id, q)) in web_settings().iter().enumerate() {
        let q32: Vec<f32> = q.iter().map(|x| *x as f32).collect();
        let m = brdf_wasm::models::Model::new(*id, &q32).expect("valid web setting");
        let px: Vec<String> = points
            .iter()
            .map(|&(x, y)| {
                let [r, g, b, a] = pixel(&m, size, x, y);
                format!("[{x},{y},{r},{g},{b},{a}]")
            })
            .collect();
        if k > 0 {
            s.push(',');
        }
        let qs: Vec<String> = q.iter().map(|x| format!("{x}")).collect();
        write!(
            s,
            "{{\"model\":\"{}\",\"params\":[{}],\"pixels\":[{}]}}",
            brdf_wasm::models::MODELS[*id as usize].name,
            qs.join(","),
            px.join(",")
        )
        .unwrap();
    }
}
