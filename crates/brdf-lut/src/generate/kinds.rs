//! The one list of table kinds. A new kind is added here and nowhere else in this crate
//! (besides its kernel's own file): its BLUT code, shape and cost ([`TableKind`]), and,
//! with the `generate` feature, its generator entry — names, axes, channels, kernel,
//! reference, model and checks (`Kind`, `Kind::def`, the entries below; what an entry
//! holds is `generate::KindDef`). docs/architecture.md, "Adding a table kind", walks
//! through it.

/// What a table holds. Its code in the header is its position in [`TableKind::ALL`]
/// (docs/lut-format.md §3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TableKind {
    /// The paper's one-sided passing factor F(θ, φ[, σ]) = M(θ, (θ − φ)/2) (channel `F`);
    /// G = min(F(|θr|, sgn θr · θi), F(θi, θr)).
    #[default]
    PassingFactor,
    /// Split-sum (A, B) (channels `A`, `B`): the environment-lighting pair of the split-sum
    /// approximation, docs/conventions.md §8.
    SplitSum,
    /// Directional albedo E(μ, r) with F = 1 (channel `E`), Kulla–Conty.
    DirectionalAlbedo,
    /// Cosine-weighted average albedo E_avg(r) = 2∫ E(μ) μ dμ (channel `Eavg`).
    AverageAlbedo,
    /// Sheen directional albedo E_sheen(μ, r) = ∫ D V μl dωl of the Charlie sheen with
    /// colour 1 (channel `E`); the visibility is the header's model.
    SheenAlbedo,
    /// Rough-glass directional albedo over (μ, roughness, η), channels `R` (reflected) and
    /// `T` (transmitted energy fraction: the adjoint, without the η² radiance factor), light
    /// arriving from the side of index 1, η the far side's index over the near side's
    /// (docs/lut-format.md, "Rough glass"). The model (distribution) is in the generator.
    GlassAlbedo,
    /// Rough-glass average albedo over (roughness, η): 2∫ (R, T)(μ) μ dμ (channels `R`, `T`).
    GlassAverageAlbedo,
}

impl TableKind {
    /// Every kind, in code order.
    pub const ALL: [TableKind; 7] = [
        TableKind::PassingFactor,
        TableKind::SplitSum,
        TableKind::DirectionalAlbedo,
        TableKind::AverageAlbedo,
        TableKind::SheenAlbedo,
        TableKind::GlassAlbedo,
        TableKind::GlassAverageAlbedo,
    ];

    /// Estimated microseconds of one core per direct evaluation: (Smith or closed-form
    /// models, the modified G), upper estimates (an average-albedo point of the default
    /// assets was measured at 6–9 ms; a sheen node at 0.86 ms on average over the 1024²
    /// Khronos grid).
    const fn cost_us(self) -> (u32, u32) {
        match self {
            TableKind::PassingFactor => (5, 5),
            TableKind::SplitSum | TableKind::DirectionalAlbedo => (100, 400),
            TableKind::AverageAlbedo => (10_000, 40_000),
            TableKind::SheenAlbedo => (1_500, 1_500),
            TableKind::GlassAlbedo => (2_000, 2_000),
            TableKind::GlassAverageAlbedo => (200_000, 200_000),
        }
    }

    /// Its code in the header.
    pub const fn code(self) -> u32 {
        self as u32
    }

    /// The kind of a header code; `None` for a code this version does not know.
    pub fn from_code(code: u32) -> Option<TableKind> {
        TableKind::ALL.get(code as usize).copied()
    }

