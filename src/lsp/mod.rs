//! `ronray lsp`: a language server for scene files over standard input and
//! output (the Language Server Protocol, through `lsp-server`, synchronous).
//!
//! - **Diagnostics** ([`diagnostics`]): the loader's errors and warnings with
//!   their help lines, for the unsaved text, published when a document opens
//!   or changes (after the queue of edits is drained, so a burst of
//!   keystrokes loads once).
//! - **Hover** ([`hover`]): a field's documentation, type, default and range,
//!   from the JSON Schema generated from `desc/` ([`schema`]).
//! - **Completion** ([`completion`]): field names, enum variants, the scene's
//!   material and mesh names.
//! - **Go to definition** ([`definition`]): a material or mesh name to its
//!   entry, an include or a file path to the file.
//!
//! Positions are UTF-16 ([`text`]), the protocol's default.

pub mod completion;
pub mod definition;
pub mod diagnostics;
pub mod hover;
pub mod names;
pub mod schema;
pub mod text;
pub mod transport;

use crate::syntax::lex::tokenize_lenient;
use crate::watch::mesh_cache::MeshCache;
use lsp_server::{Connection, Message, Notification, Request, Response};
use lsp_types::notification::Notification as _;
use lsp_types::request::Request as _;
use lsp_types::{
    CompletionOptions, GotoDefinitionResponse, Hover, HoverContents, HoverProviderCapability, Location,
    MarkupContent, MarkupKind, OneOf, PublishDiagnosticsParams, ServerCapabilities,
    TextDocumentSyncCapability, TextDocumentSyncKind, Uri, notification as note, request as req,
};
use std::collections::{BTreeSet, HashMap};
use std::error::Error;
use std::path::PathBuf;

type Result<T> = std::result::Result<T, Box<dyn Error + Send + Sync>>;

/// An open document: its text as the editor has it.
struct Document {
    path: PathBuf,
    text: String,
    /// Other files its last diagnostics pointed into (included files), to
    /// clear when they are fixed.
    published: BTreeSet<PathBuf>,
}

struct Server {
    conn: Connection,
    docs: HashMap<Uri, Document>,
    /// Documents edited since their diagnostics were last published.
    dirty: BTreeSet<Uri>,
    schema: schema::Schema,
    meshes: MeshCache,
}

/// Serves on standard input and output until the client says `exit`.
/// `Ok(true)` when a `shutdown` request came first: the protocol asks the
/// server to exit with status 0 then, and 1 on an `exit` without one (or
/// when the client goes away without either).
pub fn run() -> Result<bool> {
    let (conn, io) = transport::stdio();
    let caps = ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::FULL)),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(vec!["\"".into(), "(".into(), ",".into(), ":".into()]),
            ..Default::default()
        }),
        definition_provider: Some(OneOf::Left(true)),
        ..Default::default()
    };
    conn.initialize(serde_json::to_value(caps)?)?;
    let mut s = Server::new(conn);
    let shut_down = s.serve()?;
    drop(s);
    io.join()?;
    Ok(shut_down)
}

/// What the `lsp` fuzz target runs: `data` read as a client's framed
/// messages ([`transport::read_message`]) and handled by the server's
/// message loop, with the diagnostics published when the messages run out.
/// Whether every byte was read as a message.
pub fn replay(data: &[u8]) -> bool {
    let (server, client) = Connection::memory();
    let mut input = data;
    let whole = loop {
        match transport::read_message(&mut input) {
            Ok(Some(m)) => {
                if client.sender.send(m).is_err() {
                    break false;
                }
            }
            Ok(None) => break true,
            Err(_) => break false,
        }
    };
    // The server's replies pile up in `_replies` until it returns: once the
    // messages run out, the closed channel ends its loop.
    let Connection {
        sender,
        receiver: _replies,
    } = client;
    drop(sender);
    let _ = Server::new(server).serve();
    whole
}

