//! The header's model codes against the model catalogue and the format's own document:
//! every catalogue pair (distribution, G term) that tables are made of has a code, and the
//! code gives the pair back; the codes on disk are the ones docs/lut-format.md §3 lists.

use brdf_core::catalogue::{DistributionId, DISTRIBUTIONS, MASKINGS};
use brdf_core::models::{GeometricTerm, SheenVisibility};
use brdf_lut::generate::{Distribution, Kind, Masking, Spec};
use brdf_lut::{Convention, Model, TableKind};

/// The (distribution, G) pairs the catalogue says tables are made of, plus the G tables
/// (no distribution) of the modified G in both readings.
fn tabulated() -> Vec<(Option<DistributionId>, GeometricTerm)> {
    let mut v = vec![
        (None, GeometricTerm::Modified),
        (None, GeometricTerm::ModifiedPrinted),
    ];
    for d in DISTRIBUTIONS {
        v.extend(d.tabulated.iter().map(|&g| (Some(d.id), g)));
    }
    v
}

#[test]
fn every_tabulated_catalogue_pair_has_a_code_and_back() {
    let pairs = tabulated();
    for &(d, g) in &pairs {
        let (m, c) = Model::from_catalogue(d, g).unwrap_or_else(|| panic!("{d:?} {g:?}"));
        assert_eq!(m.catalogue(c), (d, g), "{m:?} {c:?}");
        // Through the bytes: the code read back is the same model.
        assert_eq!(Model::from_code(m.code() as u32), Some(m));
    }
    // Distinct pairs, distinct (code, convention): the map is one-to-one.
    let mut seen: Vec<(Model, Convention)> = pairs
        .iter()
        .map(|&(d, g)| Model::from_catalogue(d, g).unwrap())
        .collect();
    seen.sort_by_key(|&(m, c)| (m.code(), c as u8));
    seen.dedup();
    assert_eq!(seen.len(), pairs.len());
    // Every code is some catalogue pair (its reciprocal reading), and that pair maps back.
    for &m in Model::ALL {
        if let Some(v) = m.sheen() {
            assert_eq!(Model::from_sheen(v), m);
            continue;
        }
        if let Some(d) = m.dielectric() {
            assert_eq!(Model::from_dielectric(d), Some(m));
            continue;
        }
        let (d, g) = m.catalogue(Convention::Reciprocal);
        assert!(pairs.contains(&(d, g)), "{m:?} → {d:?} {g:?}");
        assert_eq!(
            Model::from_catalogue(d, g),
            Some((m, Convention::Reciprocal))
        );
    }
}

/// Every visibility option of the catalogue's sheen has its own code, and the code gives it
/// back; sheen codes are not microfacet pairs.
#[test]
fn every_sheen_visibility_has_a_code_and_back() {
    let mut codes: Vec<u8> = SheenVisibility::ALL
        .iter()
        .map(|&v| {
            let m = Model::from_sheen(v);
            assert_eq!(m.sheen(), Some(v), "{v:?}");
            assert_eq!(Model::from_code(m.code() as u32), Some(m));
            assert_eq!(
                Model::from_catalogue(None, GeometricTerm::Modified).map(|x| x.0 == m),
                Some(false)
            );
            m.code()
        })
        .collect();
    codes.dedup();
    assert_eq!(codes.len(), SheenVisibility::ALL.len());
}

#[test]
fn pairs_no_table_is_made_of_have_no_code() {
    let pairs = tabulated();
    let dists = [None]
        .into_iter()
        .chain(DISTRIBUTIONS.iter().map(|d| Some(d.id)));
    for d in dists {
        for g in MASKINGS.iter().map(|m| m.term) {
            if !pairs.contains(&(d, g)) {
                assert_eq!(Model::from_catalogue(d, g), None, "{d:?} {g:?}");
            }
        }
    }
}

/// The codes on disk as the format document lists them ("0 `ModifiedG`, 1 ..."), read from
/// docs/lut-format.md: an independent record of what committed files contain.
#[test]
fn codes_are_the_documented_ones() {
    let doc = include_str!("../../../docs/lut-format.md");
    let at = doc
        .find("`model: Model` (")
        .expect("the model list in lut-format.md");
    let list = &doc[at + "`model: Model` (".len()..];
    let list = &list[..list.find(';').unwrap()];
    let mut n = 0;
    for item in list.split(',') {
        let mut w = item.split_whitespace();
        let code: u32 = w.next().unwrap().parse().unwrap();
        let name = w.next().unwrap().trim_matches('`');
        let m = Model::from_code(code).unwrap_or_else(|| panic!("code {code}"));
        assert_eq!(format!("{m:?}"), name);
        assert_eq!(m.code() as u32, code);
        n += 1;
    }
    assert_eq!(n, Model::ALL.len());
    assert_eq!(Model::from_code(Model::ALL.len() as u32), None);
}

