//! The case log: a file a rule's child overwrites with each input before checking it, so the
//! parent can name the input a crash or a hang happened on without hearing from every case.
//!
//! A protocol line per case woke the parent once a case: a sixth of `certify`'s time on the
//! reference went to those wake-ups, and a tenth more to writing each input as Rust. The log
//! is one positioned write a case, of the count alone until case [`CASE_TEXT_FROM_ENV`] (a
//! second run's, naming the case the first stopped on), and is read only when the parent polls
//! for progress and when the child ends without a report. A write to a regular file is whole
//! once the call returns, so a child killed by a signal leaves the last input complete. The
//! file is `"{count:020} {len:020}\n"` then `len` bytes of the input as Rust (none: no text).

use std::fmt::{Debug, Write as _};
use std::fs::{File, OpenOptions};
use std::io;
use std::os::unix::fs::FileExt;
use std::path::Path;
use std::sync::{Mutex, OnceLock, PoisonError};

use tempfile::NamedTempFile;

/// The environment variable that gives a child its log's path.
pub(super) const CASE_LOG_ENV: &str = "REFRAST_CASE_LOG";

/// The environment variable that makes a child write the text of each input from the one with
/// this number (counting from 1) on: unset, no text.
pub(super) const CASE_TEXT_FROM_ENV: &str = "REFRAST_CASE_TEXT_FROM";

/// Bytes of the header: two 20-digit numbers, a space and a newline.
const HEADER: usize = 42;

/// The longest input read back: a mesh's text fits many times over; a longer one is cut.
const MAX_INPUT: u64 = 4 << 20;

/// The parent's side: the log a child writes, removed when dropped.
pub(super) struct CaseLog(NamedTempFile);

impl CaseLog {
    /// A new, empty log in the temp directory.
    pub(super) fn new() -> io::Result<Self> {
        tempfile::Builder::new()
            .prefix("refrast-cases-")
            .tempfile()
            .map(CaseLog)
    }

    /// Where the child is to write it.
    pub(super) fn path(&self) -> &Path {
        self.0.path()
    }

    /// How many inputs the child has announced (shrinking's included), and the last one's
    /// length; zeros before the first. A read racing a write may see a torn header: it only
    /// moves the progress display, and the log is read whole only once the child is gone.
    fn header(&self) -> (u64, u64) {
        let mut bytes = [0; HEADER];
        if self.0.as_file().read_exact_at(&mut bytes, 0).is_err() {
            return (0, 0);
        }
        let text = String::from_utf8_lossy(&bytes);
        let mut numbers = text.split_ascii_whitespace().map(|n| n.parse().unwrap_or(0));
        (numbers.next().unwrap_or(0), numbers.next().unwrap_or(0))
    }

    /// How many inputs the child has announced so far.
    pub(super) fn count(&self) -> u64 {
        self.header().0
    }

    /// The last input announced, as Rust: `None` before the first and where it was logged
    /// without its text.
    pub(super) fn last(&self) -> Option<String> {
        let (count, len) = self.header();
        if count == 0 || len == 0 {
            return None;
        }
        let kept = len.min(MAX_INPUT);
        let mut bytes = vec![0; usize::try_from(kept).unwrap_or(0)];
        self.0.as_file().read_exact_at(&mut bytes, HEADER as u64).ok()?;
        let mut text = String::from_utf8_lossy(&bytes).into_owned();
        if kept < len {
            text.push_str(&format!("… ({len} bytes, cut at {kept})"));
        }
        Some(text)
    }
}

/// The child's side: the open log, the inputs written so far, the first whose text it writes,
/// and a buffer kept between calls.
struct Writer {
    file: File,
    count: u64,
    text_from: u64,
    text: String,
}

impl Writer {
    /// Opens the log at `path` for writing, with the text of inputs from number `text_from` on.
    fn open(path: &Path, text_from: u64) -> io::Result<Self> {
        Ok(Writer {
            file: OpenOptions::new().write(true).open(path)?,
            count: 0,
            text_from,
            text: String::new(),
        })
    }

    /// Writes `input` as the last one, counting it, in one positioned write: its text only
    /// from input `text_from` on.
    fn write(&mut self, input: &dyn Debug) {
        self.count += 1;
        self.text.clear();
        self.text.extend(std::iter::repeat_n(' ', HEADER));
        if self.count >= self.text_from {
            let _ = write!(self.text, "{input:?}");
        }
        let header = format!("{:020} {:020}\n", self.count, self.text.len() - HEADER);
        self.text.replace_range(..HEADER, &header);
        // A parent that cannot read the log names no input; nothing better to do on failure.
        let _ = self.file.write_all_at(self.text.as_bytes(), 0);
    }
}

/// The child's log, opened on first use from [`CASE_LOG_ENV`]: `None` where the variable is
/// unset or the file cannot be opened.
static WRITER: OnceLock<Option<Mutex<Writer>>> = OnceLock::new();

/// Writes `input` to the child's log; `false` where this process has none, so the caller can
/// announce another way.
pub(super) fn write(input: &dyn Debug) -> bool {
    let writer = WRITER.get_or_init(|| {
        let path = std::env::var_os(CASE_LOG_ENV)?;
        let text_from = std::env::var(CASE_TEXT_FROM_ENV)
            .ok()
            .and_then(|n| n.parse().ok())
            .unwrap_or(u64::MAX);
        Writer::open(Path::new(&path), text_from).ok().map(Mutex::new)
    });
    let Some(writer) = writer else {
        return false;
    };
    writer.lock().unwrap_or_else(PoisonError::into_inner).write(input);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The last input written is read back whole after a longer one, with the count; a log
    /// never written, or written before the first input with text, names none.
    #[test]
    fn the_last_input_is_read_back() {
        let log = CaseLog::new().expect("a temp file");
        assert_eq!((log.count(), log.last()), (0, None));
        let mut writer = Writer::open(log.path(), 2).expect("the log opens");
        writer.write(&vec![1.5f32; 100]);
        assert_eq!((log.count(), log.last()), (1, None), "before input 2, no text");
        writer.write(&vec![1.5f32; 100]);
        writer.write(&("positions", [0.25f32, -1.0]));
        assert_eq!(log.count(), 3);
        assert_eq!(log.last().as_deref(), Some("(\"positions\", [0.25, -1.0])"));
    }

    /// An input longer than the parent reads is cut, and says so.
    #[test]
    fn a_huge_input_is_cut() {
        let log = CaseLog::new().expect("a temp file");
        let mut writer = Writer::open(log.path(), 1).expect("the log opens");
        writer.write(&"x".repeat(usize::try_from(MAX_INPUT).unwrap_or(0) + 10));
        let last = log.last().unwrap_or_default();
        assert!(last.starts_with("\"xxx"), "{}", &last[..10]);
        assert!(last.ends_with("cut at 4194304)"), "{}", &last[last.len() - 40..]);
    }
}
