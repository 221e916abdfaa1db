//! A [`Spec`] from names and values: the one reading of a table description that a TOML
//! file (`cargo xtask lut generate --config`), the command line's flags and the Python
//! package's `build_table` dict share. Front ends only turn their own values into
//! [`Value`]s ([`Description::set`], [`Description::set_axis`]) or fill the fields; the
//! names, defaults, order of application and errors are here.
//!
//! Order: kind, distribution and masking (with their defaults); the roughness
//! parameterisation (resetting the axes to its defaults); `warp` and `placement` for every
//! axis; each `[axes.NAME]` table; `res` (node counts, over the axes' own `count`); then
//! encoding, interpolation, samples and seed; finally [`Spec::validate`].

use super::AxisSpec;
use super::{distribution_options, Distribution, GenError, Kind, Masking, Roughness, Spec};
use crate::limits::{self, LimitError};
use crate::{Encoding, Interpolation, Placement, Warp};
use std::collections::BTreeMap;
use std::fmt;
use std::format;
use std::path::PathBuf;
use std::string::{String, ToString};
use std::vec;
use std::vec::Vec;

/// One value of a description, in the types TOML and Python share.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A string.
    Text(String),
    /// A whole number.
    Int(i64),
    /// A floating-point number.
    Float(f64),
    /// Any other type, by its name (an error wherever it is given).
    Other(String),
}

/// The options of one axis (`[axes.NAME]`); `None` keeps the kind's default.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AxisDescription {
    /// Node count.
    pub count: Option<u64>,
    /// Smallest value.
    pub lo: Option<f64>,
    /// Largest value.
    pub hi: Option<f64>,
    /// Warp name: linear, log, sqrt, cos, sqrt-cos.
    pub warp: Option<String>,
    /// Placement name: endpoint, texel-centre (texel-center).
    pub placement: Option<String>,
}

/// A table described by names and values (the fields of the TOML file); `None` keeps the
/// default. [`Description::spec`] reads it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Description {
    /// Kind name ([`KINDS`]).
    pub kind: Option<String>,
    /// Distribution name (the catalogue's, [`distribution_options`]).
    pub model: Option<String>,
    /// Masking name ([`Masking::options`]).
    pub masking: Option<String>,
    /// Roughness parameterisation: perceptual, alpha, sigma.
    pub roughness: Option<String>,
    /// σ of a g-per-sigma table.
    pub sigma: Option<f64>,
    /// Node counts of every axis, e.g. `64x32`.
    pub res: Option<String>,
    /// Warp of every axis (before the axes' own).
    pub warp: Option<String>,
    /// Placement of every axis (before the axes' own).
    pub placement: Option<String>,
    /// Encoding name: u16, f16, f32.
    pub encoding: Option<String>,
    /// Interpolation name: linear, catmull-rom.
    pub interpolation: Option<String>,
    /// Points of the error measurement.
    pub samples: Option<u64>,
    /// Seed of the error measurement.
    pub seed: Option<u64>,
    /// Largest measured max |error| accepted ([`Description::check_max_error`]).
    pub max_error: Option<f64>,
    /// Where the front end writes the table (not read here).
    pub out: Option<PathBuf>,
    /// Each axis' own options, by axis name.
    pub axes: BTreeMap<String, AxisDescription>,
}

/// The top-level fields, by name.
pub const FIELDS: &[&str] = &[
    "kind",
    "model",
    "masking",
    "roughness",
    "sigma",
    "res",
    "warp",
    "placement",
    "encoding",
    "interpolation",
    "samples",
    "seed",
    "max-error",
    "out",
    "axes",
];
/// The fields of one axis.
pub const AXIS_FIELDS: &[&str] = &["count", "lo", "hi", "warp", "placement"];

/// The kinds by name: the one list's (`generate/kinds.rs`).
pub use super::KINDS;

/// What `samples` counts, in limit messages.
const POINTS: &str = "error-measurement points";

const WARPS: &[(&str, Warp)] = &[
    ("linear", Warp::Linear),
    ("log", Warp::Log),
    ("sqrt", Warp::Sqrt),
    ("cos", Warp::Cos),
    ("sqrt-cos", Warp::SqrtCos),
];
const PLACEMENTS: &[(&str, Placement)] = &[
    ("endpoint", Placement::Endpoint),
    ("texel-centre", Placement::TexelCentre),
    ("texel-center", Placement::TexelCentre),
];
const ENCODINGS: &[(&str, Encoding)] = &[
    ("u16", Encoding::Unorm16),
    ("f16", Encoding::F16),
    ("f32", Encoding::F32),
];
const INTERPOLATIONS: &[(&str, Interpolation)] = &[
    ("linear", Interpolation::Linear),
    ("catmull-rom", Interpolation::CatmullRom),
];

