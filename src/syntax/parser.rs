//! Builds the [`super::tree`] from tokens: comments attached by line,
//! entries split at commas, groups at brackets. Groups nest through one
//! function, `Parser::group`, which recurses once per bracket; so both
//! entry points first count the depth of the tokens they were given
//! ([`super::nesting::within`], a loop) and build nothing from text nested
//! past the limit.

use super::fault::Fault;
use super::lex::{Kind, LexError, Recovered, Token, tokenize, tokenize_recovering};
use super::nesting;
use super::tree::{Atom, Comment, Document, Entry, Group, Piece, Read};

/// Parses `src` into a [`Document`]; an unbalanced bracket, a comma
/// outside any bracket or nesting past [`nesting::limit`] is an error at
/// that byte.
pub fn parse(src: &str) -> Result<Document, LexError> {
    let toks = tokenize(src)?;
    nesting::within(&toks, nesting::limit()).map_err(|deep| Fault::TooDeep(deep).lex_error())?;
    Parser::new(src, toks, true).document()
}

/// Reads `src` as far as it goes, whatever it holds (see [`Read`]); text
/// nested past [`nesting::limit`] reads as an empty tree with that one
/// fault.
pub fn read(src: &str) -> Read {
    let Recovered { tokens, unclosed } = tokenize_recovering(src);
    if let Err(deep) = nesting::within(&tokens, nesting::limit()) {
        return Read {
            doc: Document::default(),
            faults: vec![Fault::TooDeep(deep)],
            unclosed,
        };
    }
    let mut p = Parser::new(src, tokens, false);
    let doc = p.document().unwrap_or_default();
    Read {
        doc,
        faults: p.faults,
        unclosed,
    }
}

struct Parser<'a> {
    src: &'a str,
    toks: Vec<Token>,
    pos: usize,
    /// Stop at the first fault (the formatter) or record it and read on.
    strict: bool,
    faults: Vec<Fault>,
    /// The brackets open around the current token, outermost first.
    open: Vec<(char, usize)>,
}

impl<'a> Parser<'a> {
    fn new(src: &'a str, toks: Vec<Token>, strict: bool) -> Self {
        Parser {
            src,
            toks,
            pos: 0,
            strict,
            faults: Vec::new(),
            open: Vec::new(),
        }
    }

    /// Stops at `f` when strict, else records it.
    fn fault(&mut self, f: Fault) -> Result<(), LexError> {
        if self.strict {
            return Err(f.lex_error());
        }
        self.faults.push(f);
        Ok(())
    }

    fn atom(&self, t: &Token) -> Piece {
        Piece::Atom(Atom {
            text: t.text(self.src).to_string(),
            span: t.span.clone(),
        })
    }

    /// End of the last token read.
    fn end_of_prev(&self) -> usize {
        self.pos
            .checked_sub(1)
            .and_then(|p| self.toks.get(p))
            .map_or(0, |t| t.span.end)
    }

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
                        pieces: vec![self.atom(&t)],
                        ..Entry::default()
                    });
                }
                Kind::Close(_) | Kind::Comma | Kind::Colon => {
                    self.fault(Fault::Stray {
                        kind: t.kind,
                        at: t.span.start,
                    })?;
                    self.pos += 1;
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
                    pieces.push(self.atom(&t));
                    if !matches!(self.peek().map(|t| t.kind), Some(Kind::Open(_))) {
                        return Ok(pieces);
                    }
                }
                _ => return Ok(pieces),
            }
        }
    }

    /// The group opening at the current token. Groups nest through here
    /// alone: `self.open.len()` is the depth, at most the limit `parse` and
    /// `read` checked.
    fn group(&mut self, open: char) -> Result<Group, LexError> {
        let open_at = self.toks[self.pos].span.start;
        self.open.push((open, open_at));
        self.pos += 1;
        let g = self.group_body(open, open_at);
        self.open.pop();
        g
    }

    fn group_body(&mut self, open: char, open_at: usize) -> Result<Group, LexError> {
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
            span: open_at..open_at + 1,
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
                self.fault(Fault::NeverClosed { open, at: open_at })?;
                g.span = open_at..self.end_of_prev();
                g.closing = leading;
                return Ok(g);
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
                // A mismatched bracket is a fault; read on, it closes this group.
                Kind::Close(c) => {
                    if c != close {
                        let open = self.open.clone();
                        self.fault(Fault::Mismatch {
                            close: c,
                            at: t.span.start,
                            open,
                        })?;
                    }
                    self.pos += 1;
                    g.span = open_at..t.span.end;
                    g.hug = first_on_open_line
                        && !g.one_line
                        && t.newlines_before == 0
                        && matches!(g.entries.last(), Some(e) if !e.comma && matches!(e.pieces.last(), Some(Piece::Group(_))));
                    g.closing = leading;
                    return Ok(g);
                }
                // `value // why` + newline + `,`: the comment trails the value.
                Kind::Comma if g.entries.last().is_some_and(|e| !e.comma) => {
                    self.pos += 1;
                    if let Some(e) = g.entries.last_mut() {
                        e.comma = true;
                        e.trailing.append(&mut leading);
                    }
                }
                Kind::Comma => {
                    self.fault(Fault::LeadingComma { at: t.span.start })?;
                    self.pos += 1;
                }
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
        while let Some(t) = self.peek().cloned() {
            seen = match (&seen, t.kind) {
                (_, Kind::LineComment | Kind::BlockComment | Kind::Comma | Kind::Close(_)) => seen,
                (Seen::Nothing, Kind::Word | Kind::Str | Kind::Attribute) => Seen::Word,
                (Seen::Key, Kind::Word | Kind::Str) => Seen::KeyWord,
                (Seen::Nothing | Seen::Word | Seen::Key | Seen::KeyWord, Kind::Open(_)) => Seen::Value,
                (Seen::Word, Kind::Colon) => Seen::Key,
                // Read on: a colon that starts an entry is its value.
                (Seen::Nothing, Kind::Colon) => {
                    self.fault(Fault::StrayColon { at: t.span.start })?;
                    Seen::Value
                }
                // Read on: the token begins the next entry.
                _ => {
                    self.fault(Fault::MissingComma { at: t.span.start })?;
                    e.missing_comma = Some(t.span.clone());
                    break;
                }
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
                    e.pieces.push(Piece::Colon(t.span.clone()));
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
                    e.pieces.push(self.atom(&t));
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
