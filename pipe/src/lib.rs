//! A rasterizer in another process, in any language, spoken to over its stdin and stdout with
//! the protocol of `docs/protocol.md`: [`Process`] implements [`Rasterizer`], so everything the
//! suite does to a Rust implementation (`certify`, `run_as_tests`, the fuzz targets) it does to
//! a Python or C++ program.
//!
//! | module | what |
//! |---|---|
//! | this one | [`Process`]: the child started, its handshake read, each draw sent and answered; [`Misbehaviour`] read back from an error |
//! | [`wire`] | the protocol's words and records: requests, the profile a child declares, fragments |
//! | `reply` | one reply read under a deadline, every breach of the protocol named |
//! | `pipe` | the child's stdout, stdin and stderr without blocking: [`for_each_line`], [`Tail`] |
//! | [`contain`] | every child in a process group of its own, under a memory limit |
//!
//! It depends on `refrast` alone, as every implementation does; the suite uses its words (its
//! reports name the wire's keys) and its containment (a rule's own child process).
//!
//! The child is started once and reused. A child that crashes, hangs past the per-draw timeout,
//! answers garbage, a wrong count or a fragment outside the viewport fails the draw with
//! [`DrawError::Misbehaved`], whose message says which, with the end of its stderr; it is then
//! killed and started afresh for the next draw. Nothing it does can panic or hang refrast.

#![forbid(unsafe_code)]

pub mod contain;
mod pipe;
mod reply;
pub mod wire;

use std::fmt;
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use refrast::{Draw, DrawError, Fragment, Profile, Rasterizer, Resolved};

use crate::contain::{Contained, DEFAULT_MEMORY_LIMIT, memory_note};

use pipe::{Errors, Incoming, Outgoing, Stall};
pub use pipe::{KEPT_OUTPUT, Tail, for_each_line};
use reply::{Breach, Reply, read_reply};
use wire::{Declared, MAX_LINE, Op, VERSION};

/// How long one draw (or the handshake) may take by default: generous for a Python
/// rasterizer on the suite's small scenes, short enough that a hang costs a run little.
pub const DEFAULT_DRAW_TIMEOUT: Duration = Duration::from_secs(10);

/// How long an exited child's stderr may take to drain before a message is written without it.
const DRAIN: Duration = Duration::from_millis(500);

/// The words of a breach whose child did not answer in time.
const HANGS: &str = "the child hangs on this draw";
/// The words of a breach whose child closed its stdout before answering.
const DIED: &str = "it crashed or exited";

/// What went wrong with a child, read from a [`DrawError::Misbehaved`] message.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Misbehaviour {
    /// It did not answer within the per-draw timeout.
    Hung,
    /// It died (closed its stdout, exited, was killed) or could not be restarted.
    Died,
    /// It answered, but not in the protocol.
    Garbled,
}

impl Misbehaviour {
    /// Which kind of misbehaviour a [`DrawError::Misbehaved`] message of this module reports.
    #[must_use]
    pub fn of(message: &str) -> Self {
        if message.contains(HANGS) {
            Self::Hung
        } else if message.contains(DIED) || message.starts_with(RESTARTING) {
            Self::Died
        } else {
            Self::Garbled
        }
    }
}

/// How a message about a child that could not be restarted begins.
const RESTARTING: &str = "restarting after the last failure";

/// Why a child could not be started or did not complete its handshake.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ProcessError {
    /// The command line is empty or its quotes do not balance.
    Command(String),
    /// The program could not be started (not found, not executable).
    Start(String),
    /// It started but did not declare a profile this refrast understands.
    Handshake(String),
}

impl fmt::Display for ProcessError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Command(why) => write!(f, "bad command line: {why}"),
            Self::Start(why) => write!(f, "could not start the child: {why}"),
            Self::Handshake(why) => write!(f, "the child's handshake failed: {why}"),
        }
    }
}

impl std::error::Error for ProcessError {}

/// The program and arguments to start, and the command line as given.
#[derive(Clone, Debug)]
struct Launch {
    line: String,
    program: String,
    args: Vec<String>,
}

/// A command line split into words as a shell would (quotes, backslashes), without running a
/// shell; `Err` when it is empty or its quotes do not balance.
pub fn split_command(line: &str) -> Result<Vec<String>, ProcessError> {
    let words = shell_words::split(line).map_err(|e| ProcessError::Command(format!("`{line}`: {e}")))?;
    if words.is_empty() {
        return Err(ProcessError::Command("it is empty".into()));
    }
    Ok(words)
}