/// Why a description gives no spec. Field names are the TOML file's; [`fmt::Display`]
/// shows them as `` `name` ``, [`DescribeError::with_flags`] as `--name`.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum DescribeError {
    /// A field name that is not one of `known`.
    UnknownField {
        /// The name given (for an axis field: `axes.NAME.FIELD`).
        field: String,
        /// The accepted names.
        known: &'static [&'static str],
    },
    /// A value of the wrong type.
    WrongType {
        /// The field.
        field: String,
        /// What it takes.
        expected: &'static str,
        /// What was given.
        got: String,
    },
    /// A required field is absent.
    Missing {
        /// The field.
        field: &'static str,
        /// The accepted values.
        options: Vec<&'static str>,
    },
    /// A name that is not one of the field's options.
    UnknownName {
        /// The field.
        field: &'static str,
        /// The name given.
        value: String,
        /// The accepted names.
        options: Vec<&'static str>,
    },
    /// A g-per-sigma table without `sigma`.
    SigmaMissing,
    /// `sigma` given for a kind that takes a σ axis or none.
    SigmaNotApplicable,
    /// An axis name the table does not have.
    NoAxis {
        /// The name given.
        name: String,
        /// The kind's name.
        kind: String,
        /// The table's axes.
        axes: Vec<&'static str>,
    },
    /// `res` with a part that is not a whole number.
    ResNotWhole {
        /// The `res` value.
        res: String,
        /// The part.
        part: String,
    },
    /// `res` with another number of sizes than the table has axes.
    ResCount {
        /// The `res` value.
        res: String,
        /// Sizes given.
        given: usize,
        /// The kind's name.
        kind: String,
        /// The table's axes.
        axes: Vec<&'static str>,
    },
    /// A number beyond the tools' limits ([`crate::limits`]).
    Limit {
        /// The field (`None`: the spec as a whole).
        field: Option<String>,
        /// Where in the field's value (for `res`: the value and the part), or empty.
        detail: String,
        /// The limit.
        err: LimitError,
    },
    /// `max-error` not a positive finite number.
    MaxErrorNotPositive(f64),
    /// The measured max |error| exceeds `max-error` ([`Description::check_max_error`]).
    MaxErrorExceeded {
        /// The measured max |error|.
        measured: f32,
        /// The limit.
        limit: f64,
        /// What lowers it.
        hint: &'static str,
    },
    /// The spec the description gives is invalid ([`Spec::validate`]).
    Invalid(GenError),
}

impl DescribeError {
    /// The message with each field shown by `name`.
    fn render(&self, name: &dyn Fn(&str) -> String) -> String {
        use DescribeError as E;
        match self {
            E::UnknownField { field, known } => {
                format!("unknown field `{field}` (fields: {})", known.join(", "))
            }
            E::WrongType {
                field,
                expected,
                got,
            } => {
                format!("{} takes {expected}, not {got}", name(field))
            }
            E::Missing { field, options } => {
                format!("{} is missing ({})", name(field), options.join(", "))
            }
            E::UnknownName {
                field,
                value,
                options,
            } => {
                format!("unknown {field} `{value}` (one of: {})", options.join(", "))
            }
            E::SigmaMissing => format!("a g-per-sigma table needs {} S", name("sigma")),
            E::SigmaNotApplicable => format!(
                "{} is the fixed σ of a g-per-sigma table; other kinds take a σ axis",
                name("sigma")
            ),
            E::NoAxis {
                name: n,
                kind,
                axes,
            } => {
                format!(
                    "no axis `{n}`: this {kind} table's axes are {}",
                    axes.join(", ")
                )
            }
            E::ResNotWhole { res, part } => {
                format!(
                    "{} `{res}`: `{part}` is not a whole number of nodes",
                    name("res")
                )
            }
            E::ResCount {
                res,
                given,
                kind,
                axes,
            } => format!(
                "{} `{res}` gives {given} size(s); a {kind} table has {} axes ({}), e.g. {}",
                name("res"),
                axes.len(),
                axes.join(", "),
                vec!["64"; axes.len()].join("x")
            ),
            E::Limit {
                field: None, err, ..
            } => err.to_string(),
            E::Limit {
                field: Some(f),
                detail,
                err,
            } => format!("{}{detail}: {err}", name(f)),
            E::MaxErrorNotPositive(e) => {
                format!("{} must be a positive number (got {e})", name("max-error"))
            }
            E::MaxErrorExceeded {
                measured,
                limit,
                hint,
            } => format!(
                "measured max |error| {measured:.3e} exceeds {} {limit:.3e}; nothing written \
                 ({hint} lower it)",
                name("max-error")
            ),
            E::Invalid(e) => e.to_string(),
        }
    }

