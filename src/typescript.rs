//! The TypeScript types of the JS API, generated from the Rust types (ts-rs reads their serde
//! attributes), with the table of numeric options. `www/generated/types.ts` is checked in; this
//! test fails when it drifts from the Rust source. Regenerate with
//! `UPDATE_TYPES=1 cargo test --lib typescript`.

use crate::api::*;
use crate::lora::{
    AdrMode, ChannelAccess, DutyCycleMode, FairUse, LdroMode, Plan, PlanRate, Region,
    ShadowingModel,
};
use crate::metrics::{Boxplot, Draws, Intervals, Summary, WholeFlightError};
use crate::models::ModelKind;
use crate::options::{NumberOption, OPTIONS};
use crate::sim::scenario::*;
use crate::sim::*;
use crate::trajectory::{Cornering, VehicleChoice};

use ts_rs::TS;

const HEADER: &str = "// Generated from the Rust types by `UPDATE_TYPES=1 cargo test --lib typescript` (src/typescript.rs).
// Do not edit: a test fails when this file differs from what the Rust source generates.

/** A motion model: what predict, encode and decode take. */
export type MotionModelName = 'dr' | 'ctra-plus' | '3d-ctra';
";

/// The stations beyond the motion models, by their Rust names.
fn model_name() -> String {
    let beyond: Vec<String> = [StationModel::Imm, StationModel::Mission]
        .iter()
        .map(|m| format!("'{}'", m.name()))
        .collect();
    format!(
        "/** A station: one motion model, the IMM mixture of the three, or the mission-aware station. */
export type ModelName = MotionModelName | {};
/** `all` (the paper's three), one station, a comma list such as `dr,3d-ctra,imm`, or an array. */
export type ModelChoice = ModelName | 'all' | (string & {{}}) | ModelName[];
",
        beyond.join(" | ")
    )
}

fn decls() -> Vec<String> {
    // u64 counts and seeds stay below 2^53: plain numbers in JavaScript.
    let c = ts_rs::Config::new().with_large_int("number");
    vec![
        ModelKind::decl(&c),
        LdroMode::decl(&c),
        Prediction::decl(&c),
        HeadingNoise::decl(&c),
        PlanPace::decl(&c),
        SenderKind::decl(&c),
        ChannelSense::decl(&c),
        DutyCycleMode::decl(&c),
        PayloadChoice::decl(&c),
        AdrMode::decl(&c),
        Region::decl(&c),
        PlanRate::decl(&c),
        Plan::decl(&c),
        FairUse::decl(&c),
        ShadowingModel::decl(&c),
        ChannelAccess::decl(&c),
        SfPlan::decl(&c),
        Schedule::decl(&c),
        GatewaySite::decl(&c),
        FlightSettings::decl(&c),
        StationSettings::decl(&c),
        Sending::decl(&c),
        RadioSettings::decl(&c),
        ChannelSettings::decl(&c),
        NetworkSettings::decl(&c),
        DroneSettings::decl(&c),
        AccessSettings::decl(&c),
        SwarmSettings::decl(&c),
        RunSettings::decl(&c),
        Scenario::decl(&c),
        Summary::decl(&c),
        WholeFlightError::decl(&c),
        Caveats::decl(&c),
        DeliverySpread::decl(&c),
        Intervals::decl(&c),
        VersusLowest::decl(&c),
        Draws::decl(&c),
        Boxplot::decl(&c),
        Boxplots::decl(&c),
        DataRateUse::decl(&c),
        FrameTiming::decl(&c),
        GatewayReport::decl(&c),
        Delivery::decl(&c),
        Energy::decl(&c),
        ModelResult::decl(&c),
        ModelSeries::decl(&c),
        Series::decl(&c),
        Cornering::decl(&c),
        VehicleChoice::decl(&c),
        RunConfig::decl(&c),
        SimReport::decl(&c),
        DroneReport::decl(&c),
        LargestSwarm::decl(&c),
        SwarmSaturation::decl(&c),
        SfLimit::decl(&c),
        SwarmEcho::decl(&c),
        SwarmReport::decl(&c),
        NumberOption::decl(&c),
        AirtimeParams::decl(&c),
        AirtimeReport::decl(&c),
        LinkBudgetParams::decl(&c),
        SfBudget::decl(&c),
        LinkBudgetReport::decl(&c),
        PredictParams::decl(&c),
        PredictReport::decl(&c),
        EncodeParams::decl(&c),
        EncodeReport::decl(&c),
        DecodeParams::decl(&c),
        DecodeReport::decl(&c),
    ]
}

