//! Every numeric setting's default and limits, declared once.
//!
//! The validation of [`Scenario`](crate::sim::Scenario) and of the link budget, the CLI's defaults
//! and help (`loratrack simulate --help`), the WebAssembly `limits()` export and the page's form
//! (min, max, step and help of each field, `OPTIONS` in `www/generated/types.ts`), and the
//! captions that list settings changed from their defaults (`listed_when_changed`) all read this table, so a
//! limit cannot differ between them. Sources of the defaults: `docs/reference.md` §"Defaults".

use serde::Serialize;

/// One numeric setting: its JSON key, what users call it, its unit, default and accepted range.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct NumberOption {
    /// The key in JSON and JS (camelCase); the CLI's long option is its kebab-case form.
    pub key: &'static str,
    /// The name the page's form shows.
    pub label: &'static str,
    /// Unit, as shown after a value (`""` for none).
    pub unit: &'static str,
    /// Default value.
    pub default: f64,
    /// Smallest accepted value.
    pub min: f64,
    /// Largest accepted value.
    pub max: f64,
    /// Whether `min` itself is refused (a value must be above it).
    pub above_min: bool,
    /// Whole numbers only.
    pub integer: bool,
    /// The only values accepted, when not empty.
    pub values: &'static [f64],
    /// One sentence: what it is and why these limits.
    pub help: &'static str,
    /// Whether a run's caption lists it with its value when it differs from its default (the
    /// CLI's `settings:` line, the page's download and results captions): the settings that no
    /// other part of a caption words, so that two runs differing only in it are not captioned alike.
    pub listed_when_changed: bool,
}

impl NumberOption {
    const fn new(
        key: &'static str,
        label: &'static str,
        unit: &'static str,
        default: f64,
        min: f64,
        max: f64,
        help: &'static str,
    ) -> Self {
        NumberOption {
            key,
            label,
            unit,
            default,
            min,
            max,
            above_min: false,
            integer: false,
            values: &[],
            help,
            listed_when_changed: false,
        }
    }

    const fn whole(self) -> Self {
        NumberOption {
            integer: true,
            ..self
        }
    }

    const fn above(self) -> Self {
        NumberOption {
            above_min: true,
            ..self
        }
    }

    const fn only(self, values: &'static [f64]) -> Self {
        NumberOption { values, ..self }
    }

    const fn listed(self) -> Self {
        NumberOption {
            listed_when_changed: true,
            ..self
        }
    }

    /// Whether `v` is accepted.
    pub fn accepts(&self, v: f64) -> bool {
        let in_range = if self.above_min {
            v > self.min && v <= self.max
        } else {
            (self.min..=self.max).contains(&v)
        };
        v.is_finite()
            && in_range
            && (!self.integer || v.fract() == 0.0)
            && (self.values.is_empty() || self.values.contains(&v))
    }

    /// What is accepted, in words: `"7..12"`, `"0..100000 m"`, `"125, 250 or 500 kHz"`,
    /// `"in (0, 1000]"`.
    pub fn range_text(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        if !self.values.is_empty() {
            let v: Vec<String> = self.values.iter().map(|x| format!("{x}")).collect();
            let (last, rest) = v
                .split_last()
                .map_or(("", &[][..]), |(l, r)| (l.as_str(), r));
            return format!("{} or {last}{unit}", rest.join(", "));
        }
        if self.above_min {
            return format!("in ({}, {}]{unit}", self.min, self.max);
        }
        let whole = if self.integer { ", a whole number" } else { "" };
        format!("{}..{}{unit}{whole}", self.min, self.max)
    }

    /// The CLI help line: the sentence and the range (clap adds the default, from the same
    /// table).
    pub fn cli_help(&self) -> String {
        format!("{} Accepted: {}.", self.help, self.range_text())
    }