    /// The message with fields named as command-line flags (`--res`), for a front end whose
    /// flags carry the fields' names.
    pub fn with_flags(&self) -> String {
        self.render(&|f| {
            if f.starts_with("axes.") {
                format!("`{f}`")
            } else {
                format!("--{f}")
            }
        })
    }
}

impl fmt::Display for DescribeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render(&|n| format!("`{n}`")))
    }
}

impl std::error::Error for DescribeError {}

impl From<GenError> for DescribeError {
    fn from(e: GenError) -> Self {
        DescribeError::Invalid(e)
    }
}

fn type_name(v: &Value) -> String {
    match v {
        Value::Text(s) => format!("the text {s:?}"),
        Value::Int(i) => format!("the whole number {i}"),
        Value::Float(x) => format!("the number {x}"),
        Value::Other(t) => format!("a {t}"),
    }
}

fn text(field: &str, v: Value) -> Result<String, DescribeError> {
    match v {
        Value::Text(s) => Ok(s),
        o => Err(wrong(field, "text", &o)),
    }
}

fn float(field: &str, v: Value) -> Result<f64, DescribeError> {
    match v {
        Value::Float(x) => Ok(x),
        Value::Int(i) => Ok(i as f64),
        o => Err(wrong(field, "a number", &o)),
    }
}

fn whole(field: &str, v: Value) -> Result<u64, DescribeError> {
    match v {
        // A negative count is below every limit: 0 names the limit's lower end.
        Value::Int(i) => Ok(i.max(0) as u64),
        o => Err(wrong(field, "a whole number", &o)),
    }
}

fn wrong(field: &str, expected: &'static str, got: &Value) -> DescribeError {
    DescribeError::WrongType {
        field: field.to_string(),
        expected,
        got: type_name(got),
    }
}

