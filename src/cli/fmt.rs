//! `ronray fmt`: lays scene files out again, keeping what the author wrote
//! (comments, headers, number spellings, omitted defaults); `--canonical`
//! is the old rewrite from the parsed scene, which keeps none of those.
use super::print_out;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// What `ronray fmt` was asked.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct FmtOptions {
    pub check: bool,
    pub stdout: bool,
    /// Write the canonical JSON twin `<scene>.json`.
    pub json: bool,
    pub canonical: bool,
    pub drop_comments: bool,
}

pub(super) fn cmd_fmt(paths: &[PathBuf], o: FmtOptions) -> ExitCode {
    let mut failed = false;
    for p in paths {
        if let Err(e) = fmt_one(p, o, &mut failed) {
            eprintln!("error: {}: {e}", p.display());
            failed = true;
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

fn is_json(p: &Path) -> bool {
    p.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

fn fmt_one(p: &Path, o: FmtOptions, failed: &mut bool) -> Result<(), String> {
    let text = crate::load::source::read_text(p).map_err(|e| format!("cannot read: {e}"))?;
    let (out_text, target) = if o.json || o.canonical {
        let desc = match crate::load::source::parse(p, &text) {
            Ok(d) => d,
            Err(r) => {
                eprint!("{}", r.render(std::io::stderr().is_terminal()));
                return Err("not formatted".into());
            }
        };
        let target = if o.json {
            p.with_extension("json")
        } else {
            p.to_path_buf()
        };
        // The target's own format: `fmt --canonical scene.json` stays JSON.
        let t = if is_json(&target) {
            crate::load::canonical::to_json(&desc)
        } else {
            crate::load::canonical::to_ron(&desc)
        }?;
        let t = crate::load::canonical::keep_number_spellings(&text, &t);
        let keeps_comments = is_json(&target) && !is_json(p);
        if crate::load::canonical::has_comments(&text)
            && !keeps_comments
            && !o.drop_comments
            && !o.stdout
            && !o.check
        {
            return Err(
                "the canonical form drops comments; nothing was changed (pass --drop-comments to \
                        do it anyway, or use `ronray fmt` without --canonical, which keeps them)"
                    .into(),
            );
        }
        (t, target)
    } else {
        let t = crate::syntax::format(&text, is_json(p)).map_err(|e| e.to_string())?;
        (t, p.to_path_buf())
    };
    if o.check {
        let old = if target == p {
            text
        } else {
            std::fs::read_to_string(&target).unwrap_or_default()
        };
        if out_text != old {
            print_out(&unified_diff(&target, &old, &out_text));
            *failed = true;
        }
        return Ok(());
    }
    if o.stdout {
        print_out(&out_text);
        return Ok(());
    }
    if target == p && out_text == text {
        return Ok(());
    }
    write_safely(&target, &out_text).map_err(|e| format!("cannot write {}: {e}", target.display()))?;
    eprintln!("formatted {}", target.display());
    Ok(())
}

/// `diff -u` of the file against its formatted text.
pub(super) fn unified_diff(path: &Path, old: &str, new: &str) -> String {
    let name = path.display().to_string();
    similar::TextDiff::from_lines(old, new)
        .unified_diff()
        .context_radius(3)
        .header(&name, &format!("{name} (formatted)"))
        .to_string()
}

/// Writes `text` over the scene file `target` as an editor saving it would:
/// a symlink is written through to its target (the link stays a link), a
/// file with other hard links is rewritten in place (the links keep sharing
/// it), and any other file is replaced atomically — a new temporary file in
/// its folder (created exclusively under a random name, so nothing planted
/// there is followed) with the file's mode, renamed over it, so a reader
/// sees the old file or the new one. A read-only file is refused: `fmt`
/// does not change what its owner protected.
pub(super) fn write_safely(target: &Path, text: &str) -> std::io::Result<()> {
    let real = crate::files::follow_links(target);
    let meta = std::fs::metadata(&real).ok();
    if let Some(m) = &meta {
        if m.permissions().readonly() {
            return Err(std::io::Error::new(
                std::io::ErrorKind::PermissionDenied,
                "it is read-only; nothing was changed (make it writable to format it)",
            ));
        }
        #[cfg(unix)]
        if std::os::unix::fs::MetadataExt::nlink(m) > 1 {
            let mut f = std::fs::OpenOptions::new()
                .write(true)
                .truncate(true)
                .open(&real)?;
            f.write_all(text.as_bytes())?;
            return f.sync_all();
        }
    }
    let dir = match real.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::Builder::new().prefix(".ronray-fmt").tempfile_in(dir)?;
    tmp.write_all(text.as_bytes())?;
    tmp.as_file().sync_all()?;
    if let Some(m) = meta.filter(|m| m.is_file()) {
        tmp.as_file().set_permissions(m.permissions())?;
    }
    tmp.persist(&real).map_err(|e| e.error)?;
    Ok(())
}
