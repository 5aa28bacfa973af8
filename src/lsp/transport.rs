//! The protocol's framing on a byte stream (`Content-Length: N`, a blank
//! line, then N bytes of JSON), read with a cap on N, and the stdio
//! transport built on it.
//!
//! Why not `lsp_server::Connection::stdio`: its reader sizes a buffer from
//! the header before any body byte arrives, so one line,
//! `Content-Length: 99999999999999`, made the server abort on a failed
//! allocation (found by the `lsp` fuzz target). Here the body is read as it
//! arrives, never past [`MAX_MESSAGE_BYTES`].

use crossbeam_channel::{Receiver, Sender, bounded};
use lsp_server::{Connection, Message};
use std::io::{self, BufRead, Read};
use std::thread::JoinHandle;

/// Largest message body read: a `didOpen` or `didChange` carries a whole
/// file (at most [`crate::load::source::MAX_SCENE_FILE_BYTES`], 64 MiB),
/// which JSON escaping can make up to six times longer. Raise it here.
pub const MAX_MESSAGE_BYTES: u64 = 6 * crate::load::source::MAX_SCENE_FILE_BYTES + (1 << 20);

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message)
}

/// Reads one framed message; `Ok(None)` at the end of the stream.
pub fn read_message(r: &mut impl BufRead) -> io::Result<Option<Message>> {
    let mut size = None;
    let mut line = String::new();
    loop {
        line.clear();
        // A header line is short; one without a line break in 64 KiB is
        // not a header.
        if r.by_ref().take(1 << 16).read_line(&mut line)? == 0 {
            return Ok(None);
        }
        let Some(header) = line.strip_suffix("\r\n") else {
            return Err(invalid(format!("malformed header line {line:?}")));
        };
        if header.is_empty() {
            break;
        }
        let Some((name, value)) = header.split_once(": ") else {
            return Err(invalid(format!("malformed header line {line:?}")));
        };
        if name.eq_ignore_ascii_case("Content-Length") {
            let n: u64 = value
                .parse()
                .map_err(|_| invalid(format!("bad Content-Length `{value}`")))?;
            if n > MAX_MESSAGE_BYTES {
                return Err(invalid(format!(
                    "a message of {n} bytes is above the limit of {MAX_MESSAGE_BYTES}"
                )));
            }
            size = Some(n);
        }
    }
    let size = size.ok_or_else(|| invalid("a message without Content-Length".into()))?;
    let mut body = Vec::new();
    r.take(size).read_to_end(&mut body)?;
    if (body.len() as u64) < size {
        return Err(io::Error::new(
            io::ErrorKind::UnexpectedEof,
            "the stream ended inside a message",
        ));
    }
    serde_json::from_slice(&body)
        .map(Some)
        .map_err(|e| invalid(format!("malformed message: {e}")))
}

/// The reader and writer threads of [`stdio`].
pub struct IoThreads {
    reader: JoinHandle<io::Result<()>>,
    writer: JoinHandle<io::Result<()>>,
}

impl IoThreads {
    /// Waits for both threads; the first error either met.
    pub fn join(self) -> io::Result<()> {
        let reader = self
            .reader
            .join()
            .unwrap_or_else(|_| Err(invalid("reader panicked".into())));
        let writer = self
            .writer
            .join()
            .unwrap_or_else(|_| Err(invalid("writer panicked".into())));
        reader.and(writer)
    }
}

/// A connection over standard input and output, as
/// `lsp_server::Connection::stdio` makes it but reading through
/// [`read_message`].
pub fn stdio() -> (Connection, IoThreads) {
    let (to_writer, from_server): (Sender<Message>, Receiver<Message>) = bounded(0);
    let writer = std::thread::spawn(move || {
        let mut out = io::stdout().lock();
        from_server.into_iter().try_for_each(|m| m.write(&mut out))
    });
    let (to_server, from_reader) = bounded(0);
    let reader = std::thread::spawn(move || {
        let mut input = io::stdin().lock();
        while let Some(m) = read_message(&mut input)? {
            let exit = matches!(&m, Message::Notification(n) if n.method == "exit");
            if to_server.send(m).is_err() || exit {
                break;
            }
        }
        Ok(())
    });
    let conn = Connection {
        sender: to_writer,
        receiver: from_reader,
    };
    (conn, IoThreads { reader, writer })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transport_refuses_a_content_length_past_the_limit_before_reading() {
        let huge = format!("Content-Length: {}\r\n\r\n{{}}", MAX_MESSAGE_BYTES + 1);
        let e = read_message(&mut huge.as_bytes()).expect_err("refused");
        assert!(e.to_string().contains("above the limit"), "{e}");
        let absurd = b"Content-Length: 18446744073709551615\r\n\r\n";
        assert!(read_message(&mut &absurd[..]).is_err());
    }

    #[test]
    fn transport_reads_framed_messages_in_order() {
        let body = r#"{"jsonrpc":"2.0","method":"exit"}"#;
        let text = format!("Content-Length: {}\r\n\r\n{body}", body.len()).repeat(2);
        let mut r = text.as_bytes();
        for _ in 0..2 {
            let m = read_message(&mut r).expect("read").expect("a message");
            assert!(matches!(m, Message::Notification(n) if n.method == "exit"));
        }
        assert!(read_message(&mut r).expect("end").is_none());
        let cut = &text[..text.len() / 2 - 3];
        assert!(
            read_message(&mut cut.as_bytes()).is_err(),
            "a truncated body is an error"
        );
    }
}
