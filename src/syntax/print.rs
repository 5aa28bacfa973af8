//! Lays a [`Document`] out again: four-space indentation, one space after
//! `:` and `,`, a group on one line when the author wrote it so (or it is a
//! short vector) and it fits in [`WIDTH`] columns, otherwise one entry per
//! line with a trailing comma (none in JSON). Comments stay where they were
//! relative to their entries; blank lines between entries are kept (at most
//! one).

use super::tree::{Comment, Document, Entry, Group, Piece};

/// Preferred line width, in characters.
pub const WIDTH: usize = 110;
/// A group of at most this many bare values is a short vector, joined on
/// one line whenever it fits.
const SHORT_VECTOR: usize = 4;

/// The text of `doc` laid out again (JSON rules when `json`: no trailing commas).
pub fn print(doc: &Document, json: bool) -> String {
    let mut p = Printer {
        out: String::new(),
        json,
    };
    for (i, item) in doc.items.iter().enumerate() {
        if i > 0 {
            p.out.push('\n');
            if item.blank_before {
                p.out.push('\n');
            }
        }
        for c in &item.leading {
            p.out += &c.text;
            p.out.push('\n');
        }
        p.pieces(&item.pieces, 0);
        for c in &item.trailing {
            p.trailing(c);
        }
        // A leading-comment-only item printed its own newline.
        if item.pieces.is_empty() && item.trailing.is_empty() && p.out.ends_with('\n') {
            p.out.pop();
        }
    }
    p.out.push('\n');
    p.out
}

struct Printer {
    out: String,
    json: bool,
}

impl Printer {
    fn column(&self) -> usize {
        let line = self.out.rsplit('\n').next().unwrap_or("");
        line.chars().count()
    }

    fn space(&mut self) {
        if !self.out.ends_with([' ', '\n']) && !self.out.is_empty() {
            self.out.push(' ');
        }
    }

    fn newline(&mut self, indent: usize) {
        while self.out.ends_with(' ') {
            self.out.pop();
        }
        self.out.push('\n');
        self.out.extend(std::iter::repeat_n(' ', indent));
    }

    fn comment(&mut self, c: &Comment) {
        self.out += &c.text;
    }

    /// A comment after an entry on its line, as far from it as written.
    fn trailing(&mut self, c: &Comment) {
        while self.out.ends_with(' ') {
            self.out.pop();
        }
        self.out.extend(std::iter::repeat_n(' ', c.gap.max(1)));
        self.out += &c.text;
    }

    /// The pieces of one entry, starting at the current column.
    fn pieces(&mut self, pieces: &[Piece], indent: usize) {
        let mut prev: Option<&Piece> = None;
        for p in pieces {
            match (prev, p) {
                (None, _) | (_, Piece::Colon(_)) => {}
                (Some(Piece::Comment(c)), _) if c.ends_line => self.newline(indent + 4),
                (Some(Piece::Atom(a)), Piece::Group(_)) if is_ident(&a.text) => {}
                _ => self.space(),
            }
            match p {
                Piece::Atom(a) => self.out += &a.text,
                Piece::Colon(_) => self.out.push(':'),
                Piece::Comment(c) => self.comment(c),
                Piece::Group(g) => self.group(g, indent),
            }
            prev = Some(p);
        }
    }

    fn group(&mut self, g: &Group, indent: usize) {
        if let Some(flat) = flat_group(g, self.json, 4 * WIDTH.saturating_sub(self.column()))
            && (g.one_line || is_short_vector(g))
            && self.column() + flat.chars().count() < WIDTH
        // room for a comma
        {
            self.out += &flat;
            return;
        }
        if self.hugged(g, indent) {
            return;
        }
        self.out.push(g.open);
        for c in &g.open_trailing {
            self.space();
            self.comment(c);
        }
        let inner = indent + 4;
        let last = g.entries.len().saturating_sub(1);
        for (i, e) in g.entries.iter().enumerate() {
            if e.blank_before && i > 0 {
                self.newline(0);
            }
            for c in &e.leading {
                if c.blank_before && i > 0 && !e.blank_before {
                    self.newline(0);
                }
                self.newline(inner);
                self.comment(c);
            }
            self.newline(inner);
            self.pieces(&e.pieces, inner);
            if !self.json || i < last {
                self.out.push(',');
            }
            for c in &e.trailing {
                self.trailing(c);
            }
        }
        for (i, c) in g.closing.iter().enumerate() {
            if c.blank_before && (i > 0 || !g.entries.is_empty()) {
                self.newline(0);
            }
            self.newline(inner);
            self.comment(c);
        }
        self.newline(indent);
        self.out.push(g.close);
    }
}