    /// Whether a table of this kind may have `axes` axes and `channels` channels (a match of
    /// comparisons: it is in every reader, and the WASM module's 64 KiB budget counts its
    /// bytes).
    pub const fn fits(self, axes: usize, channels: usize) -> bool {
        match self {
            TableKind::PassingFactor => channels == 1 && (axes == 2 || axes == 3),
            TableKind::SplitSum => channels == 2 && axes == 2,
            TableKind::DirectionalAlbedo => channels == 1 && axes == 2,
            TableKind::AverageAlbedo => channels == 1 && axes == 1,
            TableKind::SheenAlbedo => channels == 1 && axes == 2,
            TableKind::GlassAlbedo => channels == 2 && axes == 3,
            TableKind::GlassAverageAlbedo => channels == 2 && axes == 2,
        }
    }

    /// Estimated microseconds of one core to evaluate the direct kernel once (upper
    /// estimates); `modified` for the modified G, which costs more per evaluation than
    /// Smith's closed forms.
    pub const fn cost_per_point_us(self, modified: bool) -> u64 {
        let c = self.cost_us();
        (if modified { c.1 } else { c.0 }) as u64
    }
}

#[cfg(feature = "generate")]
pub use list::{Kind, KINDS};

/// The generator's entries (`generate` feature).
#[cfg(feature = "generate")]
mod list {
    use super::super::{
        entry, entry::HeaderModel, glass, Check, Distribution, GenError, KindDef, Masking, Role,
        SheenVisibility, Spec, Work,
    };
    use super::TableKind as T;
    use crate::{Header, Model, Warp};
    use Role::{Eta, Mu, Phi, Sigma, Theta};

    /// What the table holds (each kind's axes, channels and kernel: [`Kind::def`]).
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub enum Kind {
        /// The modified G's passing factor F(θ, φ) for one σ (2 axes: theta, phi).
        GPerSigma {
            /// The RMS slope σ > 0.
            sigma: f64,
        },
        /// The modified G's passing factor F(θ, φ, σ) (3 axes: theta, phi, sigma).
        GOverSigma,
        /// Split-sum (A, B) (2 axes: mu, roughness).
        SplitSum,
        /// Directional albedo E(μ) with F = 1 (2 axes: mu, roughness).
        Albedo,
        /// Average albedo E_avg (1 axis: roughness).
        AverageAlbedo,
        /// Sheen directional albedo E_sheen(μ, r) = ∫ D V μl dωl of the Charlie sheen
        /// (colour 1) with this visibility (2 axes: mu, roughness; perceptual r,
        /// α = r² ≥ 1e-4). The spec's distribution and masking do not apply.
        SheenAlbedo {
            /// The visibility term.
            visibility: SheenVisibility,
        },
        /// Rough-glass directional albedo (R, T) (3 axes: mu, roughness, eta;
        /// `generate/glass.rs`).
        GlassAlbedo,
        /// Rough-glass average albedo (R_avg, T_avg) (2 axes: roughness, eta).
        GlassAverageAlbedo,
    }

    const EK: SheenVisibility = SheenVisibility::EstevezKulla;

    /// The kinds by the names the command line and TOML files take (a g-per-sigma
    /// table's σ is filled in from `sigma`; a sheen table's visibility is part of its
    /// name, `sheen-e` alone the specification's).
    pub const KINDS: &[(&str, Kind)] = &[
        ("g-per-sigma", Kind::GPerSigma { sigma: 0.0 }),
        ("g-over-sigma", Kind::GOverSigma),
        ("split-sum", Kind::SplitSum),
        ("e", Kind::Albedo),
        ("e-avg", Kind::AverageAlbedo),
        ("sheen-e", Kind::SheenAlbedo { visibility: EK }),
        (
            "sheen-e-estevez-kulla",
            Kind::SheenAlbedo { visibility: EK },
        ),
        (
            "sheen-e-ashikhmin",
            Kind::SheenAlbedo {
                visibility: SheenVisibility::Ashikhmin,
            },
        ),
        ("glass-e", Kind::GlassAlbedo),
        ("glass-e-avg", Kind::GlassAverageAlbedo),
    ];

