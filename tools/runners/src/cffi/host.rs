//! The C program's side of the comparison: reads its tokens (`u:<n>` integers, 8 or 16 hex
//! digits for `f32`/`f64` bits) and tables, and recomputes every value it printed on the
//! host through the same exports called from Rust.

use crate::device::protocol::{self, Val};
use anyhow::{bail, Context, Result};
use brdf_ffi::*;
use std::mem::MaybeUninit;
use std::path::Path;

/// One argument of an `R` line, as its token says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Arg {
    U(u32),
    F32(u32),
    F64(u64),
}

pub(crate) fn parse_tok(t: &str) -> Result<Arg> {
    if let Some(d) = t.strip_prefix("u:") {
        return Ok(Arg::U(d.parse().with_context(|| format!("bad u32 {t:?}"))?));
    }
    match t.len() {
        8 => Ok(Arg::F32(
            u32::from_str_radix(t, 16).with_context(|| format!("bad f32 bits {t:?}"))?,
        )),
        16 => Ok(Arg::F64(
            u64::from_str_radix(t, 16).with_context(|| format!("bad f64 bits {t:?}"))?,
        )),
        _ => bail!("token {t:?} is neither u:<n>, 8 nor 16 hex digits"),
    }
}

/// A printed result value (a float of either width).
pub(crate) fn parse_val(t: &str) -> Result<Val> {
    match parse_tok(t)? {
        Arg::F32(b) => Ok(Val::F32(b)),
        Arg::F64(b) => Ok(Val::F64(b)),
        Arg::U(_) => bail!("a result must be a float, not {t:?}"),
    }
}

/// `f32` or `f64`, read from an argument and printed as a value.
trait Scalar: Copy {
    fn from_arg(a: Arg) -> Result<Self>;
    fn val(self) -> Val;
}

/// [`Scalar`] for one width: `Arg::$v` read as `$t`, printed as `Val::$v`.
macro_rules! scalar {
    ($t:ty, $v:ident) => {
        impl Scalar for $t {
            fn from_arg(a: Arg) -> Result<Self> {
                match a {
                    Arg::$v(b) => Ok(<$t>::from_bits(b)),
                    _ => bail!(
                        concat!("expected an ", stringify!($t), " argument, got {:?}"),
                        a
                    ),
                }
            }
            fn val(self) -> Val {
                Val::$v(self.to_bits())
            }
        }
    };
}
scalar!(f32, F32);
scalar!(f64, F64);

/// A result struct of the C ABI as printed values.
trait Vals {
    fn vals(&self) -> Vec<Val>;
}

macro_rules! vals {
    ($($ty:ty: $($field:ident),+;)+) => {$(
        impl Vals for $ty {
            fn vals(&self) -> Vec<Val> {
                vec![$(self.$field.val()),+]
            }
        }
    )+};
}
vals! {
    BrdfGTermsF32: gm, gs, g;
    BrdfGTermsF64: gm, gs, g;
    BrdfRgbF32: r, g, b;
    BrdfDfgF32: a, b;
}

/// The arguments of one `R` line, read in order.
struct Args<'a>(std::slice::Iter<'a, Arg>);

impl<'a> Args<'a> {
    fn new(kernel: &str, a: &'a [Arg], n: usize) -> Result<Self> {
        if a.len() != n {
            bail!("{kernel} takes {n} arguments, got {}", a.len());
        }
        Ok(Args(a.iter()))
    }
    fn f<T: Scalar>(&mut self) -> Result<T> {
        T::from_arg(*self.0.next().context("too few arguments")?)
    }
    fn u(&mut self) -> Result<u32> {
        match self.0.next() {
            Some(Arg::U(v)) => Ok(*v),
            a => bail!("expected an integer argument, got {a:?}"),
        }
    }
}