/// One of `options` by name.
fn choose<T: Copy>(
    field: &'static str,
    v: &str,
    options: &[(&'static str, T)],
) -> Result<T, DescribeError> {
    options
        .iter()
        .find(|(n, _)| *n == v)
        .map(|(_, t)| *t)
        .ok_or_else(|| DescribeError::UnknownName {
            field,
            value: v.to_string(),
            options: options.iter().map(|(n, _)| *n).collect(),
        })
}

/// A field name as given, with `_` read as `-` (`max_error` is `max-error`).
fn field_name(key: &str) -> String {
    key.replace('_', "-")
}

impl Description {
    /// Sets the top-level field `key` (`_` read as `-`); `axes` is set per axis with
    /// [`Description::set_axis`].
    pub fn set(&mut self, key: &str, v: Value) -> Result<(), DescribeError> {
        let k = field_name(key);
        let k = k.as_str();
        match k {
            "kind" => self.kind = Some(text(k, v)?),
            "model" => self.model = Some(text(k, v)?),
            "masking" => self.masking = Some(text(k, v)?),
            "roughness" => self.roughness = Some(text(k, v)?),
            "sigma" => self.sigma = Some(float(k, v)?),
            "res" => self.res = Some(text(k, v)?),
            "warp" => self.warp = Some(text(k, v)?),
            "placement" => self.placement = Some(text(k, v)?),
            "encoding" => self.encoding = Some(text(k, v)?),
            "interpolation" => self.interpolation = Some(text(k, v)?),
            "samples" => self.samples = Some(whole(k, v)?),
            "seed" => self.seed = Some(whole(k, v)?),
            "max-error" => self.max_error = Some(float(k, v)?),
            "out" => self.out = Some(PathBuf::from(text(k, v)?)),
            "axes" => return Err(wrong(k, "a table of axes", &v)),
            _ => {
                return Err(DescribeError::UnknownField {
                    field: k.to_string(),
                    known: FIELDS,
                })
            }
        }
        Ok(())
    }

    /// Names axis `axis` (`[axes.AXIS]`), with or without fields: [`Description::spec`]
    /// refuses a name the table does not have, so an empty table of an unknown axis is an
    /// error too.
    pub fn name_axis(&mut self, axis: &str) {
        self.axes.entry(axis.to_string()).or_default();
    }

    /// Sets field `key` of axis `axis` (`[axes.AXIS] KEY = v`); the axis name is checked
    /// against the table's by [`Description::spec`].
    pub fn set_axis(&mut self, axis: &str, key: &str, v: Value) -> Result<(), DescribeError> {
        let field = format!("axes.{axis}.{key}");
        let a = self.axes.entry(axis.to_string()).or_default();
        match key {
            "count" => a.count = Some(whole(&field, v)?),
            "lo" => a.lo = Some(float(&field, v)?),
            "hi" => a.hi = Some(float(&field, v)?),
            "warp" => a.warp = Some(text(&field, v)?),
            "placement" => a.placement = Some(text(&field, v)?),
            _ => {
                return Err(DescribeError::UnknownField {
                    field,
                    known: AXIS_FIELDS,
                })
            }
        }
        Ok(())
    }

    /// The spec this description gives, validated ([`Spec::validate`]); the work-size
    /// limits are a separate check ([`check_limits`]).
    pub fn spec(&self) -> Result<Spec, DescribeError> {
        if let Some(e) = self.max_error {
            if !(e.is_finite() && e > 0.0) {
                return Err(DescribeError::MaxErrorNotPositive(e));
            }
        }
        let (kind_name, mut spec) = self.kind_and_model()?;
        if let Some(r) = &self.roughness {
            let options = Roughness::ALL.map(|r| (r.name(), r));
            spec.roughness = choose("roughness", r, &options)?;
            spec.axes = spec.default_axes();
        }
        self.apply_axes(&kind_name, &mut spec)?;
        self.apply_storage(&mut spec)?;
        spec.validate()?;
        Ok(spec)
    }

    /// Applies the grid and storage options (`res`, `warp`, `placement`, `axes`,
    /// `encoding`, `interpolation`, `samples`, `seed`) to an existing spec, such as one of
    /// the default set ([`super::default_set`]); `kind`, `model`, `masking`, `roughness`
    /// and `sigma` are not read. Not validated.
    pub fn apply(&self, kind_name: &str, spec: &mut Spec) -> Result<(), DescribeError> {
        self.apply_axes(kind_name, spec)?;
        self.apply_storage(spec)
    }

    /// The kind's name, and the spec of its kind, distribution and masking with their
    /// defaults (Torrance–Sparrow for G tables, its modified G; Smith height-correlated
    /// otherwise; a sheen table's distribution is Charlie, the option does not apply).
    fn kind_and_model(&self) -> Result<(String, Spec), DescribeError> {
        let names = || {
            KINDS
                .iter()
                .map(|(n, _)| *n)
                .filter(|n| *n != "sheen-e-estevez-kulla")
        };
        let Some(kind_s) = self.kind.clone() else {
            return Err(DescribeError::Missing {
                field: "kind",
                options: names().collect(),
            });
        };
        let mut kind = choose("kind", &kind_s, KINDS)?;
        match (&mut kind, self.sigma) {
            (Kind::GPerSigma { sigma }, Some(s)) => *sigma = s,
            (Kind::GPerSigma { .. }, None) => return Err(DescribeError::SigmaMissing),
            (_, Some(_)) => return Err(DescribeError::SigmaNotApplicable),
            (_, None) => {}
        }
        let dist = match (&self.model, kind.def().default_distribution) {
            (Some(m), _) => choose("model", m, &distribution_options())?,
            (None, Some(d)) => d,
            (None, None) => {
                return Err(DescribeError::Missing {
                    field: "model",
                    options: vec!["ggx", "beckmann", "torrance-sparrow"],
                })
            }
        };
        let masking = match &self.masking {
            Some(m) => choose("masking", m, &Masking::options())?,
            None if dist == Distribution::TorranceSparrow => Masking::Modified,
            None => Masking::SmithCorrelated,
        };
        Ok((kind_s, Spec::new(kind, dist, masking)))
    }

    /// `warp` and `placement` for every axis, each `[axes.NAME]`, then `res`.
    fn apply_axes(&self, kind: &str, spec: &mut Spec) -> Result<(), DescribeError> {
        let names = spec.axis_names();
        if let Some(w) = &self.warp {
            let w = choose("warp", w, WARPS)?;
            spec.axes.iter_mut().for_each(|x| x.warp = w);
        }
        if let Some(p) = &self.placement {
            let p = choose("placement", p, PLACEMENTS)?;
            spec.axes.iter_mut().for_each(|x| x.placement = p);
        }
        for (name, a) in &self.axes {
            let i = names
                .iter()
                .position(|n| n == name)
                .ok_or_else(|| DescribeError::NoAxis {
                    name: name.clone(),
                    kind: kind.to_string(),
                    axes: names.clone(),
                })?;
            apply_axis(name, a, &mut spec.axes[i])?;
        }
        if let Some(res) = &self.res {
            let counts = res_counts(res)?;
            if counts.len() != names.len() {
                return Err(DescribeError::ResCount {
                    res: res.clone(),
                    given: counts.len(),
                    kind: kind.to_string(),
                    axes: names,
                });
            }
            for (x, c) in spec.axes.iter_mut().zip(counts) {
                x.count = c;
            }
        }
        Ok(())
    }

    /// Encoding, interpolation, samples and seed.
    fn apply_storage(&self, spec: &mut Spec) -> Result<(), DescribeError> {
        if let Some(e) = &self.encoding {
            spec.encoding = choose("encoding", e, ENCODINGS)?;
        }
        if let Some(i) = &self.interpolation {
            spec.interpolation = choose("interpolation", i, INTERPOLATIONS)?;
        }
        if let Some(n) = self.samples {
            limits::check_samples(POINTS, n).map_err(|err| DescribeError::Limit {
                field: Some("samples".into()),
                detail: String::new(),
                err,
            })?;
            spec.samples = n as u32;
        }
        if let Some(s) = self.seed {
            spec.seed = s;
        }
        Ok(())
    }

    /// Fails when the measured max |error| exceeds `max-error`, with a hint fitting the
    /// spec's interpolation (a NaN measurement always fails).
    pub fn check_max_error(&self, spec: &Spec, measured: f32) -> Result<(), DescribeError> {
        let Some(limit) = self.max_error else {
            return Ok(());
        };
        if measured.is_nan() || measured as f64 > limit {
            let hint = match spec.interpolation {
                Interpolation::Linear => "more nodes per axis, another warp or catmull-rom",
                Interpolation::CatmullRom => "more nodes per axis or another warp",
            };
            return Err(DescribeError::MaxErrorExceeded {
                measured,
                limit,
                hint,
            });
        }
        Ok(())
    }
}

/// One axis' own options onto `x`.
fn apply_axis(name: &str, a: &AxisDescription, x: &mut AxisSpec) -> Result<(), DescribeError> {
    if let Some(c) = a.count {
        limits::check_range("nodes per axis", c, 2, limits::MAX_NODES_PER_AXIS as u64).map_err(
            |err| DescribeError::Limit {
                field: Some(format!("axes.{name}.count")),
                detail: String::new(),
                err,
            },
        )?;
        x.count = c as u32;
    }
    x.lo = a.lo.unwrap_or(x.lo);
    x.hi = a.hi.unwrap_or(x.hi);
    if let Some(w) = &a.warp {
        x.warp = choose("warp", w, WARPS)?;
    }
    if let Some(p) = &a.placement {
        x.placement = choose("placement", p, PLACEMENTS)?;
    }
    Ok(())
}

/// The node counts of `res` (`64x32`), each a whole number within the limit per axis; a
/// number too large for any integer type is over the limit, not "not a number".
pub fn res_counts(res: &str) -> Result<Vec<u32>, DescribeError> {
    let max = limits::MAX_NODES_PER_AXIS as u64;
    res.split('x')
        .map(|t| {
            let t = t.trim();
            let n = match t.parse::<u64>() {
                Ok(n) => n,
                Err(_) if !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit()) => u64::MAX,
                Err(_) => {
                    return Err(DescribeError::ResNotWhole {
                        res: res.to_string(),
                        part: t.to_string(),
                    })
                }
            };
            limits::check_range("nodes per axis", n, 2, max).map_err(|err| {
                DescribeError::Limit {
                    field: Some("res".into()),
                    detail: format!(" `{res}`: `{t}`"),
                    err,
                }
            })?;
            Ok(n as u32)
        })
        .collect()
}

/// Every number of `spec` that sizes memory or time, against the tools' limits
/// ([`crate::limits`]: points, nodes per axis, stored values, estimated work), before
/// anything is allocated or computed.
pub fn check_limits(spec: &Spec) -> Result<(), DescribeError> {
    let limit = |err| DescribeError::Limit {
        field: None,
        detail: String::new(),
        err,
    };
    limits::check_samples(POINTS, spec.samples as u64).map_err(limit)?;
    let counts: Vec<u64> = spec.axes.iter().map(|x| x.count as u64).collect();
    let def = spec.kind.def();
    let nodes = limits::check_grid(&counts, def.channels.len() as u64).map_err(limit)?;
    let model = spec.model()?;
    limits::check_generate(def.table, model, nodes, spec.samples as u64).map_err(limit)
}