    impl Kind {
        /// This kind's entry in the one list of kinds.
        pub fn def(&self) -> &'static KindDef {
            match self {
                Kind::GPerSigma { .. } => &G_PER_SIGMA,
                Kind::GOverSigma => &G_OVER_SIGMA,
                Kind::SplitSum => &SPLIT_SUM,
                Kind::Albedo => &ALBEDO,
                Kind::AverageAlbedo => &AVERAGE_ALBEDO,
                Kind::SheenAlbedo { .. } => &SHEEN_ALBEDO,
                Kind::GlassAlbedo => &GLASS_ALBEDO,
                Kind::GlassAverageAlbedo => &GLASS_AVERAGE_ALBEDO,
            }
        }
    }

    // The entries: name, kind, kind code, axes with their default node counts, channels;
    // the microfacet kernels' defaults (`KindDef::microfacet`) unless set.
    /// The roughness axis.
    const R: Role = Role::Roughness;
    const MU_R: &[(Role, u32)] = &[(Mu, 64), (R, 64)];
    const G_PER_SIGMA: KindDef = KindDef {
        from_header: g_per_sigma,
        ..KindDef::passing_factor(
            "g-per-sigma",
            Kind::GPerSigma { sigma: 0.0 },
            &[(Theta, 128), (Phi, 126)],
        )
    };
    const G_OVER_SIGMA: KindDef = KindDef::passing_factor(
        "g-over-sigma",
        Kind::GOverSigma,
        &[(Theta, 64), (Phi, 64), (Sigma, 31)],
    );
    const SPLIT_SUM: KindDef = KindDef {
        row: Some(entry::converged_row),
        ..KindDef::microfacet("split-sum", Kind::SplitSum, T::SplitSum, MU_R, &["A", "B"])
    };
    const ALBEDO: KindDef = KindDef {
        row: Some(entry::converged_row),
        ..KindDef::microfacet("e", Kind::Albedo, T::DirectionalAlbedo, MU_R, &["E"])
    };
    const AVERAGE_ALBEDO: KindDef = KindDef::microfacet(
        "e-avg",
        Kind::AverageAlbedo,
        T::AverageAlbedo,
        &[(R, 32)],
        &["Eavg"],
    );
    // `generate/sheen.rs`: both axes √-warped (nodes at lo + s²(hi − lo), denser toward
    // grazing μ and small r, where E bends most): the lookup is two square roots where a
    // log warp's is a call of `logf`, and its linear u16 form takes the inlined two-lane
    // lookup (harness `sheen_e_lut`).
    const SHEEN_ALBEDO: KindDef = KindDef {
        warp: Some(Warp::Sqrt),
        value: sheen_node,
        point: sheen_point,
        reference: sheen_reference,
        model: sheen_model,
        validate: sheen_validate,
        record: KindDef::adaptive,
        from_header: sheen_from_header,
        default_distribution: Some(Distribution::Ggx),
        ..KindDef::microfacet(
            "sheen-e",
            Kind::SheenAlbedo { visibility: EK },
            T::SheenAlbedo,
            MU_R,
            &["E"],
        )
    };
    const GLASS_ALBEDO: KindDef = KindDef::glass(
        "glass-e",
        Kind::GlassAlbedo,
        T::GlassAlbedo,
        &[(Mu, 32), (R, 32), (Eta, 32)],
    );
    const GLASS_AVERAGE_ALBEDO: KindDef = KindDef::glass(
        "glass-e-avg",
        Kind::GlassAverageAlbedo,
        T::GlassAverageAlbedo,
        &[(R, 32), (Eta, 32)],
    );

    impl KindDef {
        /// A passing-factor table of the modified G: one channel `F`, its error that of a G
        /// lookup ([`Check::ModifiedG`]), its 20-point rule recorded.
        const fn passing_factor(
            name: &'static str,
            kind: Kind,
            axes: &'static [(Role, u32)],
        ) -> KindDef {
            KindDef {
                check: Check::ModifiedG,
                validate: entry::validate_passing_factor,
                record: |_| &[20],
                default_distribution: Some(Distribution::TorranceSparrow),
                ..KindDef::microfacet(name, kind, T::PassingFactor, axes, &["F"])
            }
        }

        /// A rough-glass table (`generate/glass.rs`): channels R, T, adaptive.
        const fn glass(
            name: &'static str,
            kind: Kind,
            table: T,
            axes: &'static [(Role, u32)],
        ) -> KindDef {
            KindDef {
                value: glass_node,
                point: |s, x, out| {
                    glass_node(s, x, out);
                },
                reference: |s, x| glass::reference(s, x).unwrap_or(([f64::NAN; 2], 0.0)),
                model: glass_model,
                validate: glass::validate,
                record: KindDef::adaptive,
                from_header: glass_from_header,
                ..KindDef::microfacet(name, kind, table, axes, &["R", "T"])
            }
        }
    }

    /// The `g-per-sigma` kind of a header: its σ is the generator's.
    fn g_per_sigma(def: &KindDef, h: &Header<'_>) -> Option<HeaderModel> {
        let (_, d, m) = entry::microfacet_from_header(def, h)?;
        Some((
            Kind::GPerSigma {
                sigma: h.generator.sigma?,
            },
            d,
            m,
        ))
    }

    fn sheen_visibility(s: &Spec) -> SheenVisibility {
        match s.kind {
            Kind::SheenAlbedo { visibility } => visibility,
            _ => EK,
        }
    }

    /// The `sheen-e` node at x = (μ, r) (`generate/sheen.rs`).
    fn sheen_node(s: &Spec, x: &[f64], out: &mut [f64]) -> Work {
        super::super::sheen::node(sheen_visibility(s), x[0], x[1], out)
    }

    /// The direct sheen albedo at x = (μ, r), what the error measurement compares with.
    fn sheen_point(s: &Spec, x: &[f64], out: &mut [f64]) {
        let e = super::super::sheen_e(x[0], x[1], super::super::SHEEN_TOL);
        if let Some(o) = out.first_mut() {
            *o = e.value[super::super::sheen::channel(sheen_visibility(s))];
        }
    }

    fn sheen_reference(s: &Spec, x: &[f64]) -> ([f64; 2], f64) {
        super::super::sheen::reference(sheen_visibility(s), x[0], x[1])
    }

    fn sheen_model(s: &Spec) -> Result<Model, GenError> {
        Ok(Model::from_sheen(sheen_visibility(s)))
    }

    fn sheen_validate(s: &Spec) -> Result<(), GenError> {
        if s.roughness != super::super::Roughness::Perceptual {
            return Err(GenError::Invalid(
                "sheen tables are parameterised by the perceptual roughness r only".into(),
            ));
        }
        Ok(())
    }

    /// A sheen table's spec has no microfacet G: those fields are set and not used.
    fn sheen_from_header(_: &KindDef, h: &Header<'_>) -> Option<HeaderModel> {
        let visibility = h.generator.model.sheen()?;
        let kind = Kind::SheenAlbedo { visibility };
        Some((kind, Distribution::Ggx, Masking::SmithCorrelated))
    }

    fn glass_node(s: &Spec, x: &[f64], out: &mut [f64]) -> Work {
        glass::node(s, x, out).unwrap_or_default()
    }

    fn glass_model(s: &Spec) -> Result<Model, GenError> {
        Model::from_dielectric(s.distribution).ok_or_else(|| {
            GenError::Invalid(
                "rough-glass tables take the GGX distribution (the rough dielectric's \
                 Beckmann is not tabulated yet)"
                    .into(),
            )
        })
    }

    /// A rough-glass table's model is its distribution; its G is separable Smith.
    fn glass_from_header(def: &KindDef, h: &Header<'_>) -> Option<HeaderModel> {
        let d = h.generator.model.dielectric()?;
        Some((def.kind, d, Masking::SmithSeparable))
    }
}