/// Initialises a handle with `init` (which must return OK) and runs `query` on it.
fn with_handle<H, R>(
    init: impl FnOnce(*mut H) -> BrdfStatus,
    query: impl FnOnce(*const H) -> R,
) -> Result<R> {
    let mut h = MaybeUninit::<H>::uninit();
    let st = init(h.as_mut_ptr());
    if st != BRDF_STATUS_OK {
        bail!("init failed with status {st}");
    }
    Ok(query(h.as_ptr()))
}

type Init<H, T> = unsafe extern "C" fn(*mut H, T, BrdfConvention) -> BrdfStatus;
type Terms<H, T, R> = unsafe extern "C" fn(*const H, T, T) -> R;

/// `mg_terms_*`: σ, convention, θi, θr → GM, GS, G.
fn mg_terms<T: Scalar, H, R: Vals>(
    mut p: Args,
    init: Init<H, T>,
    terms: Terms<H, T, R>,
) -> Result<Vec<Val>> {
    let (s, c, ti, tr) = (p.f()?, p.u()?, p.f()?, p.f()?);
    // SAFETY: `h` is a live handle on `with_handle`'s stack, filled by a successful init.
    let r = with_handle(
        |h| unsafe { init(h, s, c) },
        |h| unsafe { terms(h, ti, tr) },
    )?;
    Ok(r.vals())
}

/// `mg_terms_dots_f32`: σ, convention, n·wi, n·wo, wi·wo → GM, GS, G.
fn mg_terms_dots(mut p: Args) -> Result<Vec<Val>> {
    let (s, c) = (p.f()?, p.u()?);
    let (x, y, z) = (p.f()?, p.f()?, p.f()?);
    let r = with_handle(
        // SAFETY: as in `mg_terms`.
        |h| unsafe { brdf_modified_g_init_f32(h, s, c) },
        // SAFETY: as in `mg_terms`.
        |h| unsafe { brdf_modified_g_terms_dots_f32(h, x, y, z) },
    )?;
    Ok(r.vals())
}

/// The Torrance–Sparrow exports of one scalar type.
struct TsFns<H, T> {
    init: unsafe extern "C" fn(*mut H, T, u32, u32, T, T, T) -> BrdfStatus,
    eval: unsafe extern "C" fn(*const H, T, T, T) -> T,
    specular: unsafe extern "C" fn(*const H, T, T, T) -> T,
    eval_nh: unsafe extern "C" fn(*const H, T, T, T, T) -> T,
}

/// `ts_*`: σ, G, Fresnel, its parameter, k_s, ρ_d, three dots, n·h → f, specular, f(n·h).
fn ts<T: Scalar, H>(mut p: Args, f: TsFns<H, T>) -> Result<Vec<Val>> {
    let (s, g, fr, fp) = (p.f()?, p.u()?, p.u()?, p.f()?);
    let (ks, al) = (p.f()?, p.f()?);
    let (x, y, z, nh) = (p.f()?, p.f()?, p.f()?, p.f()?);
    // SAFETY: as in `mg_terms`.
    let r = with_handle(
        |h| unsafe { (f.init)(h, s, g, fr, fp, ks, al) },
        |h| unsafe {
            [
                (f.eval)(h, x, y, z),
                (f.specular)(h, x, y, z),
                (f.eval_nh)(h, x, y, z, nh),
            ]
        },
    )?;
    Ok(r.iter().map(|v| v.val()).collect())
}

/// `ts_albedo_f32`: the Torrance–Sparrow parameters and μ → R(μ).
fn ts_albedo(mut p: Args) -> Result<Vec<Val>> {
    let (s, g, fr, fp) = (p.f()?, p.u()?, p.u()?, p.f()?);
    let (ks, al, mu) = (p.f()?, p.f()?, p.f()?);
    let r = with_handle(
        // SAFETY: as in `mg_terms`.
        |h| unsafe { brdf_torrance_sparrow_init_f32(h, s, g, fr, fp, ks, al) },
        // SAFETY: as in `mg_terms`.
        |h| unsafe { brdf_torrance_sparrow_albedo_f32(h, mu) },
    )?;
    Ok(vec![r.val()])
}

