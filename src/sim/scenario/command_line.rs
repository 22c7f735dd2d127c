//! The `loratrack` command line that runs a [`Scenario`]: the page's numbers, or a JS caller's,
//! reproduced by the CLI (`docs/reference.md` §9).
//!
//! Written from the settings' own wire form: every key whose value differs from the default
//! becomes its long option ([`long_option`](crate::options::long_option), the key in kebab case:
//! the CLI flattens the same sub-structs, so the names agree; `gateways` is the repeated
//! `--gateway E,N[,H]`, each written by [`GatewaySite::text`] beside its parser). A setting added
//! to a sub-struct therefore appears here without a line of this file, and the CLI's tests read
//! every command back into the settings it came from.

use super::{GatewaySite, Scenario, SimError, DEFAULT_CSV_NAME};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

/// Which command a [`Scenario`] is written out for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CliCommand {
    /// `loratrack simulate`: one drone; the swarm's layout (`drones`, `duration`, `sfPlan`) is
    /// not its to take and is left out.
    #[default]
    Simulate,
    /// `loratrack swarm`.
    Swarm,
}

impl CliCommand {
    /// The subcommand's name.
    pub fn name(self) -> &'static str {
        match self {
            CliCommand::Simulate => "simulate",
            CliCommand::Swarm => "swarm",
        }
    }
}

/// The file name a command gives a CSV flight that came without one.
pub const FLIGHT_FILE: &str = "flight.csv";
/// The file name a command gives a mission plan that came without one.
pub const PLAN_FILE: &str = "plan.csv";

impl Scenario {
    /// The arguments after `loratrack <command>` that run these settings: the flight, then each
    /// setting that differs from its default, in the order the settings are written, which is
    /// `simulate --help`'s (flight, station, sending, radio, channel, network, drone, access,
    /// then for `swarm` its layout, then run).
    ///
    /// A CSV flight or plan, which the settings hold as text, is named by its file name
    /// (`trajectoryName`, `planName`), or [`FLIGHT_FILE`] and [`PLAN_FILE`]: the command runs
    /// where that file is. The settings are not checked: `simulate` does that.
    ///
    /// ```
    /// use loratrack::{CliCommand, Scenario};
    /// let s = Scenario::from_json(r#"{"synthetic": 3, "sf": 9, "prediction": "bounded"}"#).unwrap();
    /// assert_eq!(s.cli_args(CliCommand::Simulate), ["--synthetic", "3", "--prediction", "bounded", "--sf", "9"]);
    /// ```
    pub fn cli_args(&self, command: CliCommand) -> Vec<String> {
        let (values, defaults) = (wire(self), wire(&Scenario::default()));
        let swarm_only = wire(&self.swarm);
        let options = |keys: &[String]| -> Vec<String> {
            keys.iter()
                .filter(|key| command == CliCommand::Swarm || !swarm_only.contains_key(*key))
                .filter_map(|key| Some((key, values.get(key)?)))
                .filter(|(key, value)| defaults.get(*key) != Some(*value))
                .flat_map(|(key, value)| option(key, value))
                .collect()
        };
        let keys = key_order(self);
        // The flight's own keys come first; the files it holds as text sit beside them.
        let (flight, rest) = keys.split_at(key_order(&self.flight).len().min(keys.len()));
        let (trajectory, plan) = self.file_args();
        [trajectory, options(flight), plan, options(rest)].concat()
    }

    /// The whole command as one line a POSIX shell reads, each argument quoted where it needs
    /// to be: `loratrack simulate --synthetic 3 --sf 9`. Refuses a key no setting has, which
    /// the command would silently leave out (the JS API's `commandLine`).
    ///
    /// ```
    /// use loratrack::{CliCommand, Scenario};
    /// let s = Scenario::from_json(r#"{"trajectoryName": "my flight.csv", "model": "dr,imm"}"#).unwrap();
    /// assert_eq!(s.command_line(CliCommand::Simulate).unwrap(), "loratrack simulate --trajectory 'my flight.csv' --model dr,imm");
    /// ```
    pub fn command_line(&self, command: CliCommand) -> Result<String, SimError> {
        self.known_keys()?;
        let mut words = vec!["loratrack".to_string(), command.name().to_string()];
        words.extend(self.cli_args(command).iter().map(|a| shell_word(a)));
        Ok(words.join(" "))
    }

