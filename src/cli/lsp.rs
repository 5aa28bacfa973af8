//! `ronray lsp`: the language server, for editors (set-up in `docs/editors.md`).
use std::process::ExitCode;

pub(super) fn cmd_lsp() -> ExitCode {
    match crate::lsp::run() {
        Ok(true) => ExitCode::SUCCESS,
        // `exit` without `shutdown`: the protocol's status 1.
        Ok(false) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("error: ronray lsp: {e}");
            ExitCode::FAILURE
        }
    }
}