/// The types that flatten others (`#[serde(flatten)]`), each with the ones it flattens, in its
/// field order.
const FLATTENED: &[(&str, &[&str])] = &[
    (
        "Scenario",
        &[
            "FlightSettings",
            "StationSettings",
            "Sending",
            "RadioSettings",
            "ChannelSettings",
            "NetworkSettings",
            "DroneSettings",
            "AccessSettings",
            "SwarmSettings",
            "RunSettings",
        ],
    ),
    ("RunConfig", &["Scenario"]),
    ("SwarmEcho", &["Scenario"]),
    ("ModelResult", &["Delivery"]),
    ("SimReport", &["Delivery"]),
    ("SwarmReport", &["Delivery"]),
];

/// A declaration as ts-rs writes a struct, `type Name = { fields };`, split into its name and
/// its fields (each with its JSDoc, as ts-rs also writes them where the struct is flattened).
fn name_and_fields(decl: &str) -> (&str, Option<&str>) {
    let (head, body) = decl.split_once(" = ").unwrap_or((decl, ""));
    let name = head.trim_start_matches("type ");
    let fields = body.strip_prefix("{ ").and_then(|b| b.strip_suffix("};"));
    (name, fields)
}

/// The declarations with each flattened type's fields replaced by the type itself, as an
/// intersection (`type RunConfig = Scenario & { trajectory: string, … }`): ts-rs writes a
/// flattened struct's fields out in full, which wrote every setting four times (its group,
/// `Scenario`, and the reports' two echoes of it). Panics, failing the test below, when a type
/// no longer holds the fields of one it is listed as flattening.
fn intersect_flattened(decls: Vec<String>) -> Vec<String> {
    let fields: std::collections::BTreeMap<String, String> = decls
        .iter()
        .filter_map(|d| match name_and_fields(d) {
            (name, Some(f)) => Some((name.to_string(), f.to_string())),
            _ => None,
        })
        .collect();
    decls
        .into_iter()
        .map(|decl| {
            let (name, _) = name_and_fields(&decl);
            let Some((_, parts)) = FLATTENED.iter().find(|(n, _)| *n == name) else {
                return decl;
            };
            let mut own = fields[name].clone();
            let mut terms: Vec<String> = Vec::new();
            for part in *parts {
                let theirs = &fields[*part];
                assert!(
                    own.contains(theirs.as_str()),
                    "{name} does not hold the fields of {part}: update FLATTENED in src/typescript.rs"
                );
                own = own.replacen(theirs.as_str(), "", 1);
                terms.push(part.to_string());
            }
            if !own.trim().is_empty() {
                terms.push(format!("{{ {own}}}"));
            }
            format!("type {name} = {};", terms.join(" & "))
        })
        .collect()
}

