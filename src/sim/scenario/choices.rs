//! The settings that are a choice rather than a number: which flight, which stations, the seed.

use crate::sim::station::StationModel;
use crate::trajectory::Cornering;
use serde::{Deserialize, Serialize, Serializer};
use std::sync::Arc;

/// The largest seed: 2^53 − 1, so that a seed round-trips through a JavaScript number (and the
/// page's URL) unchanged.
pub const MAX_SEED: u64 = (1 << 53) - 1;

/// A fresh seed in 0..=[`MAX_SEED`] from the operating system's generator (getrandom; Web
/// Crypto in WebAssembly), for runs that should differ, yet can be repeated from the seed they
/// report.
pub fn random_seed() -> Result<u64, String> {
    getrandom::u64()
        .map(|v| v & MAX_SEED)
        .map_err(|e| format!("no random seed available: {e}"))
}

/// A seed as a number, or `"random"` for [`random_seed`].
pub(crate) fn seed_or_random<'de, D: serde::Deserializer<'de>>(d: D) -> Result<u64, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Raw {
        Number(u64),
        Text(String),
    }
    match Raw::deserialize(d).map_err(|_| {
        serde::de::Error::custom("seed must be a whole number 0..2^53-1 or \"random\"")
    })? {
        Raw::Number(n) => Ok(n),
        Raw::Text(t) if t.trim().eq_ignore_ascii_case("random") => {
            random_seed().map_err(serde::de::Error::custom)
        }
        Raw::Text(t) => Err(serde::de::Error::custom(format!(
            "seed must be a whole number 0..2^53-1 or \"random\", got '{}'",
            t.chars().take(20).collect::<String>()
        ))),
    }
}

/// `--synthetic all` or `--synthetic N` (1..=30).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SyntheticChoice {
    /// The whole set of 30 flights.
    All,
    /// One flight, 1..=30.
    One(usize),
}

impl SyntheticChoice {
    fn from_number(n: f64) -> Result<Self, String> {
        if n.fract() == 0.0 && (1.0..=30.0).contains(&n) {
            Ok(SyntheticChoice::One(n as usize))
        } else {
            Err(format!(
                "synthetic must be 'all' or a flight number 1..30, got {}",
                crate::options::as_given(n)
            ))
        }
    }

    /// Parses `all` or a flight number 1..30.
    pub fn parse(text: &str) -> Result<Self, String> {
        let t = text.trim();
        if t.eq_ignore_ascii_case("all") {
            return Ok(SyntheticChoice::All);
        }
        match t.parse::<f64>() {
            Ok(n) => Self::from_number(n),
            Err(_) => Err(format!(
                "synthetic must be 'all' or a flight number 1..30, got '{}'",
                t.chars().take(40).collect::<String>()
            )),
        }
    }
}

impl Serialize for SyntheticChoice {
    /// As it is written: `"all"` or the flight number.
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            SyntheticChoice::All => s.serialize_str("all"),
            SyntheticChoice::One(n) => s.serialize_u64(*n as u64),
        }
    }
}

impl<'de> Deserialize<'de> for SyntheticChoice {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Choice;
        impl serde::de::Visitor<'_> for Choice {
            type Value = SyntheticChoice;
            fn expecting(&self, f: &mut core::fmt::Formatter) -> core::fmt::Result {
                f.write_str("'all' or a flight number 1..30")
            }
            fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<Self::Value, E> {
                SyntheticChoice::parse(s).map_err(E::custom)
            }
            fn visit_f64<E: serde::de::Error>(self, n: f64) -> Result<Self::Value, E> {
                SyntheticChoice::from_number(n).map_err(E::custom)
            }
            fn visit_i64<E: serde::de::Error>(self, n: i64) -> Result<Self::Value, E> {
                self.visit_f64(n as f64)
            }
            fn visit_u64<E: serde::de::Error>(self, n: u64) -> Result<Self::Value, E> {
                self.visit_f64(n as f64)
            }
        }
        d.deserialize_any(Choice)
    }
}

/// `--model`: the stations to compare, as `all` (the paper's three models) or a comma list of
/// `dr`, `ctra-plus`, `3d-ctra` and `imm` (also a JSON array of those names).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModelChoice(Vec<StationModel>);

impl ModelChoice {
    /// The paper's three models.
    pub fn all() -> Self {
        ModelChoice(StationModel::PAPER.to_vec())
    }