    /// `--trajectory` and `--plan`: the files the settings hold as text, which their wire form
    /// leaves out.
    fn file_args(&self) -> (Vec<String>, Vec<String>) {
        let f = &self.flight;
        let file = |option: &str, given: bool, name: &Option<String>, fallback: &str| {
            let name = match name.as_deref() {
                // A name that starts with a dash would read as an option: `./-x.csv` is that file.
                Some(n) if n.starts_with('-') => format!("./{n}"),
                Some(n) if !n.trim().is_empty() && n != DEFAULT_CSV_NAME => n.to_string(),
                _ => fallback.to_string(),
            };
            match given {
                true => vec![option.to_string(), name],
                false => Vec::new(),
            }
        };
        (
            file(
                "--trajectory",
                f.trajectory.is_some() || f.trajectory_name.is_some(),
                &f.trajectory_name,
                FLIGHT_FILE,
            ),
            file(
                "--plan",
                f.plan.is_some() || f.plan_name.is_some(),
                &f.plan_name,
                PLAN_FILE,
            ),
        )
    }
}

/// The keys of `settings`' wire form in the order it writes them (a JSON map sorts them: its
/// values are read there, exactly, and the order here, from the text).
fn key_order<T: Serialize>(settings: &T) -> Vec<String> {
    struct Keys(Vec<String>);
    impl<'de> serde::Deserialize<'de> for Keys {
        fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
            struct InOrder;
            impl<'de> serde::de::Visitor<'de> for InOrder {
                type Value = Keys;
                fn expecting(&self, f: &mut core::fmt::Formatter) -> core::fmt::Result {
                    f.write_str("an object")
                }
                fn visit_map<A: serde::de::MapAccess<'de>>(
                    self,
                    mut m: A,
                ) -> Result<Keys, A::Error> {
                    let mut keys = Vec::new();
                    while let Some((k, _)) = m.next_entry::<String, serde::de::IgnoredAny>()? {
                        keys.push(k);
                    }
                    Ok(Keys(keys))
                }
            }
            d.deserialize_map(InOrder)
        }
    }
    serde_json::to_string(settings)
        .ok()
        .and_then(|text| serde_json::from_str::<Keys>(&text).ok())
        .map_or_else(Vec::new, |k| k.0)
}

/// The settings' keys and values as the wire has them.
fn wire<T: Serialize>(settings: &T) -> Map<String, Value> {
    match serde_json::to_value(settings) {
        Ok(Value::Object(map)) => map,
        _ => Map::new(),
    }
}

/// The option(s) that give `key` its `value`.
fn option(key: &str, value: &Value) -> Vec<String> {
    match (key, value) {
        ("gateways", Value::Array(sites)) => sites
            .iter()
            .filter_map(|site| GatewaySite::deserialize(site).ok())
            .flat_map(|site| ["--gateway".to_string(), site.text()])
            .collect(),
        // An output flag, not a setting with a value.
        ("series", Value::Bool(on)) => on.then(|| "--series".to_string()).into_iter().collect(),
        (_, Value::Null) => Vec::new(),
        _ => vec![crate::options::long_option(key), text(value)],
    }
}

/// A value as the CLI reads it: a number in the shortest text that reads back to the same bits,
/// a switch as `on` or `off`.
fn text(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        Value::Bool(b) => if *b { "on" } else { "off" }.into(),
        Value::Number(n) => match (n.as_u64(), n.as_i64(), n.as_f64()) {
            (Some(u), _, _) => u.to_string(),
            (_, Some(i), _) => i.to_string(),
            (_, _, Some(f)) => f.to_string(),
            _ => n.to_string(),
        },
        other => other.to_string(),
    }
}

