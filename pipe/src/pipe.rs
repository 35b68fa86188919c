//! The child's three pipes, each served by a thread of its own, so that a child that stops
//! reading or writing can never block the parent: requests go out through a writer thread,
//! replies come in through a reader thread and wait with a deadline, stderr is kept as a tail.

use std::io::{BufRead, BufReader, ErrorKind, Read, Write};
use std::process::{ChildStderr, ChildStdin, ChildStdout};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender, SyncSender};
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::Instant;

/// How much of a child's stderr a message keeps (its end).
pub const KEPT_OUTPUT: usize = 4000;

/// The last [`KEPT_OUTPUT`] bytes of a stream.
#[derive(Debug, Default)]
pub struct Tail(pub String);

impl Tail {
    /// Appends a line, dropping the oldest text beyond twice the kept size.
    pub fn push(&mut self, line: &str) {
        self.0.push_str(line);
        self.0.push('\n');
        if self.0.len() > 2 * KEPT_OUTPUT {
            let mut cut = self.0.len() - KEPT_OUTPUT;
            while !self.0.is_char_boundary(cut) {
                cut += 1;
            }
            self.0.drain(..cut);
        }
    }

    /// The last [`KEPT_OUTPUT`] bytes, whole characters.
    #[must_use]
    pub fn end(&self) -> &str {
        let body = self.0.trim_end();
        let start = body.len().saturating_sub(KEPT_OUTPUT);
        let start = (start..body.len())
            .find(|&i| body.is_char_boundary(i))
            .unwrap_or(0);
        &body[start..]
    }
}

/// Writes requests to the child's stdin on a thread of its own; dropping it closes stdin.
#[derive(Debug)]
pub struct Outgoing(Sender<Vec<u8>>);

impl Outgoing {
    /// Starts the writer thread.
    pub fn new(mut stdin: ChildStdin) -> Self {
        let (tx, rx) = mpsc::channel::<Vec<u8>>();
        thread::spawn(move || {
            for bytes in rx {
                // A child that closed its stdin has exited or will: its reply (none) says so.
                if stdin.write_all(&bytes).and_then(|()| stdin.flush()).is_err() {
                    return;
                }
            }
        });
        Self(tx)
    }

    /// Queues `bytes` for the child.
    pub fn send(&self, bytes: Vec<u8>) {
        // The writer only stops when the child's stdin broke; the reply then says why.
        let _ = self.0.send(bytes);
    }
}

/// Why the bytes asked for did not come.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stall {
    /// The deadline passed.
    TimedOut,
    /// The child closed its stdout (it exited, most likely).
    Closed,
    /// A line went on past [`super::wire::MAX_LINE`] bytes.
    LineTooLong,
}

/// Chunks of a child's stdout read ahead of refrast, at most: 1 MiB.
const QUEUED: usize = 16;

/// The child's stdout, read on a thread of its own and handed over with deadlines.
#[derive(Debug)]
pub struct Incoming {
    rx: Receiver<Vec<u8>>,
    buffer: Vec<u8>,
    closed: bool,
}

impl Incoming {
    /// Starts the reader thread.
    pub fn new(mut stdout: ChildStdout) -> Self {
        // Bounded: a child that floods its stdout waits for refrast to read, instead of
        // filling refrast's memory (at most QUEUED chunks of 64 KiB wait here).
        let (tx, rx): (SyncSender<Vec<u8>>, _) = mpsc::sync_channel(QUEUED);
        thread::spawn(move || {
            let mut chunk = vec![0u8; 1 << 16];
            loop {
                match stdout.read(&mut chunk) {
                    Ok(0) | Err(_) => return,
                    Ok(n) => {
                        if tx.send(chunk[..n].to_vec()).is_err() {
                            return;
                        }
                    }
                }
            }
        });
        Self {
            rx,
            buffer: Vec::new(),
            closed: false,
        }
    }

    /// Bytes received and not yet taken, with whatever the reader thread holds ready (at most
    /// [`QUEUED`] chunks): what a child wrote after its last reply.
    pub fn pending(&mut self) -> &[u8] {
        while let Ok(bytes) = self.rx.try_recv() {
            self.buffer.extend_from_slice(&bytes);
        }
        &self.buffer
    }

