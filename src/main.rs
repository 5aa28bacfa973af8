use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    // Before anything else: a binary built for a newer CPU than this one
    // (`target-cpu=native` elsewhere) says so instead of dying on an
    // illegal instruction (see `ronray::cpu`).
    let missing = ronray::cpu::missing_features();
    if !missing.is_empty() {
        eprintln!(
            "error: this ronray was compiled for CPU features this machine lacks: {}\n  \
             = help: build it on this machine (`cargo build --release`), or for every machine it must run on \
             (`RUSTFLAGS=\"-C target-cpu=x86-64-v3\" cargo build --release`; the oldest CPUs: `x86-64`)",
            missing.join(", ")
        );
        return ExitCode::FAILURE;
    }
    // A nesting limit that is not a number is refused here, once, rather
    // than read as the default by every parser (see `ronray::syntax::nesting`).
    let nesting = ronray::syntax::nesting::NESTING_VAR;
    if let Err(e) = ronray::syntax::nesting::parse_limit(std::env::var(nesting).ok().as_deref()) {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    ronray::cli::run(ronray::cli::Cli::parse())
}