/// `word` as a POSIX shell reads it back: as it is where it holds nothing the shell treats
/// specially, otherwise in single quotes (a quote inside as `'\''`).
fn shell_word(word: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "-_./,:=+@%".contains(c);
    if !word.is_empty() && word.chars().all(plain) {
        return word.to_string();
    }
    format!("'{}'", word.replace('\'', r"'\''"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenario(json: &str) -> Scenario {
        Scenario::from_json(json).unwrap()
    }

    #[test]
    fn the_defaults_need_no_option_but_the_flight() {
        assert_eq!(
            scenario(r#"{"synthetic": "all"}"#)
                .command_line(CliCommand::Simulate)
                .unwrap(),
            "loratrack simulate --synthetic all"
        );
        assert_eq!(
            Scenario::default().command_line(CliCommand::Swarm).unwrap(),
            "loratrack swarm"
        );
    }

    #[test]
    fn numbers_are_written_as_they_read_back() {
        let s = scenario(
            r#"{"sample": "canberra", "distance": 2500.0, "txPower": -3, "q": 0.07, "dutyCycle": 0.001}"#,
        );
        let args = s.cli_args(CliCommand::Simulate);
        assert_eq!(
            args,
            [
                "--sample",
                "canberra",
                "--duty-cycle",
                "0.001",
                "--tx-power",
                "-3",
                "--distance",
                "2500",
                "--q",
                "0.07"
            ]
        );
        let q: f64 = args[args.len() - 1].parse().unwrap();
        assert_eq!(q.to_bits(), 0.07f64.to_bits());
    }

    #[test]
    fn gateways_are_repeated_and_switches_read_on_or_off() {
        let s = scenario(
            r#"{"synthetic": 1, "gateways": [{"east": -500, "north": 0}, {"east": 10, "north": 20.5, "height": 30}], "capture": false, "series": true}"#,
        );
        assert_eq!(
            s.command_line(CliCommand::Simulate).unwrap(),
            "loratrack simulate --synthetic 1 --gateway -500,0 --gateway 10,20.5,30 --capture off --series"
        );
    }

    #[test]
    fn the_swarm_layout_goes_to_swarm_only() {
        let s = scenario(r#"{"drones": 50, "sfPlan": "fixed"}"#);
        assert_eq!(
            s.command_line(CliCommand::Simulate).unwrap(),
            "loratrack simulate"
        );
        assert_eq!(
            s.command_line(CliCommand::Swarm).unwrap(),
            "loratrack swarm --drones 50 --sf-plan fixed"
        );
    }

    #[test]
    fn a_key_no_setting_has_is_refused_not_left_out() {
        let e = scenario(r#"{"spreadingFactor": 9}"#).command_line(CliCommand::Simulate);
        assert!(e
            .unwrap_err()
            .to_string()
            .contains("unknown setting 'spreadingFactor'"));
    }

    #[test]
    fn files_are_named_by_their_names_or_a_stand_in_and_quoted_for_the_shell() {
        let s = scenario(
            r#"{"trajectoryName": "Pat's flight.csv", "plan": "0,0,10", "model": "mission"}"#,
        );
        assert_eq!(
            s.command_line(CliCommand::Simulate).unwrap(),
            r"loratrack simulate --trajectory 'Pat'\''s flight.csv' --plan plan.csv --model mission"
        );
        let named = scenario(r#"{"trajectoryName": "flight.csv"}"#);
        assert_eq!(
            named.cli_args(CliCommand::Simulate),
            ["--trajectory", "flight.csv"]
        );
        let sample =
            scenario(r#"{"sample": "canberra", "planName": "route.plan", "model": "mission"}"#);
        assert_eq!(
            sample.command_line(CliCommand::Simulate).unwrap(),
            "loratrack simulate --sample canberra --plan route.plan --model mission"
        );
        let dashed = scenario(r#"{"trajectoryName": "-x.csv"}"#);
        assert_eq!(
            dashed.cli_args(CliCommand::Simulate),
            ["--trajectory", "./-x.csv"]
        );
        let unnamed =
            scenario(r#"{"trajectory": "t,x,y,z\n0,0,0,0", "trajectoryName": "uploaded CSV"}"#);
        assert_eq!(
            unnamed.cli_args(CliCommand::Simulate),
            ["--trajectory", "flight.csv"]
        );
    }
}