impl Server {
    fn new(conn: Connection) -> Self {
        Server {
            conn,
            docs: HashMap::new(),
            dirty: BTreeSet::new(),
            schema: schema::Schema::new(),
            meshes: MeshCache::default(),
        }
    }

    /// Answers until `exit` (or the end of input); whether `shutdown` came
    /// first. After `shutdown` requests are refused and notifications other
    /// than `exit` ignored, as the protocol says. (`lsp-server`'s
    /// `handle_shutdown` could not tell `exit` alone from `shutdown` then
    /// `exit`: both ended in status 0.)
    fn serve(&mut self) -> Result<bool> {
        let mut shut_down = false;
        while let Ok(msg) = self.conn.receiver.recv() {
            match msg {
                Message::Request(r) => {
                    let resp = if shut_down {
                        Response::new_err(
                            r.id,
                            lsp_server::ErrorCode::InvalidRequest as i32,
                            "the server is shutting down".into(),
                        )
                    } else if r.method == req::Shutdown::METHOD {
                        shut_down = true;
                        Response::new_ok(r.id, ())
                    } else {
                        self.request(r)
                    };
                    self.conn.sender.send(Message::Response(resp))?;
                }
                Message::Notification(n) if n.method == note::Exit::METHOD => return Ok(shut_down),
                Message::Notification(n) => {
                    if !shut_down {
                        self.notification(n);
                    }
                }
                Message::Response(_) => {}
            }
            if !shut_down && self.conn.receiver.is_empty() {
                self.publish_dirty()?;
            }
        }
        Ok(false)
    }

    fn notification(&mut self, n: Notification) {
        match n.method.as_str() {
            note::DidOpenTextDocument::METHOD => {
                if let Ok(p) = serde_json::from_value::<lsp_types::DidOpenTextDocumentParams>(n.params)
                    && let Some(path) = text::path_of(&p.text_document.uri)
                {
                    let doc = Document {
                        path,
                        text: p.text_document.text,
                        published: BTreeSet::new(),
                    };
                    self.docs.insert(p.text_document.uri.clone(), doc);
                    self.dirty.insert(p.text_document.uri);
                }
            }
            note::DidChangeTextDocument::METHOD => {
                if let Ok(p) = serde_json::from_value::<lsp_types::DidChangeTextDocumentParams>(n.params)
                    && let Some(doc) = self.docs.get_mut(&p.text_document.uri)
                    && let Some(change) = p.content_changes.into_iter().last()
                {
                    doc.text = change.text;
                    self.dirty.insert(p.text_document.uri);
                }
            }
            note::DidCloseTextDocument::METHOD => {
                if let Ok(p) = serde_json::from_value::<lsp_types::DidCloseTextDocumentParams>(n.params) {
                    self.docs.remove(&p.text_document.uri);
                    self.dirty.remove(&p.text_document.uri);
                }
            }
            _ => {}
        }
    }

    fn publish(&self, uri: Uri, diagnostics: Vec<lsp_types::Diagnostic>) -> Result<()> {
        let params = PublishDiagnosticsParams {
            uri,
            diagnostics,
            version: None,
        };
        let n = Notification::new(note::PublishDiagnostics::METHOD.into(), params);
        self.conn.sender.send(Message::Notification(n))?;
        Ok(())
    }

    fn publish_dirty(&mut self) -> Result<()> {
        for uri in std::mem::take(&mut self.dirty) {
            let Some(doc) = self.docs.get(&uri) else {
                continue;
            };
            let by_file = diagnostics::check(&doc.path, &doc.text, &self.meshes);
            let own = doc.path.clone();
            let mut others = BTreeSet::new();
            let stale: Vec<PathBuf> = doc
                .published
                .iter()
                .filter(|p| !by_file.contains_key(*p))
                .cloned()
                .collect();
            for (file, list) in by_file {
                let target = if file == own {
                    Some(uri.clone())
                } else {
                    others.insert(file.clone());
                    text::uri_of(&file)
                };
                if let Some(t) = target {
                    self.publish(t, list)?;
                }
            }
            for file in stale {
                if let Some(t) = text::uri_of(&file) {
                    self.publish(t, Vec::new())?;
                }
            }
            if let Some(doc) = self.docs.get_mut(&uri) {
                doc.published = others;
            }
        }
        Ok(())
    }