/// `ggx_f32` (F0, α, form, wi, wo → RGB) and `ggx_albedo_f32` (F0, α, form, μ → RGB).
fn ggx(mut p: Args, albedo: bool) -> Result<Vec<Val>> {
    let f0 = BrdfRgbF32 {
        r: p.f()?,
        g: p.f()?,
        b: p.f()?,
    };
    let (alpha, form) = (p.f()?, p.u()?);
    // SAFETY: as in `mg_terms`.
    let init = |h| unsafe { brdf_ggx_init_f32(h, f0, alpha, form) };
    let c = if albedo {
        let mu = p.f()?;
        // SAFETY: as in `mg_terms`.
        with_handle(init, |h| unsafe { brdf_ggx_albedo_f32(h, mu) })?
    } else {
        let mut v = || -> Result<BrdfVec3F32> {
            Ok(BrdfVec3F32 {
                x: p.f()?,
                y: p.f()?,
                z: p.f()?,
            })
        };
        let (wi, wo) = (v()?, v()?);
        // SAFETY: as in `mg_terms`.
        with_handle(init, |h| unsafe { brdf_ggx_eval_f32(h, wi, wo) })?
    };
    Ok(c.vals())
}

/// The rough dielectric exports of one scalar type, with its vector constructor.
struct RdFns<H, T, V> {
    init: unsafe extern "C" fn(*mut H, u32, T, T) -> BrdfStatus,
    eval: unsafe extern "C" fn(*const H, V, V) -> T,
    adjoint: unsafe extern "C" fn(*const H, V, V) -> T,
    pdf: unsafe extern "C" fn(*const H, V, V) -> T,
    vec: fn(T, T, T) -> V,
}

/// `rd_f32` (distribution, α, η, wi, wo → f, f*, pdf(wo, wi)) and `rd_f64` (→ f).
fn rd<T: Scalar, H, V: Copy>(mut p: Args, f: RdFns<H, T, V>, all: bool) -> Result<Vec<Val>> {
    let (d, a, eta) = (p.u()?, p.f()?, p.f()?);
    let wi = (f.vec)(p.f()?, p.f()?, p.f()?);
    let wo = (f.vec)(p.f()?, p.f()?, p.f()?);
    // SAFETY: as in `mg_terms`.
    let r = with_handle(
        |h| unsafe { (f.init)(h, d, a, eta) },
        |h| unsafe {
            [
                (f.eval)(h, wi, wo),
                (f.adjoint)(h, wi, wo),
                (f.pdf)(h, wo, wi),
            ]
        },
    )?;
    let n = if all { 3 } else { 1 };
    Ok(r[..n].iter().map(|v| v.val()).collect())
}

/// `rd_sample_f32`: distribution, α, η, wo, u0, u1, uc → wi, pdf, weight (a failed sample
/// is an error: the C program prints only successful ones).
fn rd_sample(mut p: Args) -> Result<Vec<Val>> {
    let (d, a, eta) = (p.u()?, p.f()?, p.f()?);
    let wo = BrdfVec3F32 {
        x: p.f()?,
        y: p.f()?,
        z: p.f()?,
    };
    let (u0, u1, uc) = (p.f()?, p.f()?, p.f()?);
    let mut s = MaybeUninit::<BrdfBsdfSampleF32>::uninit();
    let st = with_handle(
        // SAFETY: as in `mg_terms`.
        |h| unsafe { brdf_rough_dielectric_init_f32(h, d, a, eta) },
        // SAFETY: as in `mg_terms`; `s` is valid for writes of one sample.
        |h| unsafe { brdf_rough_dielectric_sample_f32(h, wo, u0, u1, uc, s.as_mut_ptr()) },
    )?;
    if st != BRDF_STATUS_OK {
        bail!("sample failed with status {st}");
    }
    // SAFETY: a successful sample wrote `s`.
    let s = unsafe { s.assume_init() };
    let w = [s.wi.x, s.wi.y, s.wi.z, s.pdf];
    Ok(w.iter().map(|v| v.val()).chain(s.weight.vals()).collect())
}

