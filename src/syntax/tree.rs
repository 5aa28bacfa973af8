//! The token stream grouped into brackets and entries, with every comment
//! attached to the entry it belongs to: a comment on the line of an entry
//! (after its comma) trails it, a comment on its own line leads the next
//! one (or closes the group). Nothing is interpreted: atoms keep their
//! spelling, so laying the tree out again cannot change what a scene means.
//!
//! Every atom and group keeps its byte span, so the same tree serves the
//! formatter ([`super::parser::parse`], which refuses any [`Fault`]) and
//! the loader ([`super::parser::read`], which records the faults and reads
//! on: [`super::spans`] and [`super::outline`] are views of it). The types
//! are here; `parser.rs` builds them.

pub use super::fault::Fault;
use super::lex::Unclosed;
use std::ops::Range;

/// A comment, with what its placement needs.
#[derive(Clone, Debug, PartialEq)]
pub struct Comment {
    /// The comment as written, trailing spaces removed.
    pub text: String,
    /// A blank line came before it.
    pub blank_before: bool,
    /// It must be followed by a line break (`//`, or a `/* */` spanning
    /// lines).
    pub ends_line: bool,
    /// Spaces between it and the token before it on its line (kept for a
    /// trailing comment, so aligned comments stay aligned); 0 on its own line.
    pub gap: usize,
}

/// A word or string, as written, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct Atom {
    /// The text as written (quotes included).
    pub text: String,
    /// Its bytes in the source.
    pub span: Range<usize>,
}

/// A part of an entry, in source order.
#[derive(Clone, Debug, PartialEq)]
pub enum Piece {
    /// A word or string, as written.
    Atom(Atom),
    /// `:` between a key and its value, and where.
    Colon(Range<usize>),
    /// A bracketed group.
    Group(Group),
    /// A comment in the middle of an entry (`key: /* why */ value`).
    Comment(Comment),
}

/// One element of a group: `key: value`, `value`, `"name": Variant(...)`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Entry {
    /// A blank line came before it.
    pub blank_before: bool,
    /// Comments on their own lines before it.
    pub leading: Vec<Comment>,
    /// The key, colon, name and value, with comments between them.
    pub pieces: Vec<Piece>,
    /// Comments after it on its last line.
    pub trailing: Vec<Comment>,
    /// A comma followed it in the source.
    pub comma: bool,
    /// Where a comma was missing after it (only in [`read`]'s trees): the
    /// token that began the next entry.
    pub missing_comma: Option<Range<usize>>,
}

impl Entry {
    /// The pieces that are not comments.
    fn significant(&self) -> impl Iterator<Item = &Piece> {
        self.pieces.iter().filter(|p| !matches!(p, Piece::Comment(_)))
    }

    /// The key of `key: value`: an atom followed by `:`.
    pub fn key(&self) -> Option<&Atom> {
        let mut it = self.significant();
        match (it.next(), it.next()) {
            (Some(Piece::Atom(a)), Some(Piece::Colon(_))) => Some(a),
            _ => None,
        }
    }

    /// The value's pieces (after `key:` when there is one), comments left
    /// out.
    pub fn value(&self) -> Vec<&Piece> {
        let skip = if self.key().is_some() { 2 } else { 0 };
        self.significant().skip(skip).collect()
    }

    /// The bytes of the value, from its first piece to its last; an empty
    /// range after the colon when nothing follows it.
    pub fn value_span(&self) -> Option<Range<usize>> {
        let v = self.value();
        match (v.first(), v.last()) {
            (Some(a), Some(b)) => Some(a.span().start..b.span().end),
            _ => self.significant().nth(1).map(|c| c.span().end..c.span().end),
        }
    }
}

impl Piece {
    /// Its bytes in the source (a comment's are not kept: it is empty).
    pub fn span(&self) -> Range<usize> {
        match self {
            Piece::Atom(a) => a.span.clone(),
            Piece::Colon(r) => r.clone(),
            Piece::Group(g) => g.span.clone(),
            Piece::Comment(_) => 0..0,
        }
    }
}

/// A bracketed group and its entries.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// The opening bracket.
    pub open: char,
    /// The closing bracket.
    pub close: char,
    /// Comments on the line of the opening bracket.
    pub open_trailing: Vec<Comment>,
    /// The entries, in order.
    pub entries: Vec<Entry>,
    /// Comments on their own lines before the closing bracket.
    pub closing: Vec<Comment>,
    /// The source had no line break between the brackets.
    pub one_line: bool,
    /// Written hugging its last entry: `of: [` on the opening line, the
    /// entries of the last value below, `])` closing both on one line.
    pub hug: bool,
    /// From the opening bracket to the closing one (to the last token read
    /// when it is never closed).
    pub span: Range<usize>,
}

/// A tree read from text that may be broken: what could be read, the faults
/// met on the way, and the literal that swallowed the end, if any.
#[derive(Clone, Debug, Default)]
pub struct Read {
    /// What could be read.
    pub doc: Document,
    /// The faults, in the order of the text.
    pub faults: Vec<Fault>,
    /// A string or comment running to the end of the text.
    pub unclosed: Option<Unclosed>,
}

impl Read {
    /// The top-level values, past comments and `#![…]` attributes (a
    /// scene file holds one).
    pub fn values(&self) -> impl Iterator<Item = &Entry> {
        self.doc.items.iter().filter(|e| {
            !e.pieces.is_empty()
                && !matches!(e.pieces.as_slice(), [Piece::Atom(a)] if a.text.starts_with('#'))
        })
    }
}

/// A whole file: comments, attributes and the value, each on its own lines.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Document {
    /// Top-level items: comments, `#![...]` attributes and the value.
    pub items: Vec<Entry>,
}