impl Launch {
    fn parse(line: &str) -> Result<Self, ProcessError> {
        let words = split_command(line)?;
        let Some((program, args)) = words.split_first() else {
            return Err(ProcessError::Command("it is empty".into()));
        };
        Ok(Self {
            line: line.to_owned(),
            program: program.clone(),
            args: args.to_vec(),
        })
    }

    /// The last path component of the program's last argument, a name until the child says its own.
    fn short_name(&self) -> String {
        let last = self.args.last().unwrap_or(&self.program);
        std::path::Path::new(last)
            .file_stem()
            .map_or_else(|| last.clone(), |s| s.to_string_lossy().into_owned())
    }
}

/// A started child with its pipes.
#[derive(Debug)]
struct Running {
    child: Contained,
    outgoing: Outgoing,
    incoming: Incoming,
    errors: Errors,
}

/// A rasterizer in a child process speaking `docs/protocol.md` on its stdin and stdout.
#[derive(Debug)]
pub struct Process {
    launch: Launch,
    timeout: Duration,
    memory: Option<u64>,
    declared: Declared,
    running: Option<Running>,
    starts: u32,
    start_error: Option<String>,
}

impl Process {
    /// Starts `command` (split as a shell would, without running one) with the default
    /// per-draw timeout and reads its profile.
    pub fn try_spawn(command: &str) -> Result<Self, ProcessError> {
        Self::try_spawn_with(command, DEFAULT_DRAW_TIMEOUT)
    }

    /// [`Process::try_spawn`] with `timeout` for the handshake and for each draw.
    pub fn try_spawn_with(command: &str, timeout: Duration) -> Result<Self, ProcessError> {
        Self::try_spawn_limited(command, timeout, Some(DEFAULT_MEMORY_LIMIT))
    }

    /// [`Process::try_spawn_with`], the child limited to `memory` bytes of data (`None`: no
    /// limit; [`crate::contain`] says how).
    pub fn try_spawn_limited(
        command: &str,
        timeout: Duration,
        memory: Option<u64>,
    ) -> Result<Self, ProcessError> {
        let launch = Launch::parse(command)?;
        let (running, declared) = start(&launch, timeout, memory)?;
        Ok(Self {
            launch,
            timeout,
            memory,
            declared,
            running: Some(running),
            starts: 1,
            start_error: None,
        })
    }

    /// Like [`Process::try_spawn`], but never fails, for the suite's `run_as_tests`: a child that
    /// cannot start gives a rasterizer with the default profile whose every draw fails with
    /// the reason, so each rule says it.
    #[must_use]
    pub fn spawn(command: &str) -> Self {
        Self::spawn_with(command, DEFAULT_DRAW_TIMEOUT)
    }

    /// [`Process::spawn`] with `timeout` for the handshake and for each draw.
    #[must_use]
    pub fn spawn_with(command: &str, timeout: Duration) -> Self {
        Self::try_spawn_with(command, timeout).unwrap_or_else(|e| {
            let launch = Launch::parse(command).unwrap_or_else(|_| Launch {
                line: command.to_owned(),
                program: command.to_owned(),
                args: Vec::new(),
            });
            Self {
                declared: Declared::defaults(&launch.short_name(), VERSION),
                launch,
                timeout,
                memory: Some(DEFAULT_MEMORY_LIMIT),
                running: None,
                starts: 0,
                start_error: Some(e.to_string()),
            }
        })
    }

    /// The command line it was started with.
    #[must_use]
    pub fn command(&self) -> &str {
        &self.launch.line
    }

    /// How many times the child has been started (1 plus its restarts after misbehaving).
    #[must_use]
    pub fn starts(&self) -> u32 {
        self.starts
    }

    /// Why the child could not be started, for one built by [`Process::spawn`].
    #[must_use]
    pub fn start_error(&self) -> Option<&str> {
        self.start_error.as_deref()
    }

