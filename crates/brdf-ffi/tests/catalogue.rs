//! The C header's option values against the model catalogue: every masking term, sheen
//! visibility and dielectric distribution of `brdf_core::catalogue` is a `#define` of
//! include/brdf.h named after it (upper case, `-` as `_`) whose value is its index there, and
//! the header defines no other value of those families. Reads the header C users compile.

use brdf_core::catalogue::MASKINGS;
use brdf_core::models::{DielectricDistribution, SheenVisibility};

/// The `#define PREFIX… value` lines of brdf.h, as (suffix, value).
fn defines(prefix: &str) -> Vec<(String, u32)> {
    let h = include_str!("../include/brdf.h");
    h.lines()
        .filter_map(|l| l.strip_prefix("#define "))
        .filter_map(|l| l.strip_prefix(prefix))
        .filter_map(|l| {
            let (name, v) = l.split_once(' ')?;
            Some((name.to_string(), v.trim().parse().ok()?))
        })
        .collect()
}

/// The header's family `prefix` is exactly `names`, each at its index.
fn check(prefix: &str, names: &[&str]) {
    let mut want: Vec<(String, u32)> = names
        .iter()
        .enumerate()
        .map(|(k, n)| (n.to_uppercase().replace('-', "_"), k as u32))
        .collect();
    let mut got = defines(prefix);
    want.sort();
    got.sort();
    assert_eq!(got, want, "{prefix}*");
}

#[test]
fn masking_terms_are_the_catalogue_s() {
    let names: Vec<&str> = MASKINGS.iter().map(|m| m.name).collect();
    check("BRDF_GEOMETRIC_", &names);
}

#[test]
fn sheen_visibilities_are_the_catalogue_s() {
    check("BRDF_SHEEN_VISIBILITY_", SheenVisibility::NAMES);
}

#[test]
fn dielectric_distributions_are_the_catalogue_s() {
    check(
        "BRDF_DIELECTRIC_DISTRIBUTION_",
        DielectricDistribution::NAMES,
    );
}
