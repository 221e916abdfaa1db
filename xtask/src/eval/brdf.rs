//! `cargo xtask eval brdf`: rows `wi_x,wi_y,wi_z,wo_x,wo_y,wo_z` (local frame, z = normal,
//! wi toward the light, wo toward the viewer; normalised on input) in, the same columns plus
//! `r,g,b` out, from the f64 models of `brdf_core::models`. `--list` prints every model with
//! its parameters, units, ranges and defaults. A Dirac part (mirror) is not in r,g,b: the
//! columns are the model's `eval`, i.e. f in 1/sr (the standard lighting model gives its lit
//! colour, see `--list`).

use anyhow::{anyhow, bail, Context, Result};
use brdf_core::models::*;
use brdf_core::Vec3;
use std::collections::BTreeMap;
use std::io::Write;

#[derive(clap::Args)]
pub struct Args {
    /// Model name (see `--list`).
    #[arg(long)]
    model: Option<String>,
    /// A model parameter as key=value (repeatable). Colours take one value or r,g,b.
    #[arg(long = "param", value_name = "KEY=VALUE")]
    params: Vec<String>,
    /// Print every model with its parameters and exit.
    #[arg(long)]
    list: bool,
}

/// The output header.
pub const HEADER: &str = "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,r,g,b";

/// One documented parameter.
pub struct ParamSpec {
    pub key: &'static str,
    pub unit: &'static str,
    pub range: &'static str,
    pub default: &'static str,
    pub help: &'static str,
}

type Build = fn(&Params) -> Result<Box<dyn Brdf<f64>>>;

/// One model of the command line.
pub struct ModelSpec {
    pub name: &'static str,
    pub about: &'static str,
    pub params: &'static [ParamSpec],
    build: Build,
}

const fn p(
    key: &'static str,
    unit: &'static str,
    range: &'static str,
    default: &'static str,
    help: &'static str,
) -> ParamSpec {
    ParamSpec {
        key,
        unit,
        range,
        default,
        help,
    }
}

const RGB01: &str = "[0, 1] per channel (v or r,g,b)";
const RGB0INF: &str = "[0, inf) per channel (v or r,g,b)";