    /// `Ok(v)` when accepted, otherwise the error naming the key, the value and the range.
    pub fn check(&'static self, v: f64) -> Result<f64, OutOfRange> {
        if self.accepts(v) {
            Ok(v)
        } else {
            Err(OutOfRange {
                option: self,
                value: v,
            })
        }
    }
}

/// A value outside its [`NumberOption`]'s range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutOfRange {
    /// The setting.
    pub option: &'static NumberOption,
    /// The value given.
    pub value: f64,
}

impl core::fmt::Display for OutOfRange {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "{} must be {}, got {}",
            self.option.key,
            self.option.range_text(),
            as_given(self.value)
        )
    }
}

impl std::error::Error for OutOfRange {}

// --- radio -------------------------------------------------------------------------------------

/// Spreading factor (paper §IV-A: SF7 by default).
pub const SF: NumberOption = NumberOption::new(
    "sf",
    "Spreading factor",
    "",
    7.0,
    7.0,
    12.0,
    "Spreading factor; with ADR, the one the drone starts at.",
)
.whole();
/// Bandwidth, kHz (paper: 250 kHz).
pub const BW: NumberOption = NumberOption::new(
    "bw",
    "Bandwidth",
    "kHz",
    250.0,
    125.0,
    500.0,
    "LoRa bandwidth.",
)
.only(&[125.0, 250.0, 500.0]);
/// Coding rate index n of 4/(4+n) (LoRaWAN uplinks: 4/5).
pub const CR: NumberOption = NumberOption::new(
    "cr",
    "Coding rate",
    "",
    1.0,
    1.0,
    4.0,
    "Coding rate n of 4/(4+n).",
)
.whole()
.listed();
/// MAC overhead per packet, bytes (LoRaWAN: 13; the paper's Table II: 0).
pub const OVERHEAD: NumberOption = NumberOption::new(
    "overhead",
    "LoRaWAN overhead",
    "bytes",
    13.0,
    0.0,
    255.0,
    "MAC overhead added to each payload: 13 for LoRaWAN, 0 as in the paper's Table II.",
)
.whole();
/// Duty-cycle limit as a fraction (EU868 868.0–868.6 MHz: 1 %; per sub-band, so 2 % for a device
/// alternating two 1 % sub-bands, reference §6.1).
pub const DUTY_CYCLE: NumberOption = NumberOption::new(
    "dutyCycle",
    "Duty cycle",
    "",
    0.01,
    1e-4,
    1.0,
    "Duty-cycle limit as a fraction: 0.01, EU868's default channels; 0.02, two 1 % sub-bands alternated (The Things Network's eight channels); 0.0001 is ten times below EU868's strictest sub-band.",
);
/// Transmit power, dBm (EU868's 14 dBm ERP).
pub const TX_POWER: NumberOption = NumberOption::new(
    "txPower",
    "Tx power",
    "dBm",
    14.0,
    -30.0,
    30.0,
    "Drone transmit power.",
)
.listed();

// --- channel -----------------------------------------------------------------------------------

/// Horizontal distance to the default gateway, m (paper: 1 km).
pub const DISTANCE: NumberOption = NumberOption::new(
    "distance",
    "Distance",
    "m",
    1000.0,
    0.0,
    100_000.0,
    "simulate: horizontal distance from the flight's first point to the gateway (placed east of it) when no gateway is given; swarm: every drone's starting distance from the centre.",
);
/// Path-loss exponent (ns-3 `lorawan` examples: 3.76).
pub const PATH_LOSS_EXPONENT: NumberOption = NumberOption::new(
    "pathLossExponent",
    "Path-loss exponent",
    "",
    3.76,
    1.5,
    6.0,
    "Exponent of the log-distance path loss: free space 2, obstructed paths up to 6.",
)
.listed();
/// Log-normal shadowing standard deviation, dB.
pub const SHADOWING: NumberOption = NumberOption::new(
    "shadowing",
    "Shadowing sigma",
    "dB",
    4.0,
    0.0,
    20.0,
    "Standard deviation of log-normal shadowing (0 turns it off).",
)
.listed();
/// Gateway antenna height, m (default of every gateway not given a height).
pub const GATEWAY_HEIGHT: NumberOption = NumberOption::new(
    "gatewayHeight",
    "Gateway height",
    "m",
    15.0,
    0.0,
    1000.0,
    "Antenna height of every gateway not given its own.",
)
.listed();
/// A gateway's east or north coordinate, m.
pub const GATEWAY_COORDINATE: NumberOption = NumberOption::new(
    "gateway",
    "Gateway coordinate",
    "m",
    0.0,
    -100_000.0,
    100_000.0,
    "A gateway's east or north coordinate in the scenario's frame.",
);
/// How many gateways a scenario may have.
pub const GATEWAYS: NumberOption = NumberOption::new(
    "gateways",
    "Gateways",
    "",
    1.0,
    1.0,
    16.0,
    "Number of gateways.",
)
.whole();