    /// Sends one request and reads its reply; a breach kills the child, to be restarted.
    fn exchange(&mut self, op: Op, draw: &Draw) -> Result<Reply, DrawError> {
        if let Some(why) = &self.start_error {
            return Err(DrawError::Misbehaved(why.clone()));
        }
        if self.running.is_none() {
            let (running, declared) = start(&self.launch, self.timeout, self.memory)
                .map_err(|e| DrawError::Misbehaved(format!("{RESTARTING}: {e}")))?;
            self.starts += 1;
            self.running = Some(running);
            if declared != self.declared {
                return Err(self.breach(Breach(
                    "the restarted child declared another profile than at its first start".into(),
                )));
            }
        }
        let Some(running) = self.running.as_mut() else {
            return Err(DrawError::Misbehaved("the child is not running".into()));
        };
        let extra = running.incoming.pending().len();
        if extra > 0 {
            return Err(self.breach(Breach(format!(
                "the child wrote {extra} bytes after its last reply's `end` (a wrong count?)"
            ))));
        }
        let deadline = Instant::now() + self.timeout;
        // Only a provoking mode the child declared is sent (any draw may ask any mode).
        let provoking = self.declared.profile.fit(draw.state).provoking_vertex;
        running
            .outgoing
            .send(wire::request_in(op, draw, self.declared.version, provoking));
        match read_reply(
            &mut running.incoming,
            op,
            draw,
            &self.declared,
            deadline,
            self.timeout,
        ) {
            Ok(reply) => Ok(reply),
            Err(breach) => Err(self.breach(breach)),
        }
    }

    /// Ends the child after a breach and says what happened, with its exit and its stderr.
    fn breach(&mut self, Breach(what): Breach) -> DrawError {
        let Some(running) = self.running.take() else {
            return DrawError::Misbehaved(what);
        };
        DrawError::Misbehaved(running.end(&what, &self.launch, self.memory))
    }
}

impl Running {
    /// Ends the child after `what` went wrong and says so, with how it ended and its stderr;
    /// whatever it started goes with it.
    fn end(mut self, what: &str, launch: &Launch, memory: Option<u64>) -> String {
        // A child that closed its stdout is exiting: give it a moment before killing it.
        let status = match self.child.wait_for(DRAIN) {
            Some(status) => Some(Ended::Exited(status)),
            None => Some(self.child.end().map_or(Ended::Killed, Ended::Exited)),
        };
        // Its group too, so that a grandchild holding stderr open lets it close.
        self.child.end();
        let stderr = self.errors.end(Instant::now() + DRAIN);
        let mut message = format!("{what} [{}; `{}`]", describe(status), launch.line);
        if !stderr.is_empty() {
            message.push_str(&memory_note(&stderr, memory));
            message.push_str(&format!("; its stderr ends:\n{stderr}"));
        }
        message
    }
}

impl Drop for Process {
    fn drop(&mut self) {
        if let Some(mut running) = self.running.take() {
            // Closing stdin asks the child to exit; one that does not is killed, with its group.
            drop(running.outgoing);
            running.child.wait_for(Duration::from_millis(200));
            running.child.end();
        }
    }
}

impl Process {
    /// `Err(Unsupported)` for a draw the child's profile does not declare: its topology and
    /// sample count, or its state (a scissor or a cull mode it does not list), so that nothing
    /// it did not ask for reaches it (docs/protocol.md promises as much), whoever draws.
    fn declares(&self, draw: &Draw) -> Result<(), DrawError> {
        let profile = &self.declared.profile;
        if !profile.draws(draw.topology, draw.samples) {
            return Err(DrawError::Unsupported(format!(
                "{} (the child does not declare it)",
                draw.describe()
            )));
        }
        let d = &draw.distances;
        if d.clip > profile.state.clip_distances || d.cull > profile.state.cull_distances {
            return Err(DrawError::Unsupported(format!(
                "{} clip and {} cull distances per vertex (the child declares {} and {})",
                d.clip, d.cull, profile.state.clip_distances, profile.state.cull_distances
            )));
        }
        if !profile.supports(&draw.state) {
            return Err(DrawError::Unsupported(format!(
                "{:?} (the child does not declare it; it does declare {:?})",
                draw.state,
                profile.fit(draw.state)
            )));
        }
        Ok(())
    }
}

impl Rasterizer for Process {
    fn profile(&self) -> Profile {
        self.declared.profile.clone()
    }

    fn about(&self) -> String {
        let run = format!("run as `{}`", self.launch.line);
        if self.declared.about.is_empty() {
            run
        } else {
            format!("{}; {run}", self.declared.about)
        }
    }