/// Every model, in `--list` order.
pub const MODELS: &[ModelSpec] = &[
    ModelSpec {
        name: "lambert",
        about: "Lambertian f = albedo/pi (seed 003 diffuse, FCG 24.2)",
        params: &[p("albedo", "1", RGB01, "0.8", "hemispherical reflectance")],
        build: |p| Ok(Box::new(Lambert::new(p.rgb("albedo")?)?)),
    },
    ModelSpec {
        name: "standard",
        about: "standard lighting model (seed 003): lit colour for one white unit light at wi, \
                viewer wo: m_emis + g_amb*m_amb + m_diff max(n.l,0) + m_spec max(cos,0)^gloss \
                (not a BRDF; diffuse exponent typo of the seed not applied)",
        params: &[
            p("emission", "1", RGB0INF, "0", "m_emis"),
            p("ambient", "1", RGB0INF, "0", "m_amb"),
            p("g_amb", "1", RGB0INF, "0", "global ambient g_amb"),
            p("diffuse", "1", RGB0INF, "0.8", "m_diff"),
            p("specular", "1", RGB0INF, "0.5", "m_spec"),
            p("gloss", "1", "[0, 1e6]", "32", "m_gls"),
            p("highlight", "-", "phong | blinn-phong", "phong", "(v.r)^gloss or (n.h)^gloss"),
        ],
        build: |p| {
            let m = StandardLighting::new(
                p.rgb("emission")?,
                p.rgb("ambient")?,
                p.rgb("diffuse")?,
                p.rgb("specular")?,
                p.num("gloss")?,
                match p.choice("highlight", &["phong", "blinn-phong"])? {
                    0 => Highlight::Phong,
                    _ => Highlight::BlinnPhong,
                },
            )?;
            Ok(Box::new(StandardCli { m, g_amb: p.rgb("g_amb")? }))
        },
    },
    ModelSpec {
        name: "phong",
        about: "energy-normalised Phong kd/pi + ks (n+2)/(2pi) max(wo.r_i,0)^n",
        params: &[
            p("kd", "1", RGB01, "0.5", "diffuse reflectance"),
            p("ks", "1", RGB01, "0.5", "specular reflectance"),
            p("n", "1", "[0, 1e6]", "32", "Phong exponent"),
        ],
        build: |p| Ok(Box::new(PhongNormalized::new(p.rgb("kd")?, p.rgb("ks")?, p.num("n")?)?)),
    },
    ModelSpec {
        name: "blinn-phong",
        about: "energy-normalised Blinn-Phong kd/pi + ks (n+2)(n+4)/(8pi(n+2^(-n/2))) (n.h)^n",
        params: &[
            p("kd", "1", RGB01, "0.5", "diffuse reflectance"),
            p("ks", "1", RGB01, "0.5", "specular reflectance"),
            p("n", "1", "[0, 1e6]", "32", "Blinn-Phong exponent"),
        ],
        build: |p| {
            Ok(Box::new(BlinnPhongNormalized::new(p.rgb("kd")?, p.rgb("ks")?, p.num("n")?)?))
        },
    },
    ModelSpec {
        name: "cook-torrance",
        about: "Cook-Torrance (seed 002) kd/pi + ks D F G/(4 cos_i cos_o), Beckmann D, Schlick F",
        params: &[
            p("kd", "1", RGB01, "0.2", "Lambertian reflectance"),
            p("ks", "1", RGB01, "0.8", "specular scale"),
            p("m", "1 (RMS slope * sqrt 2)", "[1e-4, 1e4]", "0.3", "Beckmann roughness"),
            p("r0", "1", "[0, 1]", "0.04", "Fresnel reflectance at normal incidence"),
            p(
                "g",
                "-",
                "none | blinn | smith-separable | smith-correlated | modified | modified-printed",
                "blinn",
                "geometric term (blinn = V-groove, paper eq 4)",
            ),
        ],
        build: |p| {
            let names: Vec<&str> = GeometricTerm::ALL.iter().map(|g| g.name()).collect();
            let g = GeometricTerm::ALL[p.choice("g", &names)?];
            Ok(Box::new(CookTorrance::new(p.rgb("kd")?, p.rgb("ks")?, p.num("m")?, p.num("r0")?, g)?))
        },
    },
    ModelSpec {
        name: "lambert-mirror",
        about: "Lambert plus mirror (FCG 24.4): rd/pi (+ rs times a Dirac mirror, not in r,g,b)",
        params: &[
            p("rd", "1", RGB01, "0.5", "matte reflectance"),
            p("rs", "1", "[0, 1], rd + rs <= 1", "0.3", "mirror reflectance"),
        ],
        build: |p| Ok(Box::new(LambertSpecularMix::new(p.rgb("rd")?, p.num("rs")?)?)),
    },
    ModelSpec {
        name: "shirley",
        about: "Shirley's damped model (FCG 24.4): rd (1 - R_f(theta_o))/pi (+ Dirac); NOT reciprocal",
        params: &[
            p("rd", "1", RGB01, "0.5", "matte reflectance"),
            p("r0", "1", "[0, 1]", "0.04", "Fresnel reflectance at normal incidence"),
        ],
        build: |p| Ok(Box::new(ShirleyDamped::new(p.rgb("rd")?, p.num("r0")?)?)),
    },
    ModelSpec {
        name: "coupled",
        about: "coupled smooth-layered model (FCG eq 24.3): k rm f(theta_i) f(theta_o) (+ Dirac)",
        params: &[
            p("rm", "1", RGB01, "1", "matte reflectance R_m"),
            p("r0", "1", "[0, 1)", "0.04", "Fresnel reflectance at normal incidence"),
            p(
                "k",
                "-",
                "conserving | printed",
                "conserving",
                "conserving: 21(1-R0)/(20pi); printed (FCG 24.2): 21/(20pi(1-R0)), albedo > 1",
            ),
        ],
        build: |p| {
            let k = match p.choice("k", &["conserving", "printed"])? {
                0 => CoupledK::Conserving,
                _ => CoupledK::Printed,
            };
            Ok(Box::new(CoupledSmooth::new(p.rgb("rm")?, p.num("r0")?, k)?))
        },
    },
    ModelSpec {
        name: "ashikhmin-shirley",
        about: "Ashikhmin-Shirley anisotropic Phong (FCG 24.5-24.9) + coupled diffuse (24.7); u = x, v = y",
        params: &[
            p("rs", "1", RGB01, "0.05", "specular reflectance at normal incidence"),
            p("rd", "1", RGB01, "0.5", "diffuse reflectance"),
            p("nu", "1", "[0, 1e6]", "100", "exponent along x"),
            p("nv", "1", "[0, 1e6]", "100", "exponent along y"),
        ],
        build: |p| {
            Ok(Box::new(AshikhminShirley::new(p.rgb("rs")?, p.rgb("rd")?, p.num("nu")?, p.num("nv")?)?))
        },
    },
    ModelSpec {
        name: "bank",
        about: "Bank anisotropic BRDF (seed 002): kd/pi + ks (sqrt(1-(L.T)^2) sqrt(1-(V.T)^2) - (L.T)(V.T))^ns",
        params: &[
            p("kd", "1", RGB01, "0.3", "Lambertian reflectance"),
            p("ks", "1", RGB0INF, "0.5", "specular coefficient"),
            p("ns", "1", "[0, 1e6]", "20", "specular exponent"),
            p(
                "tangent",
                "-",
                "fixed | n-cross-v",
                "fixed",
                "fixed material tangent (reciprocal) or T = n x wo as in seed 002 (not reciprocal)",
            ),
            p("tangent_azimuth", "rad", "finite", "0", "azimuth of the fixed tangent from x"),
        ],
        build: |p| {
            let t = match p.choice("tangent", &["fixed", "n-cross-v"])? {
                0 => BankTangent::Azimuth(p.num("tangent_azimuth")?),
                _ => BankTangent::NormalCrossView,
            };
            Ok(Box::new(Bank::new(p.rgb("kd")?, p.rgb("ks")?, p.num("ns")?, t)?))
        },
    },
    ModelSpec {
        name: "ward",
        about: "Ward anisotropic (seed 002): rd/pi + rs exp(-tan^2 h (cos^2/ax^2 + sin^2/ay^2))/(4pi ax ay sqrt(cos_i cos_o))",
        params: &[
            p("rd", "1", RGB01, "0.3", "diffuse reflectance"),
            p("rs", "1", RGB01, "0.3", "specular reflectance"),
            p("ax", "1 (RMS slope)", "[1e-4, 1e4]", "0.1", "roughness along x"),
            p("ay", "1 (RMS slope)", "[1e-4, 1e4]", "0.3", "roughness along y"),
        ],
        build: |p| Ok(Box::new(Ward::new(p.rgb("rd")?, p.rgb("rs")?, p.num("ax")?, p.num("ay")?)?)),
    },
    ModelSpec {
        name: "ggx",
        about: "Trowbridge-Reitz (GGX) D F G/(4 cos_i cos_o), Schlick F (F90 = 1), Smith G",
        params: &[
            p("f0", "1", RGB01, "0.04", "Fresnel reflectance at normal incidence"),
            p("alpha", "1", "[1e-4, 1e4]", "0.25", "GGX roughness (perceptual roughness squared)"),
            p("smith", "-", "separable | correlated", "correlated", "Smith masking form"),
        ],
        build: |p| {
            let s = match p.choice("smith", &["separable", "correlated"])? {
                0 => SmithForm::Separable,
                _ => SmithForm::Correlated,
            };
            Ok(Box::new(Ggx::new(p.rgb("f0")?, p.num("alpha")?, s, MicrofacetSampling::VisibleNormals)?))
        },
    },
];