// --- drone and station -------------------------------------------------------------------------

/// Drone sensor and filter rate, Hz (paper: 10 Hz).
pub const SENSOR_RATE: NumberOption = NumberOption::new(
    "sensorRate",
    "Sensor rate",
    "Hz",
    10.0,
    0.1,
    1000.0,
    "Drone sensor and filter rate.",
)
.listed();
/// Station prediction step T, s (paper: 0.1 s).
pub const STEP: NumberOption = NumberOption::new(
    "step",
    "Prediction step T",
    "s",
    0.1,
    0.001,
    10.0,
    "Station prediction step T.",
)
.listed();
/// Tilt-rate decay per station step (paper: 0.9).
pub const ETA: NumberOption = NumberOption::new(
    "eta",
    "Tilt decay eta",
    "",
    0.9,
    0.0,
    1.0,
    "3D-CTRA's tilt-rate decay per station step.",
)
.listed();
/// Process noise scale q of Q = q·I (paper: 0.1).
pub const Q: NumberOption = NumberOption::new(
    "q",
    "Process noise q",
    "",
    0.1,
    0.0,
    1000.0,
    "Process noise q of Q = q I per second.",
)
.above()
.listed();
/// How far from its plan a packet may place the drone for the mission station to follow the
/// plan, m (reference §16).
pub const PLAN_TOLERANCE: NumberOption = NumberOption::new(
    "planTolerance",
    "Off-plan distance",
    "m",
    10.0,
    0.1,
    1000.0,
    "Mission station: a packet farther than this from the plan hands over to bounded 3D-CTRA.",
)
.listed();

// --- sending -----------------------------------------------------------------------------------

/// Error-triggered threshold, m.
pub const THRESHOLD: NumberOption = NumberOption::new(
    "threshold",
    "Threshold",
    "m",
    2.0,
    0.0,
    10_000.0,
    "Error-triggered sending: the drift between the mirrored station and the drone's own estimate that triggers a packet.",
);
/// Error-triggered heartbeat, s.
pub const MAX_INTERVAL: NumberOption = NumberOption::new(
    "maxInterval",
    "Heartbeat",
    "s",
    10.0,
    0.0,
    3600.0,
    "Error-triggered sending: the longest silence (at least every drone's duty-cycle interval).",
)
.above();
/// Budget rule capacity, packets.
pub const BURST: NumberOption = NumberOption::new(
    "burst",
    "Burst",
    "packets",
    10.0,
    1.0,
    3600.0,
    "Budget duty-cycle rule: the most packets' airtime the credit holds (1 is per-packet).",
)
.whole();

// --- network -----------------------------------------------------------------------------------

