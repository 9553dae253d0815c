//! The law tables a pair scene, a chain's pairs and a config share, as written: `[physical]`
//! ([`RawPhysical`]), `[base]` ([`RawBase`]) and a mass that may be infinite ([`Mass`]).

use super::Num;
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;
use toml::Spanned;

/// A mass that may be infinite: a number, `inf`, or the string `"inf"`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mass(pub f64);

impl<'de> Deserialize<'de> for Mass {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Mass;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a mass in kg or \"inf\"")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Mass, E> {
                Ok(Mass(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Mass, E> {
                Ok(Mass(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Mass, E> {
                Ok(Mass(v as f64))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Mass, E> {
                if v == "inf" {
                    Ok(Mass(f64::INFINITY))
                } else {
                    Err(E::invalid_value(de::Unexpected::Str(v), &self))
                }
            }
        }
        d.deserialize_any(V)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
/// A `[base]` table (scenes, `[[base]]` entries, chain pairs): base parameters `P*`.
pub struct RawBase {
    pub name: Option<Spanned<String>>,
    pub model: Option<Spanned<String>>,
    #[serde(rename = "B_b")]
    pub b_b: Option<Num>,
    #[serde(rename = "Gamma_b")]
    pub gamma_b: Option<Num>,
    pub kappa: Option<Num>,
    pub sigma_b: Option<Num>,
    pub n: Option<Num>,
    pub p: Option<Num>,
    #[serde(rename = "U_b")]
    pub u_b: Option<Num>,
    #[serde(rename = "T_b")]
    pub t_b: Option<Num>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
/// A `[physical]` table (scenes, chain pairs): the SI law and the mass.
pub struct RawPhysical {
    pub m: Option<Num>,
    pub k: Option<Num>,
    pub c: Option<Num>,
    pub n: Option<Num>,
    pub p: Option<Num>,
    pub alpha: Option<Num>,
    pub beta: Option<Num>,
    pub gamma: Option<Num>,
    #[serde(rename = "A")]
    pub a: Option<Num>,
}