/// The standard model on the command line: the full lit colour, with emission and ambient.
struct StandardCli {
    m: StandardLighting<f64>,
    g_amb: Rgb<f64>,
}

impl Brdf<f64> for StandardCli {
    fn flags(&self) -> BrdfFlags {
        self.m.flags()
    }
    fn eval(&self, wi: Vec3<f64>, wo: Vec3<f64>) -> Rgb<f64> {
        let light = Light {
            dir: wi,
            color: Rgb::splat(1.0),
        };
        self.m
            .shade(Vec3::new(0.0, 0.0, 1.0), wo, &[light], self.g_amb)
    }
    fn pdf(&self, wo: Vec3<f64>, wi: Vec3<f64>) -> f64 {
        self.m.pdf(wo, wi)
    }
    fn sample(&self, wo: Vec3<f64>, u: [f64; 2]) -> Option<BrdfSample<f64>> {
        self.m.sample(wo, u)
    }
}

/// The parameters given on the command line, checked against a model's spec.
pub struct Params {
    spec: &'static ModelSpec,
    given: BTreeMap<String, String>,
}

impl Params {
    fn parse(spec: &'static ModelSpec, raw: &[String]) -> Result<Self> {
        let mut given = BTreeMap::new();
        for r in raw {
            let (k, v) = r
                .split_once('=')
                .ok_or_else(|| anyhow!("--param `{r}`: expected KEY=VALUE"))?;
            let k = k.trim();
            if !spec.params.iter().any(|p| p.key == k) {
                let keys: Vec<&str> = spec.params.iter().map(|p| p.key).collect();
                bail!(
                    "model `{}` has no parameter `{k}` (parameters: {})",
                    spec.name,
                    keys.join(", ")
                );
            }
            if given.insert(k.to_string(), v.trim().to_string()).is_some() {
                bail!("--param `{k}` given twice");
            }
        }
        Ok(Self { spec, given })
    }
    fn raw(&self, key: &str) -> &str {
        match self.given.get(key) {
            Some(v) => v,
            None => {
                self.spec
                    .params
                    .iter()
                    .find(|p| p.key == key)
                    .expect("parameter missing from its model's spec")
                    .default
            }
        }
    }
    fn num(&self, key: &str) -> Result<f64> {
        let v = self.raw(key);
        let x: f64 = v
            .parse()
            .map_err(|_| anyhow!("parameter `{key}`: `{v}` is not a number"))?;
        Ok(x)
    }
    fn rgb(&self, key: &str) -> Result<Rgb<f64>> {
        let v = self.raw(key);
        let parts: Vec<&str> = v.split(',').map(str::trim).collect();
        let nums: Vec<f64> = parts
            .iter()
            .map(|s| s.parse::<f64>())
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| anyhow!("parameter `{key}`: `{v}` is not a number or r,g,b"))?;
        match nums.as_slice() {
            [x] => Ok(Rgb::splat(*x)),
            [r, g, b] => Ok(Rgb::new(*r, *g, *b)),
            _ => bail!("parameter `{key}`: `{v}` needs 1 or 3 values"),
        }
    }
    fn choice(&self, key: &str, options: &[&str]) -> Result<usize> {
        let v = self.raw(key);
        options.iter().position(|o| *o == v).ok_or_else(|| {
            anyhow!(
                "parameter `{key}`: `{v}` is not one of {}",
                options.join(" | ")
            )
        })
    }
}