/// The tables the C program embedded, parsed on the host from `assets/`.
#[derive(Default)]
pub(crate) struct HostTables {
    g: Option<Box<BrdfGTable>>,
    dfg: Option<Box<BrdfDfgTable>>,
    e: Option<Box<BrdfAlbedoTable>>,
    eavg: Option<Box<BrdfAverageAlbedoTable>>,
}

fn fnv1a(bytes: &[u8]) -> u32 {
    let mut h: u32 = 2_166_136_261;
    for &b in bytes {
        h = (h ^ b as u32).wrapping_mul(16_777_619);
    }
    h
}

/// A boxed handle filled by `parse`, which borrows `bytes` for the program's lifetime.
fn parse_boxed<H>(
    bytes: &'static [u8],
    parse: unsafe extern "C" fn(*mut H, *const u8, usize) -> BrdfStatus,
) -> Result<Box<H>> {
    let mut h = Box::new(MaybeUninit::<H>::uninit());
    // SAFETY: the pointer is valid for writes; `bytes` lives for the rest of the program.
    let st = unsafe { parse(h.as_mut_ptr(), bytes.as_ptr(), bytes.len()) };
    if st != BRDF_STATUS_OK {
        bail!("parse failed with status {st}");
    }
    // SAFETY: a successful parse initialised the handle.
    Ok(unsafe { Box::from_raw(Box::into_raw(h).cast::<H>()) })
}

impl HostTables {
    /// Loads every table a `TABLE <role> <file> <bytes> <fnv1a>` line names, checking that
    /// `assets/` holds the very bytes the program embedded.
    pub(crate) fn load(root: &Path, tables: &[Vec<String>]) -> Result<Self> {
        let mut t = HostTables::default();
        for words in tables {
            let [role, file, len, fnv] = &words[..] else {
                bail!("TABLE line needs <role> <file> <bytes> <fnv1a>: {words:?}");
            };
            let (len, fnv): (usize, u32) = (len.parse()?, u32::from_str_radix(fnv, 16)?);
            let bytes = protocol::asset(root, file)?;
            if bytes.len() != len || fnv1a(&bytes) != fnv {
                bail!(
                    "{file}: the C program embeds {len} bytes (FNV-1a {fnv:08x}), assets/ holds {} ({:08x})",
                    bytes.len(),
                    fnv1a(&bytes)
                );
            }
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            let ctx = || format!("{file} on the host");
            match role.as_str() {
                "g" => t.g = Some(parse_boxed(bytes, brdf_g_table_parse).with_context(ctx)?),
                "dfg" => t.dfg = Some(parse_boxed(bytes, brdf_dfg_table_parse).with_context(ctx)?),
                "e" => t.e = Some(parse_boxed(bytes, brdf_albedo_table_parse).with_context(ctx)?),
                "eavg" => {
                    let h = parse_boxed(bytes, brdf_average_albedo_table_parse);
                    t.eavg = Some(h.with_context(ctx)?)
                }
                other => bail!("unknown table role {other:?}"),
            }
        }
        Ok(t)
    }
}

fn tbl<T>(x: &Option<Box<T>>, kernel: &str) -> Result<*const T> {
    x.as_deref()
        .map(|r| r as *const T)
        .with_context(|| format!("{kernel} results without a TABLE line"))
}

