//! `ronray lsp`: the language server, for editors (set-up in `docs/editors.md`).
use std::process::ExitCode;

pub(super) fn cmd_lsp() -> ExitCode {
    match crate::lsp::run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: ronray lsp: {e}");
            ExitCode::FAILURE
        }
    }
}