/// Builds a model by name with `key=value` parameters.
pub fn build(name: &str, raw: &[String]) -> Result<Box<dyn Brdf<f64>>> {
    let spec = MODELS.iter().find(|m| m.name == name).ok_or_else(|| {
        let names: Vec<&str> = MODELS.iter().map(|m| m.name).collect();
        anyhow!("unknown model `{name}` (models: {})", names.join(", "))
    })?;
    let params = Params::parse(spec, raw)?;
    (spec.build)(&params).with_context(|| format!("model `{name}`"))
}

fn print_list(out: &mut impl Write) -> Result<()> {
    for m in MODELS {
        writeln!(out, "{}\n    {}", m.name, m.about)?;
        for p in m.params {
            writeln!(
                out,
                "    --param {}=…  unit {}; range {}; default {}; {}",
                p.key, p.unit, p.range, p.default, p.help
            )?;
        }
    }
    Ok(())
}

/// One parsed row: the six fields as typed, and the normalised wi and wo.
type Row<'a> = ([&'a str; 6], Vec3<f64>, Vec3<f64>);

/// The input columns.
const COLUMNS: [&str; 6] = ["wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z"];

/// Parses one row's six fields (read by `super::for_each_row`).
fn parse_row<'a>(f: &[&'a str], lineno: usize) -> Result<Option<Row<'a>>> {
    let mut v = [0.0; 6];
    for (i, s) in f.iter().enumerate() {
        let x: f64 = s
            .parse()
            .map_err(|_| anyhow!("line {lineno}: field {} `{s}` is not a number", i + 1))?;
        if !x.is_finite() {
            bail!("line {lineno}: field {} is not finite", i + 1);
        }
        v[i] = x;
    }
    let wi = Vec3::new(v[0], v[1], v[2])
        .normalize()
        .ok_or_else(|| anyhow!("line {lineno}: wi is a zero vector"))?;
    let wo = Vec3::new(v[3], v[4], v[5])
        .normalize()
        .ok_or_else(|| anyhow!("line {lineno}: wo is a zero vector"))?;
    Ok(Some(([f[0], f[1], f[2], f[3], f[4], f[5]], wi, wo)))
}

pub fn run(a: Args) -> Result<()> {
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    if a.list {
        print_list(&mut out)?;
        out.flush()?;
        return Ok(());
    }
    let name = a
        .model
        .ok_or_else(|| anyhow!("--model NAME is required (see --list)"))?;
    let model = build(&name, &a.params)?;
    writeln!(out, "{HEADER}")?;
    super::for_each_row(std::io::stdin().lock(), &COLUMNS, |lineno, f| {
        let Some((fields, wi, wo)) = parse_row(f, lineno)? else {
            return Ok(());
        };
        let c = model.eval(wi, wo);
        writeln!(
            out,
            "{},{:.16e},{:.16e},{:.16e}",
            fields.join(","),
            c.r,
            c.g,
            c.b
        )?;
        Ok(())
    })?;
    out.flush()?;
    Ok(())
}
