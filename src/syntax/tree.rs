//! The token stream grouped into brackets and entries, with every comment
//! attached to the entry it belongs to: a comment on the line of an entry
//! (after its comma) trails it, a comment on its own line leads the next
//! one (or closes the group). Nothing is interpreted: atoms keep their
//! spelling, so laying the tree out again cannot change what a scene means.

use super::lex::{Kind, LexError, Token, tokenize};

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

/// A part of an entry, in source order.
#[derive(Clone, Debug, PartialEq)]
pub enum Piece {
    /// A word or string, as written.
    Atom(String),
    /// `:` between a key and its value.
    Colon,
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
}

/// A whole file: comments, attributes and the value, each on its own lines.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Document {
    /// Top-level items: comments, `#![...]` attributes and the value.
    pub items: Vec<Entry>,
}

/// Parses `src` into a [`Document`]; an unbalanced bracket or a comma
/// outside any bracket is an error at that byte.
pub fn parse(src: &str) -> Result<Document, LexError> {
    let toks = tokenize(src)?;
    let mut p = Parser { src, toks, pos: 0 };
    p.document()
}

struct Parser<'a> {
    src: &'a str,
    toks: Vec<Token>,
    pos: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&Token> {
        self.toks.get(self.pos)
    }

    fn comment(&self, t: &Token) -> Comment {
        let text = t.text(self.src);
        let prev_end = self.toks[..self.pos]
            .iter()
            .rev()
            .find(|p| p.span.end <= t.span.start);
        let gap = match prev_end {
            Some(p) if t.newlines_before == 0 => self.src[p.span.end..t.span.start].chars().count(),
            _ => 0,
        };
        Comment {
            text: text.trim_end().to_string(),
            blank_before: t.newlines_before >= 2,
            ends_line: t.kind == Kind::LineComment || text.contains('\n'),
            gap,
        }
    }

    fn error(&self, at: usize, message: &str) -> LexError {
        LexError {
            at,
            message: message.into(),
        }
    }

    fn document(&mut self) -> Result<Document, LexError> {
        let mut doc = Document::default();
        while let Some(t) = self.peek().cloned() {
            match t.kind {
                Kind::LineComment | Kind::BlockComment => {
                    let c = self.comment(&t);
                    self.pos += 1;
                    match doc.items.last_mut() {
                        Some(last) if t.newlines_before == 0 => last.trailing.push(c),
                        _ => doc.items.push(Entry {
                            blank_before: c.blank_before,
                            leading: vec![c],
                            ..Entry::default()
                        }),
                    }
                }
                Kind::Attribute => {
                    self.pos += 1;
                    doc.items.push(Entry {
                        blank_before: t.newlines_before >= 2,
                        pieces: vec![Piece::Atom(t.text(self.src).to_string())],
                        ..Entry::default()
                    });
                }
                Kind::Close(_) | Kind::Comma | Kind::Colon => {
                    return Err(self.error(t.span.start, "unexpected token outside any bracket"));
                }
                _ => {
                    let blank_before = t.newlines_before >= 2;
                    let pieces = self.value_pieces()?;
                    doc.items.push(Entry {
                        blank_before,
                        pieces,
                        ..Entry::default()
                    });
                }
            }
        }
        Ok(doc)
    }

    /// A top-level value: `Name(...)`, `(...)`, `{...}`, a word or a string.
    fn value_pieces(&mut self) -> Result<Vec<Piece>, LexError> {
        let mut pieces = Vec::new();
        loop {
            let Some(t) = self.peek().cloned() else {
                return Ok(pieces);
            };
            match t.kind {
                Kind::Open(c) => {
                    pieces.push(Piece::Group(self.group(c)?));
                    return Ok(pieces);
                }
                Kind::Word | Kind::Str if pieces.is_empty() => {
                    self.pos += 1;
                    pieces.push(Piece::Atom(t.text(self.src).to_string()));
                    if !matches!(self.peek().map(|t| t.kind), Some(Kind::Open(_))) {
                        return Ok(pieces);
                    }
                }
                _ => return Ok(pieces),
            }
        }
    }

    /// The group opening at the current token.
    fn group(&mut self, open: char) -> Result<Group, LexError> {
        let open_at = self.toks[self.pos].span.start;
        self.pos += 1;
        let close = match open {
            '(' => ')',
            '[' => ']',
            _ => '}',
        };
        let mut g = Group {
            open,
            close,
            open_trailing: Vec::new(),
            entries: Vec::new(),
            closing: Vec::new(),
            one_line: true,
            hug: false,
        };
        let first_on_open_line = self
            .peek()
            .is_some_and(|t| t.newlines_before == 0 && !t.is_comment());
        // Still on the line of the opening bracket or of the last comma.
        let mut trailing_line = true;
        let mut leading: Vec<Comment> = Vec::new();
        let mut blank_before = false;
        loop {
            let Some(t) = self.peek().cloned() else {
                return Err(self.error(open_at, &format!("`{open}` is never closed")));
            };
            if t.newlines_before > 0 {
                g.one_line = false;
                trailing_line = false;
            }
            match t.kind {
                Kind::LineComment | Kind::BlockComment => {
                    self.pos += 1;
                    let c = self.comment(&t);
                    if trailing_line {
                        match g.entries.last_mut() {
                            Some(e) => e.trailing.push(c),
                            None => g.open_trailing.push(c),
                        }
                    } else {
                        if leading.is_empty() {
                            blank_before = c.blank_before;
                        }
                        leading.push(c);
                    }
                }
                Kind::Close(c) if c == close => {
                    self.pos += 1;
                    g.hug = first_on_open_line
                        && !g.one_line
                        && t.newlines_before == 0
                        && matches!(g.entries.last(), Some(e) if !e.comma && matches!(e.pieces.last(), Some(Piece::Group(_))));
                    g.closing = leading;
                    return Ok(g);
                }
                Kind::Close(c) => {
                    return Err(self.error(t.span.start, &format!("`{c}` closes `{open}`")));
                }
                // `value // why` + newline + `,`: the comment trails the value.
                Kind::Comma if g.entries.last().is_some_and(|e| !e.comma) => {
                    self.pos += 1;
                    if let Some(e) = g.entries.last_mut() {
                        e.comma = true;
                        e.trailing.append(&mut leading);
                    }
                }
                Kind::Comma => return Err(self.error(t.span.start, "a comma with nothing before it")),
                _ => {
                    if leading.is_empty() {
                        blank_before = t.newlines_before >= 2;
                    }
                    let mut e = Entry {
                        blank_before,
                        leading: std::mem::take(&mut leading),
                        ..Entry::default()
                    };
                    self.entry(&mut e, &mut g.one_line)?;
                    if let Some(t) = self.peek()
                        && t.kind == Kind::Comma
                    {
                        g.one_line &= t.newlines_before == 0;
                        self.pos += 1;
                        e.comma = true;
                    }
                    trailing_line = true;
                    g.entries.push(e);
                }
            }
        }
    }

    /// Whether only comments stand between here and the next comma or
    /// closing bracket.
    fn only_comments_before_end(&self) -> bool {
        self.toks[self.pos..]
            .iter()
            .find(|t| !t.is_comment())
            .is_none_or(|t| matches!(t.kind, Kind::Comma | Kind::Close(_)))
    }

    /// The pieces of one entry, up to (not including) its comma or the
    /// closing bracket. Comments after the last piece trail the entry.
    fn entry(&mut self, e: &mut Entry, one_line: &mut bool) -> Result<(), LexError> {
        // What the entry holds so far: nothing, a word (a key, a variant or
        // a value), `key:`, `key: word`, or a complete value.
        #[derive(PartialEq)]
        enum Seen {
            Nothing,
            Word,
            Key,
            KeyWord,
            Value,
        }
        let mut seen = Seen::Nothing;
        let missing_comma = |p: &Self, at: usize| p.error(at, "expected `,` between two values");
        while let Some(t) = self.peek().cloned() {
            seen = match (&seen, t.kind) {
                (_, Kind::LineComment | Kind::BlockComment | Kind::Comma | Kind::Close(_)) => seen,
                (Seen::Nothing, Kind::Word | Kind::Str | Kind::Attribute) => Seen::Word,
                (Seen::Key, Kind::Word | Kind::Str) => Seen::KeyWord,
                (Seen::Nothing | Seen::Word | Seen::Key | Seen::KeyWord, Kind::Open(_)) => Seen::Value,
                (Seen::Word, Kind::Colon) => Seen::Key,
                _ => return Err(missing_comma(self, t.span.start)),
            };
            if t.newlines_before > 0 {
                *one_line = false;
            }
            match t.kind {
                Kind::Comma | Kind::Close(_) => break,
                Kind::Open(c) => {
                    let g = self.group(c)?;
                    *one_line &= g.one_line;
                    e.pieces.push(Piece::Group(g));
                }
                Kind::Colon => {
                    self.pos += 1;
                    e.pieces.push(Piece::Colon);
                }
                Kind::LineComment | Kind::BlockComment => {
                    // Comments on their own lines before the comma or the
                    // closing bracket belong to the group, not this entry.
                    if t.newlines_before > 0 && !e.pieces.is_empty() && self.only_comments_before_end() {
                        break;
                    }
                    self.pos += 1;
                    e.pieces.push(Piece::Comment(self.comment(&t)));
                }
                Kind::Word | Kind::Str | Kind::Attribute => {
                    self.pos += 1;
                    e.pieces.push(Piece::Atom(t.text(self.src).to_string()));
                }
            }
        }
        while let Some(Piece::Comment(_)) = e.pieces.last() {
            // A comment after the value, on its line: it trails the entry.
            if let Some(Piece::Comment(c)) = e.pieces.pop() {
                e.trailing.insert(0, c);
            }
        }
        Ok(())
    }
}