/// LoRaWAN ADR's device margin, dB (Semtech 10; The Things Stack 15).
pub const ADR_MARGIN: NumberOption = NumberOption::new(
    "adrMargin",
    "ADR margin",
    "dB",
    10.0,
    0.0,
    30.0,
    "LoRaWAN ADR: the device margin.",
);
/// LoRaWAN ADR's history, uplinks (Semtech and The Things Stack: 20).
pub const ADR_HISTORY: NumberOption = NumberOption::new(
    "adrHistory",
    "ADR history",
    "uplinks",
    20.0,
    1.0,
    100.0,
    "LoRaWAN ADR: the uplinks whose best SNR decides.",
)
.whole();
/// Uplink channels: 1, or the regional plan's (EU868 and IN865 3, US915 and AU915 8, AS923 2;
/// the default).
pub const CHANNELS: NumberOption = NumberOption::new(
    "channels",
    "Channels",
    "",
    3.0,
    1.0,
    8.0,
    "Uplink channels: 1, or the plan's default channels with a random one per packet (EU868 868.1/868.3/868.5 MHz, under one 1 % duty cycle; US915 and AU915 8 of a sub-band; AS923 2; IN865 3), the default. swarm only.",
)
.only(&[1.0, 2.0, 3.0, 8.0]);

// --- channel access ----------------------------------------------------------------------------

/// The longest random delay before each uplink, s (LoRaMac-node's periodic-uplink example:
/// `APP_TX_DUTYCYCLE_RND` = 1 s). The default is a swarm's; `simulate` keeps the paper's exact
/// timing (0) unless given.
pub const JITTER: NumberOption = NumberOption::new(
    "jitter",
    "Jitter",
    "s",
    1.0,
    0.0,
    60.0,
    "The longest random delay a drone adds before each uplink (swarm default 1 s as LoRaMac-node's example; simulate default 0, the paper's timing).",
)
.listed();
/// The largest clock error of a drone, ppm (crystals are specified at ±10–20 ppm). The default
/// is a swarm's; `simulate` keeps a perfect clock (0) unless given.
pub const CLOCK_DRIFT: NumberOption = NumberOption::new(
    "clockDrift",
    "Clock drift",
    "ppm",
    20.0,
    0.0,
    1000.0,
    "Each drone's clock runs up to this fast or slow, drawn per drone (swarm default 20 ppm, a common crystal; simulate default 0).",
)
.listed();

/// The sending interval where the plan has no duty cycle (US915, AU915, IN865), s: once a
/// second, the rate at which drone Remote ID broadcasts (ASTM F3411-22a: at least 1 Hz).
pub const INTERVAL: NumberOption = NumberOption::new(
    "interval",
    "Interval",
    "s",
    1.0,
    0.05,
    3600.0,
    "Where the plan has no duty cycle (US915, AU915, IN865): seconds from one uplink's start to the next (default 1 s, Remote ID's rate); at least the time on air.",
);

// --- swarm and run -----------------------------------------------------------------------------

/// Drones in a swarm.
pub const DRONES: NumberOption = NumberOption::new(
    "drones",
    "Drones",
    "",
    12.0,
    1.0,
    500.0,
    "Number of drones sharing the gateways.",
)
.whole();
/// Seconds of flight per swarm drone.
pub const DURATION: NumberOption = NumberOption::new(
    "duration",
    "Duration",
    "s",
    600.0,
    10.0,
    3600.0,
    "Seconds of flight per drone when the drones fly chained synthetic flights (refused with a chosen flight, flown whole).",
);
/// Seed of every random draw.
pub const SEED: NumberOption = NumberOption::new(
    "seed",
    "Seed",
    "",
    1.0,
    0.0,
    9_007_199_254_740_991.0,
    "Seed of every random draw; the largest is 2^53 - 1, the largest integer a JavaScript number holds exactly.",
)
.whole();
/// Seeds a simulation repeats with (`seed`, `seed + 1`, …): the runs behind each statistic's
/// 95 % interval.
pub const SEEDS: NumberOption = NumberOption::new(
    "seeds",
    "Seeds",
    "",
    1.0,
    1.0,
    100.0,
    "Repeat the simulation with this many seeds (seed, seed + 1, ...): the statistics pool every run and each gets a 95 % interval.",
)
.whole();