    /// One station.
    pub fn one(model: impl Into<StationModel>) -> Self {
        ModelChoice(vec![model.into()])
    }

    /// The stations to run, in the order given, each once.
    pub fn models(&self) -> &[StationModel] {
        &self.0
    }

    /// Whether the mission station is among them: the one reader of a plan beside a logged
    /// flight, of `planTolerance` and `planPace`, and a reader of the vehicle.
    pub fn runs_mission(&self) -> bool {
        self.0.contains(&StationModel::Mission)
    }

    /// Parses `all` or a comma list.
    pub fn parse(text: &str) -> Result<Self, String> {
        if text.trim().is_empty() {
            return Self::from_names([]);
        }
        if text.trim().eq_ignore_ascii_case("all") {
            return Ok(Self::all());
        }
        Self::from_names(text.split(','))
    }

    fn from_names<'a>(names: impl IntoIterator<Item = &'a str>) -> Result<Self, String> {
        let mut models = Vec::new();
        for name in names {
            // `all` inside a list stands for the paper's three (`all,imm`).
            if name.trim().is_empty() {
                return Err(format!(
                    "model: an empty name in the list (name {}, a comma list of them, or all)",
                    StationModel::names()
                ));
            }
            let named: Vec<StationModel> = if name.trim().eq_ignore_ascii_case("all") {
                StationModel::PAPER.to_vec()
            } else {
                vec![name.trim().parse::<StationModel>().map_err(|_| {
                    format!(
                        "unknown model '{}' (expected {}, a comma list of them, or all)",
                        name.trim().chars().take(40).collect::<String>(),
                        StationModel::names()
                    )
                })?]
            };
            for m in named {
                if !models.contains(&m) {
                    models.push(m);
                }
            }
        }
        if models.is_empty() {
            return Err(format!(
                "model: name at least one of {}, or all",
                StationModel::names()
            ));
        }
        Ok(ModelChoice(models))
    }
}

impl Serialize for ModelChoice {
    /// As the comma list it parses from (`"dr,3d-ctra"`), `"all"` for the paper's three.
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if *self == Self::all() {
            return s.serialize_str("all");
        }
        let names: Vec<&str> = self.0.iter().map(|m| m.name()).collect();
        s.serialize_str(&names.join(","))
    }
}

impl core::str::FromStr for ModelChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::parse(s)
    }
}

/// `N` or `random` (the CLI's `--seed`): a whole number 0..2^53 − 1, or a fresh one from
/// [`random_seed`].
pub fn parse_seed(text: &str) -> Result<u64, String> {
    if text.trim().eq_ignore_ascii_case("random") {
        return random_seed();
    }
    // The range is checked with every other setting (`Scenario::validate`).
    match text.trim().parse::<u64>() {
        Ok(n) => Ok(n),
        Err(_) => Err(format!(
            "seed must be a whole number 0..2^53-1 or 'random', got '{}'",
            text.chars().take(20).collect::<String>()
        )),
    }
}

impl Default for ModelChoice {
    fn default() -> Self {
        Self::all()
    }
}

impl<'de> Deserialize<'de> for ModelChoice {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Text(String),
            List(Vec<String>),
        }
        let raw = Raw::deserialize(d).map_err(|_| {
            serde::de::Error::custom(
                "model must be a name, a comma list of names, or an array of names",
            )
        })?;
        match raw {
            Raw::Text(t) => ModelChoice::parse(&t),
            Raw::List(v) => ModelChoice::from_names(v.iter().map(String::as_str)),
        }
        .map_err(serde::de::Error::custom)
    }
}

/// Where the flight comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum TrajectorySource {
    /// CSV text (shared with the settings it came from) and a name.
    Csv(Arc<str>, String),
    /// Synthetic set or one flight of it.
    Synthetic(SyntheticChoice),
    /// A bundled sample by name.
    Sample(String),
    /// A mission plan's text (`x,y,z[,speed[,hold]]`, `.plan` or waypoint list), a name and
    /// the vehicle it is flown as where set (`vehicle`; else as the file says): the drone flies
    /// the plan as [`fly_plan`](crate::fly_plan) flies it, the mission station's best case (no
    /// wind, every leg at its planned speed, every hold as planned).
    Plan(Arc<str>, String, Option<Cornering>),
}
