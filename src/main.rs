use clap::Parser;

fn main() -> std::process::ExitCode {
    ronray::cli::run(ronray::cli::Cli::parse())
}