/// The most drone and station filter steps one run may take per model, summed over its flights,
/// seeds and drones: twice what the page's largest setting needs (the whole 44-minute set with 100 Hz
/// sensors and T = 0.01 s is 528 000), about a second of work per model natively.
pub const MAX_FILTER_STEPS: u64 = 1_000_000;

/// The most filter steps a swarm may take, summed over its drones and flights: its largest
/// chained setting (500 drones × 3600 s × (10 Hz sensors + 1 / 0.1 s station steps)).
pub const MAX_SWARM_FILTER_STEPS: u64 = 36_000_000;

/// Every option, in the order the CLI help and the page list them.
pub const OPTIONS: &[&NumberOption] = &[
    &SF,
    &BW,
    &CR,
    &OVERHEAD,
    &DUTY_CYCLE,
    &TX_POWER,
    &DISTANCE,
    &PATH_LOSS_EXPONENT,
    &SHADOWING,
    &GATEWAY_HEIGHT,
    &GATEWAY_COORDINATE,
    &GATEWAYS,
    &SENSOR_RATE,
    &STEP,
    &ETA,
    &Q,
    &PLAN_TOLERANCE,
    &THRESHOLD,
    &MAX_INTERVAL,
    &BURST,
    &ADR_MARGIN,
    &ADR_HISTORY,
    &CHANNELS,
    &INTERVAL,
    &JITTER,
    &CLOCK_DRIFT,
    &DRONES,
    &DURATION,
    &SEED,
    &SEEDS,
];

/// The option with JSON key `key`.
pub fn option(key: &str) -> Option<&'static NumberOption> {
    OPTIONS.iter().copied().find(|o| o.key == key)
}

/// The command line's long option for the setting `key`: its kebab-case form, since the CLI
/// flattens the same settings structs as the JSON (reference §9).
///
/// ```
/// use loratrack::options::long_option;
/// assert_eq!(long_option("maxInterval"), "--max-interval");
/// assert_eq!(long_option("sf"), "--sf");
/// ```
pub fn long_option(key: &str) -> String {
    let mut out = String::with_capacity(key.len() + 6);
    out.push_str("--");
    for c in key.chars() {
        if c.is_ascii_uppercase() {
            out.push('-');
            out.push(c.to_ascii_lowercase());
        } else {
            out.push(c);
        }
    }
    out
}

/// `message`, a refusal that starts by naming its setting as JS and JSON do, with that name
/// replaced by `flag` where `flag` is that setting's long option: what a CLI user typed, not a
/// key they never saw. Any other message comes back as it is.
///
/// ```
/// use loratrack::options::naming_flag;
/// let m = "maxInterval must be in (0, 3600] s, got 0";
/// assert_eq!(naming_flag(m, "--max-interval"), "--max-interval must be in (0, 3600] s, got 0");
/// assert_eq!(naming_flag(m, "--interval"), m);
/// ```
pub fn naming_flag(message: &str, flag: &str) -> String {
    match message.split_once(' ') {
        Some((key, rest)) if rest.starts_with("must ") && long_option(key) == flag => {
            format!("{flag} {rest}")
        }
        _ => message.to_string(),
    }
}