/// The generator's names are the catalogue's, old spellings accepted; every pair it can
/// build is a catalogue pair with a code.
#[test]
fn generator_options_are_the_catalogue_s() {
    assert_eq!(Masking::from_name("blinn"), Some(Masking::Blinn));
    assert_eq!(Masking::from_name("v-cavity"), Some(Masking::Blinn));
    assert_eq!(Masking::Blinn.name(), "blinn");
    assert_eq!(Masking::from_name("none"), None);
    for m in Masking::ALL {
        assert_eq!(Masking::from_name(m.name()), Some(m));
        assert!(MASKINGS.iter().any(|s| s.name == m.name()));
    }
    let pairs = tabulated();
    for d in DISTRIBUTIONS {
        for m in Masking::ALL {
            let spec = Spec::new(Kind::SplitSum, d.id, m);
            let ok = pairs.contains(&(Some(d.id), m.term()));
            assert_eq!(spec.model().is_ok(), ok, "{} {}", d.name, m.name());
        }
    }
    let opts = brdf_lut::generate::distribution_options();
    assert!(opts.contains(&("torrance-sparrow", Distribution::TorranceSparrow)));
    assert_eq!(
        opts.len(),
        DISTRIBUTIONS.iter().map(|d| 1 + d.aliases.len()).sum()
    );
}

/// The table-kind codes and shapes against docs/lut-format.md §3 (the field-3 row and the
/// "`kind` fixes the shape" rule), and every generator kind's axes and channels against the
/// shape of its code: the one list of kinds (`src/generate/kinds.rs`) says what the format says.
#[test]
fn kind_codes_and_shapes_are_the_documented_ones() {
    let doc = include_str!("../../../docs/lut-format.md");
    let row = doc
        .lines()
        .find(|l| l.contains("| `kind`") && l.contains("GlassAverageAlbedo"))
        .expect("the kind row");
    let cell = row.split('|').nth(4).unwrap();
    let mut codes = 0;
    let words: Vec<&str> = cell.split_whitespace().collect();
    for w in words.windows(2) {
        let Ok(code) = w[0].parse::<u32>() else {
            continue;
        };
        let name = w[1].trim_end_matches(',').trim_matches('`');
        let kind = TableKind::from_code(code).unwrap_or_else(|| panic!("code {code}"));
        assert_eq!(format!("{kind:?}"), name);
        assert_eq!(kind.code(), code);
        codes += 1;
    }
    assert_eq!(codes, TableKind::ALL.len());
    assert_eq!(TableKind::from_code(codes as u32), None);
    // "* `kind` fixes the shape: `A` 1 channel and 2 or 3 axes; `B` 2 channels (…) and 2 axes; …"
    let start = doc.find("* `kind` fixes the shape:").unwrap();
    let rule = &doc[start..start + doc[start..].find("\n* ").unwrap()];
    let rule = rule.split_once(':').unwrap().1.replace('\n', " ");
    let mut seen = 0;
    for clause in rule.split(';') {
        let name = clause.split('`').nth(1).unwrap();
        let kind = *TableKind::ALL
            .iter()
            .find(|k| format!("{k:?}") == name)
            .unwrap_or_else(|| panic!("{name}"));
        let ch = clause.find(" channel").unwrap();
        let channels: Vec<usize> = clause[..ch]
            .split_whitespace()
            .last()
            .and_then(|w| w.parse().ok())
            .into_iter()
            .collect();
        let between = &clause[ch..clause.find(" ax").unwrap()];
        let between = between.rsplit(')').next().unwrap();
        let axes: Vec<usize> = between
            .split(|c: char| !c.is_ascii_digit())
            .filter_map(|t| t.parse().ok())
            .collect();
        assert_eq!(channels.len(), 1, "{clause}");
        for c in 1..=4 {
            for d in 1..=3 {
                let documented = c == channels[0] && axes.contains(&d);
                assert_eq!(
                    kind.fits(d, c),
                    documented,
                    "{name}: {d} axes, {c} channels"
                );
            }
        }
        seen += 1;
    }
    assert_eq!(seen, TableKind::ALL.len());
    for (name, kind) in brdf_lut::generate::KINDS {
        let def = kind.def();
        assert!(def.table.fits(def.axes.len(), def.channels.len()), "{name}");
    }
}
