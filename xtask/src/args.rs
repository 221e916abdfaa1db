//! Whole numbers typed on the command line: one reading for every size flag, so that a
//! number too large for its integer type is told apart from text that is not a number (the
//! caller then names its limit, not only "too large").

use std::fmt::Display;
use std::str::FromStr;

/// `s` as a whole number: `Ok(Some(n))`; `Ok(None)` when `s` is all ASCII digits but too
/// large for `T`; `Err(why)` when it is not a whole number.
pub fn whole<T: FromStr>(s: &str) -> Result<Option<T>, String>
where
    T::Err: Display,
{
    match s.parse::<T>() {
        Ok(n) => Ok(Some(n)),
        Err(_) if !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()) => Ok(None),
        Err(e) => Err(e.to_string()),
    }
}