    /// A draw the child does not declare is refused here, without asking it.
    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        self.declares(draw)?;
        match self.exchange(Op::Rasterize, draw)? {
            // Flat values under a mode the child does not report them in are none.
            Reply::Fragments(mut fragments) => {
                if !self
                    .declared
                    .profile
                    .state
                    .flat
                    .contains(draw.state.provoking_vertex)
                {
                    fragments.iter_mut().for_each(|f| f.flat = None);
                }
                Ok(fragments)
            }
            Reply::Refused(e) => Err(e),
            Reply::Resolved(_) => Err(DrawError::Misbehaved("answered rasterize with a resolve".into())),
        }
    }

    /// A draw the child does not declare is refused here, without asking it; a child with no
    /// depth test of its own has its fragments replayed.
    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        if !self.declared.profile.features.depth_test {
            let fragments = self.rasterize(draw)?;
            return Ok(Resolved::from_fragments(draw, fragments));
        }
        self.declares(draw)?;
        match self.exchange(Op::Resolve, draw)? {
            Reply::Resolved(resolved) => Ok(resolved),
            Reply::Refused(e) => Err(e),
            Reply::Fragments(_) => Err(DrawError::Misbehaved("answered resolve with fragments".into())),
        }
    }
}

/// Starts the child, limited to `memory` bytes, and reads its handshake up to `ready`.
fn start(
    launch: &Launch,
    timeout: Duration,
    memory: Option<u64>,
) -> Result<(Running, Declared), ProcessError> {
    let mut command = Command::new(&launch.program);
    command
        .args(&launch.args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = Contained::spawn(&mut command, memory)
        .map_err(|e| ProcessError::Start(format!("`{}`: {e}", launch.line)))?;
    let (Some(stdin), Some(stdout), Some(stderr)) = (
        child.child.stdin.take(),
        child.child.stdout.take(),
        child.child.stderr.take(),
    ) else {
        child.end();
        return Err(ProcessError::Start("its pipes could not be opened".into()));
    };
    let mut running = Running {
        child,
        outgoing: Outgoing::new(stdin),
        incoming: Incoming::new(stdout),
        errors: Errors::new(stderr),
    };
    match handshake(&mut running.incoming, launch, timeout) {
        Ok(declared) => Ok((running, declared)),
        Err(why) => Err(ProcessError::Handshake(running.end(&why, launch, memory))),
    }
}

/// Reads the version line and the profile up to `ready`.
fn handshake(incoming: &mut Incoming, launch: &Launch, timeout: Duration) -> Result<Declared, String> {
    let deadline = Instant::now() + timeout;
    let stalled = |stall: Stall, lines: usize| match stall {
        Stall::TimedOut => format!(
            "no complete profile within {} s ({lines} lines, no `ready`)",
            timeout.as_secs_f64()
        ),
        Stall::Closed => {
            format!("the child closed its stdout after {lines} lines of its profile, before `ready`")
        }
        Stall::LineTooLong => format!("a profile line is longer than {MAX_LINE} bytes"),
    };
    let first = incoming.line(deadline, MAX_LINE).map_err(|s| stalled(s, 0))?;
    let version = wire::version(&first)?;
    let mut lines = Vec::new();
    loop {
        let line = incoming
            .line(deadline, MAX_LINE)
            .map_err(|s| stalled(s, lines.len() + 1))?;
        if line.trim() == "ready" {
            return wire::parse_profile(&lines, &launch.short_name(), version);
        }
        if lines.len() >= 64 {
            return Err("more than 64 profile lines without `ready`".into());
        }
        lines.push(line);
    }
}

/// How a child ended.
enum Ended {
    /// On its own.
    Exited(ExitStatus),
    /// Killed by refrast after a breach.
    Killed,
}

/// How the child ended, in words.
fn describe(ended: Option<Ended>) -> String {
    match ended {
        None => "exit status unknown".into(),
        Some(Ended::Killed) => "killed by refrast".into(),
        Some(Ended::Exited(status)) => status_words(status),
    }
}

/// An exit status in words: a code, or the signal that ended the process.
#[must_use]
pub fn status_words(status: ExitStatus) -> String {
    if let Some(code) = status.code() {
        return format!("exit code {code}");
    }
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(signal) = status.signal() {
            let name = match signal {
                4 => " (SIGILL)",
                6 => " (SIGABRT: an abort)",
                7 => " (SIGBUS)",
                8 => " (SIGFPE)",
                9 => " (SIGKILL)",
                11 => " (SIGSEGV: a crash)",
                _ => "",
            };
            return format!("killed by signal {signal}{name}");
        }
    }
    format!("{status}")
}
