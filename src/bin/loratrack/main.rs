//! `loratrack`: the command-line skin over [`loratrack::api`] (reference §9).
//!
//! Every command prints a human summary, or with `--json` exactly one JSON object on stdout.
//! Bad input exits with status 2 and one line `error: ...` on stderr. On a terminal, `simulate`
//! and `swarm` show their progress on stderr while they run, and `sweep` counts its runs (erased
//! when they end).

#[cfg(not(target_arch = "wasm32"))]
mod adr_doc;
#[cfg(not(target_arch = "wasm32"))]
mod commands;
#[cfg(not(target_arch = "wasm32"))]
mod doc_cells;
#[cfg(not(target_arch = "wasm32"))]
mod mission_doc;
#[cfg(not(target_arch = "wasm32"))]
mod payloads_doc;
#[cfg(not(target_arch = "wasm32"))]
mod progress;
#[cfg(not(target_arch = "wasm32"))]
mod real_flight_rates;
#[cfg(not(target_arch = "wasm32"))]
mod real_flight_variants;
#[cfg(not(target_arch = "wasm32"))]
mod reproduction;
#[cfg(not(target_arch = "wasm32"))]
mod senders_doc;
#[cfg(not(target_arch = "wasm32"))]
mod svg;
#[cfg(not(target_arch = "wasm32"))]
mod swarm_doc;
#[cfg(not(target_arch = "wasm32"))]
mod sweep;

#[cfg(not(target_arch = "wasm32"))]
use std::io::Write;

/// Remote UAV tracking over LoRa: airtime, motion models, payload codec and tracking
/// simulation (Mason et al., LoRaWAN + 3D-CTRA).
#[cfg(not(target_arch = "wasm32"))]
#[derive(clap::Parser)]
#[command(name = "loratrack", version, about, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: commands::Command,
}

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    use clap::Parser;
    use std::process::ExitCode;

    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // --help and --version are not errors: printed, they exit 0; a help that cannot be
        // written (a full disk, a closed pipe) is one.
        Err(e) if !e.use_stderr() => {
            let mut out = std::io::stdout().lock();
            return match write!(out, "{}", e.render()).and_then(|()| out.flush()) {
                Ok(()) => ExitCode::SUCCESS,
                Err(w) => fail(&format!("cannot write the output: {w}")),
            };
        }
        // Without a command clap's message is the whole help; one line names the commands.
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            use clap::CommandFactory;
            let names: Vec<String> = Cli::command()
                .get_subcommands()
                .map(|c| c.get_name().to_string())
                .collect();
            return fail(&format!(
                "a command is needed: {} (see --help)",
                names.join(", ")
            ));
        }
        Err(e) => {
            let message = refused_value(&e).or_else(|| unknown_choice(&e));
            return fail(&message.unwrap_or_else(|| one_line(&e.render().to_string())));
        }
    };
    match commands::run(cli.command) {
        Ok(text) => {
            let mut out = std::io::stdout().lock();
            match writeln!(out, "{text}").and_then(|()| out.flush()) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => fail(&format!("cannot write the output: {e}")),
            }
        }
        Err(e) => fail(&in_flags(&e)),
    }
}

/// The core's refusal in the words of the command line: the settings it names by the flags its
/// user typed (`--max-interval must be …`, `set --interval instead of --duty-cycle`), not by
/// their JS keys (`maxInterval`, `dutyCycle`), wherever the CLI has that flag.
#[cfg(not(target_arch = "wasm32"))]
fn in_flags(e: &loratrack::api::ApiError) -> String {
    use clap::CommandFactory;
    use loratrack::options::{long_option, naming_flag, naming_settings};
    let command = Cli::command();
    let flag = |key: &str| {
        let flag = long_option(key);
        let has = command
            .get_subcommands()
            .flat_map(|c| c.get_arguments())
            .any(|a| a.get_long() == flag.strip_prefix("--"));
        has.then_some(flag)
    };
    let message = naming_settings(&e.to_string(), flag);
    match e.setting().and_then(flag) {
        Some(flag) => naming_flag(&message, &flag),
        None => message,
    }
}

/// A value its flag's parser refused, in the parser's words with the flag named first
/// (`--sf must be 7..12, a whole number, got 7.5 (see --help)`: that message already quotes the
/// value, so clap's "invalid value '7.5' for '--sf <SF>'" before it would say it twice). `None`
/// for any other error, or a parser whose message does not start with its setting.
#[cfg(not(target_arch = "wasm32"))]
fn refused_value(e: &clap::Error) -> Option<String> {
    use clap::error::{ContextKind, ContextValue};
    let Some(ContextValue::String(arg)) = e.get(ContextKind::InvalidArg) else {
        return None;
    };
    let flag = arg.split(' ').next()?;
    let reason = std::error::Error::source(e)?.to_string();
    let named = loratrack::options::naming_flag(&reason, flag);
    (named != reason).then(|| format!("{named} (see --help)"))
}

/// A value that is none of its flag's choices, with the choices (clap lists them on a line of
/// their own, which the one line left out): `invalid value 'x' for --fair-use: expected off or
/// ttn (see --help)`.
#[cfg(not(target_arch = "wasm32"))]
fn unknown_choice(e: &clap::Error) -> Option<String> {
    use clap::error::{ContextKind, ContextValue};
    let (
        Some(ContextValue::String(arg)),
        Some(ContextValue::String(value)),
        Some(ContextValue::Strings(choices)),
    ) = (
        e.get(ContextKind::InvalidArg),
        e.get(ContextKind::InvalidValue),
        e.get(ContextKind::ValidValue),
    )
    else {
        return None;
    };
    let (last, rest) = choices.split_last()?;
    let choices = if rest.is_empty() {
        last.clone()
    } else {
        format!("{} or {last}", rest.join(", "))
    };
    let flag = arg.split(' ').next()?;
    Some(format!(
        "invalid value '{value}' for {flag}: expected {choices} (see --help)"
    ))
}

/// clap's message in one line: its first line, without its own `error: ` prefix, and a pointer
/// to --help instead of the usage block. A first line ending in a colon lists what it means on
/// the indented lines after it ("the following required arguments were not provided:" then
/// `--markdown`): those join it, or the message would name nothing.
#[cfg(not(target_arch = "wasm32"))]
fn one_line(rendered: &str) -> String {
    let mut lines = rendered.lines();
    let first = lines.next().unwrap_or("invalid arguments");
    let first = first.strip_prefix("error: ").unwrap_or(first);
    let listed: Vec<&str> = if first.ends_with(':') {
        lines
            .take_while(|l| l.starts_with(' '))
            .map(str::trim)
            .collect()
    } else {
        Vec::new()
    };
    if listed.is_empty() {
        format!("{first} (see --help)")
    } else {
        format!("{first} {} (see --help)", listed.join(", "))
    }
}

/// Prints `error: <msg>` on stderr and returns exit status 2.
#[cfg(not(target_arch = "wasm32"))]
fn fail(msg: &str) -> std::process::ExitCode {
    let _ = writeln!(
        std::io::stderr(),
        "error: {}",
        loratrack::api::clean_message(msg)
    );
    std::process::ExitCode::from(2)
}

/// The CLI is native only; `cargo test --target wasm32-unknown-unknown` builds every binary
/// target, so wasm32 gets this stub.
#[cfg(target_arch = "wasm32")]
fn main() {}