/// The whole generated file.
fn generated() -> String {
    let mut out = String::from(HEADER);
    out.push_str(&model_name());
    for d in intersect_flattened(decls()) {
        out.push('\n');
        out.push_str("export ");
        out.push_str(&d);
        out.push('\n');
    }
    let options = serde_json::to_string_pretty(&OPTIONS.to_vec()).unwrap_or_default();
    out.push_str(&format!(
        "\n/** Every numeric setting's default and accepted range, as the core validates them (src/options.rs). */\nexport const OPTIONS: NumberOption[] = {options};\n"
    ));
    out.push_str(&choice_defaults());
    let plans: Vec<Plan> = Region::ALL.iter().map(|r| r.plan()).collect();
    let plans = serde_json::to_string_pretty(&plans).unwrap_or_default();
    out.push_str(&format!(
        "\n/** Every regional plan's data rates and limits, as the core checks them (src/lora/region.rs). */\nexport const PLANS: Plan[] = {plans};\n"
    ));
    let stations = StationModel::PAPER
        .into_iter()
        .chain([StationModel::Imm, StationModel::Mission]);
    let bytes: Vec<String> = stations
        .map(|m| format!("  '{}': {}", m.name(), m.payload_bytes()))
        .collect();
    out.push_str(&format!(
        "\n/** Each station's payload, bytes: the model whose state its drone sends (src/sim/station/station_model.rs). */\nexport const PAYLOAD_BYTES: Record<ModelName, number> = {{\n{}\n}};\n",
        bytes.join(",\n")
    ));
    let speeds: Vec<String> = Cornering::ALL
        .iter()
        .map(|&v| {
            format!(
                "  '{}': {}",
                v.name(),
                crate::sim::Bounds::for_vehicle(v).v_max
            )
        })
        .collect();
    out.push_str(&format!(
        "\n/** The top speed, m/s, a bounded or mission station holds each vehicle to (src/sim/station/prediction.rs, `Bounds::for_vehicle`). */\nexport const TOP_SPEEDS: Record<Cornering, number> = {{\n{}\n}};\n",
        speeds.join(",\n")
    ));
    let ranges: Vec<String> = crate::FIELDS
        .iter()
        .map(|f| format!("  {}: \"{}\"", f.name, f.words()))
        .collect();
    out.push_str(&format!(
        "\n/** Each payload field, what it is and the values it sends as themselves, in words; beyond them a value is sent as the range's edge (src/codec/fields.rs, reference §5). */\nexport const PAYLOAD_FIELDS: Record<string, string> = {{\n{}\n}};\n",
        ranges.join(",\n")
    ));
    out.push_str(&format!(
        "\n/** How many of the drone filter's settled standard deviations a manoeuvre field (a, ω, ψ) may reach and still be left out of a lean payload (src/sim/sender/payload.rs). */\nexport const LEAN_SIGNIFICANCE = {};\n",
        crate::sim::LEAN_SIGNIFICANCE
    ));
    out
}

/// The default of every setting that is a choice among names (`prediction`, `sender`,
/// `channelSense`, …): the string-valued keys of [`Scenario::default`], so that the page's form
/// starts where a call that leaves the key out does.
fn choice_defaults() -> String {
    let defaults = serde_json::to_value(Scenario::default()).unwrap_or_default();
    let choices: serde_json::Map<String, serde_json::Value> = defaults
        .as_object()
        .into_iter()
        .flatten()
        .filter(|(_, v)| v.is_string())
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect();
    let keys: Vec<String> = choices.keys().map(|k| format!("'{k}'")).collect();
    let body = serde_json::to_string_pretty(&choices).unwrap_or_default();
    format!(
        "\n/** The default of every setting chosen by name, as `Scenario::default` gives it (src/sim/scenario/mod.rs). */\nexport const CHOICE_DEFAULTS: Pick<Scenario, {}> = {body};\n",
        keys.join(" | ")
    )
}

#[test]
fn the_checked_in_typescript_types_match_the_rust_source() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/www/generated/types.ts");
    let want = generated();
    if std::env::var_os("UPDATE_TYPES").is_some() {
        std::fs::write(path, &want).unwrap();
    }
    let have = std::fs::read_to_string(path).unwrap_or_default();
    assert!(
        have == want,
        "www/generated/types.ts is out of date: run `UPDATE_TYPES=1 cargo test --lib typescript`"
    );
}