impl Printer {
    /// `Name(a: 1, of: [` … `])`: the author's hugging layout, kept when
    /// every entry but the last fits on the opening line.
    fn hugged(&mut self, g: &Group, indent: usize) -> bool {
        let Some((last, rest)) = g.entries.split_last() else {
            return false;
        };
        if !g.hug || g.open == '{' || !g.open_trailing.is_empty() || !g.closing.is_empty() {
            return false;
        }
        let Some(Piece::Group(inner)) = last.pieces.last() else {
            return false;
        };
        let head = Entry {
            pieces: last.pieces[..last.pieces.len() - 1].to_vec(),
            ..Entry::default()
        };
        let Some(mut line) = rest
            .iter()
            .chain([&head])
            .map(|e| flat_entry(e, self.json, 4 * WIDTH))
            .collect::<Option<Vec<_>>>()
            .map(|v| v.join(", "))
        else {
            return false;
        };
        if !last.leading.is_empty()
            || !last.trailing.is_empty()
            || self.column() + line.chars().count() + 2 > WIDTH
        {
            return false;
        }
        if matches!(head.pieces.last(), Some(Piece::Colon(_))) {
            line.push(' ');
        }
        self.out.push(g.open);
        self.out += &line;
        self.group(inner, indent);
        self.out.push(g.close);
        true
    }
}

fn is_ident(a: &str) -> bool {
    a.starts_with(|c: char| c.is_alphabetic() || c == '_')
}

fn is_short_vector(g: &Group) -> bool {
    g.entries.len() <= SHORT_VECTOR
        && g.entries
            .iter()
            .all(|e| matches!(e.pieces.as_slice(), [Piece::Atom(_)]))
}

/// `g` on one line, or `None` when a comment forbids it or it is longer
/// than `budget` bytes (four per character of room left on the line: then
/// it cannot fit). The budget keeps the work per group within a line's
/// width: building every group's whole flat text made formatting quadratic
/// in the nesting depth (10,000 deep took over 20 s).
fn flat_group(g: &Group, json: bool, budget: usize) -> Option<String> {
    if !g.open_trailing.is_empty() || !g.closing.is_empty() {
        return None;
    }
    let mut parts = Vec::with_capacity(g.entries.len());
    let mut used = 0;
    for e in &g.entries {
        let part = flat_entry(e, json, budget.checked_sub(used)?)?;
        used += part.len() + 2;
        parts.push(part);
    }
    let body = parts.join(", ");
    // `(x,)` keeps its comma: in RON a one-element tuple may need it.
    let comma = if !json && g.open == '(' && g.entries.len() == 1 && g.entries[0].comma {
        ","
    } else {
        ""
    };
    Some(match g.open {
        '{' if !body.is_empty() => format!("{{ {body} }}"),
        _ => format!("{}{body}{comma}{}", g.open, g.close),
    })
}

/// `e` on one line, within `budget` bytes (see [`flat_group`]).
fn flat_entry(e: &Entry, json: bool, budget: usize) -> Option<String> {
    if !e.leading.is_empty() || !e.trailing.is_empty() {
        return None;
    }
    let mut s = String::new();
    let mut prev: Option<&Piece> = None;
    for p in &e.pieces {
        match (prev, p) {
            (None, _) | (_, Piece::Colon(_)) => {}
            (Some(Piece::Atom(a)), Piece::Group(_)) if is_ident(&a.text) => {}
            _ => s.push(' '),
        }
        match p {
            Piece::Atom(a) => s += &a.text,
            Piece::Colon(_) => s.push(':'),
            Piece::Comment(c) if !c.ends_line => s += &c.text,
            Piece::Comment(_) => return None,
            Piece::Group(g) => s += &flat_group(g, json, budget.checked_sub(s.len())?)?,
        }
        if s.len() > budget {
            return None;
        }
        prev = Some(p);
    }
    Some(s)
}