/// `message` with the settings it names in the middle of a sentence, which the core marks as
/// `` `key` `` ("set `interval` instead of `dutyCycle`"), named as each skin's users know them:
/// `name` gives the words for a key (the CLI: its flag), `None` keeps the key (the JS API); the
/// marks go either way. Backticks around anything but one word (a command, `` `loratrack
/// simulate --help` ``) stay as they are.
///
/// ```
/// use loratrack::options::{long_option, naming_settings};
/// let m = "US915 has no duty cycle: set `interval` instead of `dutyCycle`";
/// assert_eq!(naming_settings(m, |_| None), "US915 has no duty cycle: set interval instead of dutyCycle");
/// assert_eq!(
///     naming_settings(m, |key| Some(long_option(key))),
///     "US915 has no duty cycle: set --interval instead of --duty-cycle"
/// );
/// ```
pub fn naming_settings(message: &str, name: impl Fn(&str) -> Option<String>) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(open) = rest.find('`') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        let Some(close) = after.find('`') else {
            out.push_str(&rest[open..]);
            return out;
        };
        let inner = &after[..close];
        if !inner.is_empty() && inner.chars().all(|c| c.is_ascii_alphabetic()) {
            out.push_str(&name(inner).unwrap_or_else(|| inner.to_string()));
        } else {
            out.push_str(&rest[open..open + close + 2]);
        }
        rest = &after[close + 1..];
    }
    out.push_str(rest);
    out
}

/// A refused value as its error message writes it: a whole number as one (`got 300`, where the
/// user typed 300, not `got 300.0`), anything else as Rust reads it back (`0.5`, `1e300`, `NaN`).
///
/// ```
/// use loratrack::options::as_given;
/// assert_eq!(as_given(300.0), "300");
/// assert_eq!(as_given(-5.0), "-5");
/// assert_eq!(as_given(0.25), "0.25");
/// assert_eq!(as_given(1e300), "1e300");
/// ```
pub fn as_given(value: f64) -> String {
    // Below 2^53 every whole f64 is an exact integer; above it Debug's exponent form is shorter.
    if value.fract() == 0.0 && value.abs() < 9_007_199_254_740_992.0 {
        format!("{}", value as i64)
    } else {
        format!("{value:?}")
    }
}

/// A command-line parser for the whole-number setting `key`: any number is read, so that `7.5`,
/// `-1` or text are refused in the words the core uses for a value out of range (the option's
/// range where it is one of [`OPTIONS`]), not as the integer type's parse error ("invalid digit
/// found in string"). Values the type holds pass on to be checked with every other setting.
#[cfg(cli)]
pub fn whole<T>(
    key: &'static str,
) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static
where
    T: TryFrom<i64> + Clone + Send + Sync + 'static,
{
    let read = number(key);
    move |text: &str| {
        let v = read(text)?;
        let exact = v.fract() == 0.0 && v.abs() < 9_007_199_254_740_992.0;
        let held = exact.then(|| T::try_from(v as i64).ok()).flatten();
        held.ok_or_else(|| whole_refusal(key, v))
    }
}

/// How the whole-number setting `key` refuses `value`, a number its type cannot hold (a fraction,
/// a negative count): in its range's words where it is one of [`OPTIONS`] (as [`OutOfRange`]),
/// otherwise what it takes. The CLI's parsers and the JS API's reading of a parameter object both
/// word it so.
pub fn whole_refusal(key: &str, value: f64) -> String {
    match option(key) {
        Some(option) => OutOfRange { option, value }.to_string(),
        None if value < 0.0 => format!(
            "{key} must be a whole number, not negative, got {}",
            as_given(value)
        ),
        None => format!("{key} must be a whole number, got {}", as_given(value)),
    }
}