/// The table lookups: `g_table`, `g_table_dots`, `dfg`, `e`, `eavg`.
fn table_values(t: &HostTables, kernel: &str, a: &[Arg]) -> Result<Vec<Val>> {
    let n = |k| Args::new(kernel, a, k);
    // SAFETY (every block below): the handles come from `HostTables::load`, filled by a
    // successful parse over bytes leaked for the program's lifetime.
    Ok(match kernel {
        "g_table" => {
            let (mut p, h) = (n(2)?, tbl(&t.g, kernel)?);
            // SAFETY: `h` is a parsed handle from `HostTables::load` (above).
            unsafe { brdf_g_table_terms(h, p.f()?, p.f()?) }.vals()
        }
        "g_table_dots" => {
            let (mut p, h) = (n(3)?, tbl(&t.g, kernel)?);
            // SAFETY: `h` is a parsed handle from `HostTables::load` (above).
            vec![unsafe { brdf_g_table_g_dots(h, p.f()?, p.f()?, p.f()?) }.val()]
        }
        "dfg" => {
            let (mut p, h) = (n(2)?, tbl(&t.dfg, kernel)?);
            // SAFETY: `h` is a parsed handle from `HostTables::load` (above).
            unsafe { brdf_dfg_table_ab(h, p.f()?, p.f()?) }.vals()
        }
        "e" => {
            let (mut p, h) = (n(2)?, tbl(&t.e, kernel)?);
            // SAFETY: `h` is a parsed handle from `HostTables::load` (above).
            vec![unsafe { brdf_albedo_table_e(h, p.f()?, p.f()?) }.val()]
        }
        "eavg" => {
            let (mut p, h) = (n(1)?, tbl(&t.eavg, kernel)?);
            // SAFETY: `h` is a parsed handle from `HostTables::load` (above).
            vec![unsafe { brdf_average_albedo_table_e_avg(h, p.f()?) }.val()]
        }
        other => bail!("the host does not know kernel {other:?}"),
    })
}

