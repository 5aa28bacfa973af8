//! `ronray fmt`: canonical RON or JSON, never silently dropping comments.
use super::print_out;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

pub(super) fn cmd_fmt(
    paths: &[PathBuf],
    check: bool,
    stdout: bool,
    json: bool,
    drop_comments: bool,
) -> ExitCode {
    use crate::load::format::{has_comments, to_json, to_ron};
    let mut failed = false;
    for p in paths {
        let text = match std::fs::read_to_string(p) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: cannot read {}: {e}", p.display());
                failed = true;
                continue;
            }
        };
        let desc = match crate::load::pipeline::parse(p, &text) {
            Ok(d) => d,
            Err(r) => {
                eprint!("{}", r.render(std::io::stderr().is_terminal()));
                failed = true;
                continue;
            }
        };
        let (out_text, target) = if json {
            (to_json(&desc), p.with_extension("json"))
        } else {
            (to_ron(&desc), p.clone())
        };
        let out_text = match out_text {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: {}: {e}", p.display());
                failed = true;
                continue;
            }
        };
        if check {
            if out_text != text {
                print_out(&format!("{}: not in canonical form\n", p.display()));
                failed = true;
            }
            continue;
        }
        if stdout {
            print_out(&out_text);
            continue;
        }
        if has_comments(&text) && !json && !drop_comments {
            eprintln!(
                "error: {} has comments, which ron cannot keep through formatting; nothing was changed \
                 (pass --drop-comments to format it anyway, or --stdout to see the result)",
                p.display()
            );
            failed = true;
            continue;
        }
        let tmp = target.with_extension("fmt.tmp");
        if let Err(e) = std::fs::write(&tmp, &out_text).and_then(|_| std::fs::rename(&tmp, &target)) {
            eprintln!("error: cannot write {}: {e}", target.display());
            failed = true;
            continue;
        }
        eprintln!("formatted {}", target.display());
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