    /// Waits for more bytes until `deadline`.
    fn fill(&mut self, deadline: Instant) -> Result<(), Stall> {
        if self.closed {
            return Err(Stall::Closed);
        }
        let left = deadline.saturating_duration_since(Instant::now());
        match self.rx.recv_timeout(left) {
            Ok(bytes) => {
                self.buffer.extend_from_slice(&bytes);
                Ok(())
            }
            Err(RecvTimeoutError::Timeout) => Err(Stall::TimedOut),
            Err(RecvTimeoutError::Disconnected) => {
                self.closed = true;
                Err(Stall::Closed)
            }
        }
    }

    /// The next line, without its `\n` (and a `\r` before it), as UTF-8 with bad bytes replaced.
    pub fn line(&mut self, deadline: Instant, max: usize) -> Result<String, Stall> {
        loop {
            if let Some(end) = self.buffer.iter().position(|&b| b == b'\n') {
                let mut line: Vec<u8> = self.buffer.drain(..=end).collect();
                line.pop();
                if line.last() == Some(&b'\r') {
                    line.pop();
                }
                return Ok(String::from_utf8_lossy(&line).into_owned());
            }
            if self.buffer.len() > max {
                return Err(Stall::LineTooLong);
            }
            self.fill(deadline)?;
        }
    }

    /// The next `n` bytes; on a stall, how many of them had come.
    pub fn bytes(&mut self, n: usize, deadline: Instant) -> Result<Vec<u8>, (Stall, usize)> {
        while self.buffer.len() < n {
            self.fill(deadline).map_err(|stall| (stall, self.buffer.len()))?;
        }
        Ok(self.buffer.drain(..n).collect())
    }
}

/// Keeps the tail of the child's stderr; [`Errors::end`] reads it once the stream is done.
#[derive(Debug)]
pub struct Errors {
    tail: Arc<Mutex<Tail>>,
    done: Receiver<()>,
}

impl Errors {
    /// Starts the thread that reads stderr.
    pub fn new(stderr: ChildStderr) -> Self {
        let tail = Arc::new(Mutex::new(Tail::default()));
        let (tx, done) = mpsc::channel();
        let kept = Arc::clone(&tail);
        thread::spawn(move || {
            for_each_line(stderr, 2 * KEPT_OUTPUT, |line, _| {
                if let Ok(mut tail) = kept.lock() {
                    tail.push(String::from_utf8_lossy(line).trim_end_matches('\r'));
                }
                true
            });
            let _ = tx.send(());
        });
        Self { tail, done }
    }

    /// The end of stderr, after waiting until `deadline` for the stream to close (a child that
    /// has exited has closed it; one that left a grandchild holding it has not).
    #[must_use]
    pub fn end(&self, deadline: Instant) -> String {
        let _ = self
            .done
            .recv_timeout(deadline.saturating_duration_since(Instant::now()));
        self.tail.lock().map(|t| t.end().to_owned()).unwrap_or_default()
    }
}

/// Reads `stream` to its end line by line, handing each line (without its `\n` or a `\r`
/// before it) to `f`, with whether it was cut, until `f` returns `false`. A line longer than
/// `max` bytes is cut to its first `max` and the rest skipped, so the memory this takes is
/// bounded whatever the stream holds.
pub fn for_each_line(stream: impl Read, max: usize, mut f: impl FnMut(&[u8], bool) -> bool) {
    let mut reader = BufReader::new(stream);
    let (mut line, mut cut) = (Vec::new(), false);
    loop {
        let buffer = match reader.fill_buf() {
            Ok([]) => break,
            Ok(buffer) => buffer,
            Err(e) if e.kind() == ErrorKind::Interrupted => continue,
            Err(_) => break,
        };
        let newline = buffer.iter().position(|&b| b == b'\n');
        let part = &buffer[..newline.unwrap_or(buffer.len())];
        let room = max.saturating_sub(line.len());
        cut |= part.len() > room;
        line.extend_from_slice(&part[..part.len().min(room)]);
        let used = newline.map_or(buffer.len(), |i| i + 1);
        reader.consume(used);
        if newline.is_some() {
            if line.last() == Some(&b'\r') {
                line.pop();
            }
            if !f(&line, cut) {
                return;
            }
            (cut, line) = (false, Vec::new());
        }
    }
    if !line.is_empty() {
        f(&line, cut);
    }
}