/// The values the C program should have printed for `kernel` at arguments `a`.
pub(crate) fn host_values(t: &HostTables, kernel: &str, a: &[Arg]) -> Result<Vec<Val>> {
    let n = |k| Args::new(kernel, a, k);
    match kernel {
        "mg_terms_f32" => mg_terms(n(4)?, brdf_modified_g_init_f32, brdf_modified_g_terms_f32),
        "mg_terms_f64" => mg_terms(n(4)?, brdf_modified_g_init_f64, brdf_modified_g_terms_f64),
        "mg_terms_dots_f32" => mg_terms_dots(n(5)?),
        "blinn_f32" => {
            let mut p = n(2)?;
            Ok(vec![brdf_g_blinn_f32(p.f()?, p.f()?).val()])
        }
        "blinn_dots_f32" => {
            let mut p = n(3)?;
            Ok(vec![brdf_g_blinn_dots_f32(p.f()?, p.f()?, p.f()?).val()])
        }
        "g1_smith_f32" => {
            let mut p = n(3)?;
            Ok(vec![brdf_g1_smith_f32(p.u()?, p.f()?, p.f()?).val()])
        }
        "g_smith_f32" => {
            let mut p = n(5)?;
            let (d, f) = (p.u()?, p.u()?);
            Ok(vec![brdf_g_smith_f32(d, f, p.f()?, p.f()?, p.f()?).val()])
        }
        "ts_f32" => ts(
            n(10)?,
            TsFns {
                init: brdf_torrance_sparrow_init_f32,
                eval: brdf_torrance_sparrow_eval_f32,
                specular: brdf_torrance_sparrow_specular_f32,
                eval_nh: brdf_torrance_sparrow_eval_nh_f32,
            },
        ),
        "ts_f64" => ts(
            n(10)?,
            TsFns {
                init: brdf_torrance_sparrow_init_f64,
                eval: brdf_torrance_sparrow_eval_f64,
                specular: brdf_torrance_sparrow_specular_f64,
                eval_nh: brdf_torrance_sparrow_eval_nh_f64,
            },
        ),
        "ts_albedo_f32" => ts_albedo(n(7)?),
        "ggx_f32" => ggx(n(11)?, false),
        "ggx_albedo_f32" => ggx(n(6)?, true),
        "rd_f32" => rd(
            n(9)?,
            RdFns {
                init: brdf_rough_dielectric_init_f32,
                eval: brdf_rough_dielectric_eval_f32,
                adjoint: brdf_rough_dielectric_eval_adjoint_f32,
                pdf: brdf_rough_dielectric_pdf_f32,
                vec: |x, y, z| BrdfVec3F32 { x, y, z },
            },
            true,
        ),
        "rd_f64" => rd(
            n(9)?,
            RdFns {
                init: brdf_rough_dielectric_init_f64,
                eval: brdf_rough_dielectric_eval_f64,
                adjoint: brdf_rough_dielectric_eval_adjoint_f64,
                pdf: brdf_rough_dielectric_pdf_f64,
                vec: |x, y, z| BrdfVec3F64 { x, y, z },
            },
            false,
        ),
        "rd_sample_f32" => rd_sample(n(9)?),
        _ => table_values(t, kernel, a),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_matches_the_published_test_vectors() {
        // FNV-1a 32-bit test vectors from the algorithm's reference description.
        assert_eq!(fnv1a(b""), 0x811c_9dc5);
        assert_eq!(fnv1a(b"a"), 0xe40c_292c);
        assert_eq!(fnv1a(b"foobar"), 0xbf9c_f968);
    }

    #[test]
    fn protocol_tokens_parse_by_width() {
        assert_eq!(parse_tok("u:7").unwrap(), Arg::U(7));
        assert_eq!(parse_tok("3e99999a").unwrap(), Arg::F32(0.3f32.to_bits()));
        assert_eq!(
            parse_tok("3fd3333333333333").unwrap(),
            Arg::F64(0.3f64.to_bits())
        );
        assert!(parse_tok("3e9999").is_err());
        assert!(parse_tok("zz99999a").is_err());
        assert!(parse_val("u:1").is_err());
    }

    #[test]
    fn a_one_ulp_difference_is_reported() {
        let t = HostTables::default();
        let args = [Arg::F32(0.5f32.to_bits()), Arg::F32(0.2f32.to_bits())];
        let host = host_values(&t, "blinn_f32", &args).unwrap();
        let Val::F32(b) = host[0] else { panic!() };
        assert_ne!(host, vec![Val::F32(b ^ 1)]);
        // Wrong argument counts and kinds, unknown kernels and missing tables are errors.
        assert!(host_values(&t, "blinn_f32", &args[..1]).is_err());
        assert!(host_values(&t, "g1_smith_f32", &[args[0], args[0], args[1]]).is_err());
        assert!(host_values(&t, "nope", &args).is_err());
        assert!(host_values(&t, "g_table", &args).is_err());
    }

    #[test]
    fn f32_and_f64_twins_agree_with_each_other() {
        // The f64 recomputation goes through the same generic helper as the f32 one: at
        // σ = 0.3, θi = 0.4, θr = 0.2 the two G values agree to f32 precision (1e-5).
        let t = HostTables::default();
        let f = |x: f32| Arg::F32(x.to_bits());
        let d = |x: f64| Arg::F64(x.to_bits());
        let a32 = [f(0.3), Arg::U(0), f(0.4), f(0.2)];
        let a64 = [d(0.3), Arg::U(0), d(0.4), d(0.2)];
        let g32 = host_values(&t, "mg_terms_f32", &a32).unwrap();
        let g64 = host_values(&t, "mg_terms_f64", &a64).unwrap();
        let (Val::F32(x), Val::F64(y)) = (g32[2], g64[2]) else {
            panic!("{g32:?} {g64:?}")
        };
        let (x, y) = (f32::from_bits(x) as f64, f64::from_bits(y));
        assert!((x - y).abs() < 1e-5 && (0.0..=1.0).contains(&y), "{x} {y}");
    }
}