/// A command-line parser for the setting `key` in any number form Rust reads (`1e3`, `-5`, `0.25`):
/// text is refused with the setting's name and range ("distance must be a number (0..100000 m),
/// got '1km'"), not as a float parse error; the range itself is checked with every other setting.
#[cfg(cli)]
pub fn number(
    key: &'static str,
) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |text: &str| {
        text.trim().parse().map_err(|_| {
            let quoted: String = text.chars().take(20).collect();
            let range = option(key).map_or(String::new(), |o| format!(" ({})", o.range_text()));
            format!(
                "{key} must be a number{range}, got '{}'",
                quoted.escape_debug()
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_refusal_takes_a_flags_name_only_where_it_starts_with_that_flags_setting() {
        assert_eq!(
            naming_flag("sensorRate must be 0.1..1000 Hz, got 0", "--sensor-rate"),
            "--sensor-rate must be 0.1..1000 Hz, got 0"
        );
        // `--distances` lists distances; a refused one is named as the setting it is.
        let one = "distance must be a number (0..100000 m), got ''";
        assert_eq!(naming_flag(one, "--distances"), one);
        // A message that names its setting otherwise than "<key> must …" stays as it is.
        let adr = "adr starts at an EU868 data rate (SF7..12 at 125 kHz or SF7 at 250 kHz)";
        assert_eq!(naming_flag(adr, "--adr"), adr);
        assert_eq!(naming_flag("", "--sf"), "");
    }

    #[test]
    fn only_one_word_in_backticks_is_a_setting_to_name() {
        let flags = |key: &str| Some(long_option(key));
        // A command in backticks is quoted text, not a setting.
        let unknown = "unknown setting 'x' (see `loratrack simulate --help` or limits())";
        assert_eq!(naming_settings(unknown, flags), unknown);
        // A key the skin has no name for keeps its own, without the marks.
        assert_eq!(
            naming_settings("`drones` and `sfPlan` are swarm settings", |k| {
                (k == "sfPlan").then(|| long_option(k))
            }),
            "drones and --sf-plan are swarm settings"
        );
        // An unclosed backtick is left as it is.
        assert_eq!(naming_settings("set `dutyCycle", flags), "set `dutyCycle");
    }

    #[cfg(cli)]
    #[test]
    fn number_options_refuse_text_with_their_name_and_range() {
        assert_eq!(number("distance")("1e3"), Ok(1000.0));
        assert_eq!(
            number("distance")("1km"),
            Err("distance must be a number (0..100000 m), got '1km'".into())
        );
        assert_eq!(
            number("dt")("x"),
            Err("dt must be a number, got 'x'".into())
        );
    }

    #[cfg(cli)]
    #[test]
    fn whole_number_options_refuse_fractions_negatives_and_text_in_their_own_words() {
        assert_eq!(whole::<i64>("sf")("9"), Ok(9));
        assert_eq!(
            whole::<i64>("sf")("7.5"),
            Err("sf must be 7..12, a whole number, got 7.5".into())
        );
        assert_eq!(
            whole::<usize>("overhead")("-1").unwrap_err(),
            OutOfRange {
                option: &OVERHEAD,
                value: -1.0
            }
            .to_string()
        );
        assert_eq!(
            whole::<u32>("seeds")("many"),
            Err("seeds must be a number (1..100, a whole number), got 'many'".into())
        );
        // A setting outside the options table (the airtime command's payload) says what it wants.
        assert_eq!(
            whole::<usize>("payload")("-3"),
            Err("payload must be a whole number, not negative, got -3".into())
        );
        assert_eq!(
            whole::<usize>("payload")("2.5"),
            Err("payload must be a whole number, got 2.5".into())
        );
    }

    #[test]
    fn every_default_is_accepted_and_keys_are_unique() {
        for o in OPTIONS {
            assert!(o.accepts(o.default), "{} default {}", o.key, o.default);
            assert_eq!(
                OPTIONS.iter().filter(|p| p.key == o.key).count(),
                1,
                "{}",
                o.key
            );
        }
    }

    #[test]
    fn limits_refuse_what_is_outside_and_say_why() {
        assert!(SF.check(13.0).is_err());
        assert!(SF.check(7.5).is_err());
        assert!(BW.check(300.0).is_err());
        assert!(Q.check(0.0).is_err());
        assert!(Q.check(1e-9).is_ok());
        assert!(DISTANCE.check(f64::NAN).is_err());
        assert_eq!(
            BW.check(300.0).unwrap_err().to_string(),
            "bw must be 125, 250 or 500 kHz, got 300"
        );
        assert_eq!(
            SF.check(13.0).unwrap_err().to_string(),
            "sf must be 7..12, a whole number, got 13"
        );
    }
}