    fn request(&mut self, r: Request) -> Response {
        let result = match r.method.as_str() {
            req::HoverRequest::METHOD => self.hover(r.params),
            req::Completion::METHOD => self.completion(r.params),
            req::GotoDefinition::METHOD => self.definition(r.params),
            _ => {
                return Response::new_err(
                    r.id,
                    lsp_server::ErrorCode::MethodNotFound as i32,
                    format!("ronray lsp does not handle `{}`", r.method),
                );
            }
        };
        match result {
            Ok(v) => Response::new_ok(r.id, v),
            Err(e) => Response::new_err(r.id, lsp_server::ErrorCode::InvalidParams as i32, e.to_string()),
        }
    }

    /// The document and byte offset a position request names.
    fn locate(&self, p: &lsp_types::TextDocumentPositionParams) -> Option<(&Document, usize)> {
        let doc = self.docs.get(&p.text_document.uri)?;
        Some((doc, text::offset(&doc.text, p.position)))
    }

    fn hover(&self, params: serde_json::Value) -> Result<serde_json::Value> {
        let p: lsp_types::HoverParams = serde_json::from_value(params)?;
        let Some((doc, off)) = self.locate(&p.text_document_position_params) else {
            return Ok(serde_json::Value::Null);
        };
        let toks = tokenize_lenient(&doc.text);
        let h = hover::hover(&self.schema, &doc.text, &toks, off).map(|(md, span)| Hover {
            contents: HoverContents::Markup(MarkupContent {
                kind: MarkupKind::Markdown,
                value: md,
            }),
            range: Some(text::range(&doc.text, span)),
        });
        Ok(serde_json::to_value(h)?)
    }

    fn completion(&self, params: serde_json::Value) -> Result<serde_json::Value> {
        let p: lsp_types::CompletionParams = serde_json::from_value(params)?;
        let Some((doc, off)) = self.locate(&p.text_document_position) else {
            return Ok(serde_json::Value::Null);
        };
        let toks = tokenize_lenient(&doc.text);
        let json = doc.path.extension().is_some_and(|e| e == "json");
        // Names the included files define.
        let mut extra = Vec::new();
        let base = doc.path.parent().unwrap_or(std::path::Path::new("."));
        for inc in names::includes(&doc.text, &toks, base) {
            if let Ok(t) = crate::load::source::read_text(&inc) {
                let it = tokenize_lenient(&t);
                for map in ["materials", "meshes"] {
                    extra.extend(names::defined(&t, &it, map).into_iter().map(|(n, _)| (map, n)));
                }
            }
        }
        let items = completion::complete(&self.schema, &doc.text, &toks, off, json, &extra);
        Ok(serde_json::to_value(items)?)
    }

    fn definition(&self, params: serde_json::Value) -> Result<serde_json::Value> {
        let p: lsp_types::GotoDefinitionParams = serde_json::from_value(params)?;
        let uri = p.text_document_position_params.text_document.uri.clone();
        let Some((doc, off)) = self.locate(&p.text_document_position_params) else {
            return Ok(serde_json::Value::Null);
        };
        let toks = tokenize_lenient(&doc.text);
        let Some((file, span)) = definition::definition(&doc.text, &toks, &doc.path, off) else {
            return Ok(serde_json::Value::Null);
        };
        let loc = match file {
            None => Location::new(uri, text::range(&doc.text, span)),
            Some(f) => {
                let t = crate::load::source::read_text(&f).unwrap_or_default();
                let Some(u) = text::uri_of(&f) else {
                    return Ok(serde_json::Value::Null);
                };
                Location::new(u, text::range(&t, span))
            }
        };
        Ok(serde_json::to_value(GotoDefinitionResponse::Scalar(loc))?)
    }
}

#[cfg(test)]
mod tests;
