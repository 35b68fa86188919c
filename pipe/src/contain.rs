//! Child processes held on a leash: a process group, so that what a child forks goes when it
//! goes, and a memory limit, so that a child that allocates without bound fails its rule
//! instead of exhausting the machine.
//!
//! Every child refrast starts (a rule's process, a `--exec` rasterizer) leads a process group
//! of its own, unless refrast itself runs inside such a group (a rule's process starting a
//! `--exec` child): then the child joins that group, and the outer refrast, which leads it,
//! clears it. Ending a child kills its whole group with `SIGKILL`, so a grandchild that
//! outlived its parent (a shell's `&`, a daemon that forked) does not outlive the run. A
//! grandchild that leaves the group on purpose (`setsid`) escapes; no plain process can stop
//! that without privileges.
//!
//! The memory limit is `RLIMIT_DATA` (the heap and every private writable mapping; Linux 4.7
//! and later), set with `prlimit` right after the child starts and inherited by whatever it
//! starts. Virtual address space (`RLIMIT_AS`) would also count the address ranges GPU drivers
//! and JIT compilers reserve without using, and fail them. A child over the limit sees its
//! allocations fail: a Rust program aborts with "memory allocation of N bytes failed", Python
//! raises `MemoryError`; [`out_of_memory`] recognises both in its stderr.

use std::collections::BTreeSet;
use std::io;
use std::process::{Child, Command, ExitStatus};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// The memory limit of every child refrast starts, unless told otherwise: 4 GiB, far above
/// what the suite's scenes need (a few MB), and five at once still fit this project's 24 GiB
/// machines.
pub const DEFAULT_MEMORY_LIMIT: u64 = 4 << 30;

/// Set in the environment of every child: it runs inside a group that its parent leads.
const IN_GROUP: &str = "REFRAST_IN_PROCESS_GROUP";

/// The process groups this process's children lead and that have not been ended yet, for
/// [`end_all`], and whether it has run (no child starts after it).
static LEADERS: Mutex<Leaders> = Mutex::new(Leaders {
    groups: BTreeSet::new(),
    ending: false,
});

/// The groups to end on an interrupt.
#[derive(Debug)]
struct Leaders {
    /// The process groups children lead.
    groups: BTreeSet<u32>,
    /// Set by [`end_all`]: the process is ending, and starts no more children.
    ending: bool,
}

/// Kills every process group a child of this process leads: for an interrupt (Ctrl-C, `SIGTERM`)
/// of refrast, which the terminal delivers to refrast's own group only, so that no child, nor
/// anything it started, outlives refrast. It holds the list while it kills, and a child is
/// started and listed under the same lock ([`Contained::spawn`]), so a child started just
/// before is ended too and none starts after.
pub fn end_all() {
    end_listed(&LEADERS);
}

/// [`end_all`] on the groups of `list`.
fn end_listed(list: &Mutex<Leaders>) {
    let mut leaders = list.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    leaders.ending = true;
    for &pid in &leaders.groups {
        kill_group(pid);
    }
}

/// `SIGKILL` to process group `pid` (harmless when the group is empty).
fn kill_group(pid: u32) {
    #[cfg(unix)]
    if let Some(pid) = rustix::process::Pid::from_raw(pid as i32) {
        let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
    }
    #[cfg(not(unix))]
    let _ = pid;
}

/// A started child, its group and its limit.
#[derive(Debug)]
pub struct Contained {
    /// The child itself.
    pub child: Child,
    /// Whether it leads a process group of its own (so that ending it ends the group).
    leads: bool,
    /// The list its group is on while it leads one ([`LEADERS`] but in tests).
    listed_in: &'static Mutex<Leaders>,
    /// Its exit, once seen.
    status: Option<ExitStatus>,
}

impl Contained {
    /// Starts `command` in a group of its own (or in refrast's, see the module), limited to
    /// `memory` bytes (`None`: no limit).
    pub fn spawn(command: &mut Command, memory: Option<u64>) -> io::Result<Self> {
        Self::spawn_listed(command, memory, &LEADERS)
    }

    /// [`Contained::spawn`], its group listed in `list`.
    fn spawn_listed(
        command: &mut Command,
        memory: Option<u64>,
        list: &'static Mutex<Leaders>,
    ) -> io::Result<Self> {
        let leads = std::env::var_os(IN_GROUP).is_none();
        command.env(IN_GROUP, "1");
        #[cfg(unix)]
        if leads {
            use std::os::unix::process::CommandExt;
            command.process_group(0);
        }
        // Started and listed at once, under the lock `end_all` takes: an interrupt between the
        // two would miss the child.
        let child = {
            let mut leaders = list.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            if leaders.ending {
                return Err(io::Error::other("refrast is ending: no child starts now"));
            }
            let child = command.spawn()?;
            if leads {
                leaders.groups.insert(child.id());
            }
            child
        };
        if let Some(bytes) = memory {
            limit_memory(&child, bytes);
        }
        Ok(Self {
            child,
            leads,
            listed_in: list,
            status: None,
        })
    }

    /// The child's exit if it has exited, without waiting.
    pub fn try_wait(&mut self) -> Option<ExitStatus> {
        if self.status.is_none() {
            self.status = self.child.try_wait().ok().flatten();
        }
        self.status
    }

    /// The child's exit within `within`, if it exits.
    pub fn wait_for(&mut self, within: Duration) -> Option<ExitStatus> {
        let deadline = Instant::now() + within;
        loop {
            if let Some(status) = self.try_wait() {
                return Some(status);
            }
            if Instant::now() >= deadline {
                return None;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// Kills the child and everything in its group, and waits for the child; `None` when it
    /// had to be killed, its exit when it had already exited.
    pub fn end(&mut self) -> Option<ExitStatus> {
        let exited = self.try_wait();
        self.kill_group();
        if exited.is_none() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
        exited
    }

    /// `SIGKILL` to the child's group, when it leads one; the group is then no longer tracked.
    fn kill_group(&self) {
        if self.leads {
            kill_group(self.child.id());
            if let Ok(mut leaders) = self.listed_in.lock() {
                leaders.groups.remove(&self.child.id());
            }
        }
    }
}

impl Drop for Contained {
    /// Nothing the child started outlives it.
    fn drop(&mut self) {
        self.end();
    }
}

/// Sets the child's `RLIMIT_DATA` to `bytes` (soft and hard). Best effort: where the call
/// fails (not Linux, or a hard limit already lower) the child keeps the limit it inherited.
fn limit_memory(child: &Child, bytes: u64) {
    #[cfg(target_os = "linux")]
    {
        use rustix::process::{Pid, Resource, Rlimit, prlimit};
        let Some(pid) = Pid::from_raw(child.id() as i32) else {
            return;
        };
        let limit = Rlimit {
            current: Some(bytes),
            maximum: Some(bytes),
        };
        let _ = prlimit(Some(pid), Resource::Data, limit);
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (child, bytes);
}

/// Whether a child's stderr says that an allocation failed: Rust's "memory allocation of N
/// bytes failed" or Python's `MemoryError`.
#[must_use]
pub fn out_of_memory(stderr: &str) -> bool {
    stderr.contains("memory allocation of") || stderr.contains("MemoryError")
}

/// What to add to a message about a child whose stderr says it ran out of memory under
/// `limit`: the limit and the option that sets it; empty otherwise.
#[must_use]
pub fn memory_note(stderr: &str, limit: Option<u64>) -> String {
    match limit {
        Some(bytes) if out_of_memory(stderr) => format!(
            " (out of memory: the process is limited to {} MiB of data; --memory-limit sets it)",
            bytes >> 20
        ),
        _ => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A child started and listed ends with `end_all`, and none starts after it: an interrupt
    /// that came between a child's start and its listing once let it outlive refrast.
    #[test]
    fn ending_all_ends_the_listed_and_starts_none() {
        let list: &'static Mutex<Leaders> = Box::leak(Box::new(Mutex::new(Leaders {
            groups: BTreeSet::new(),
            ending: false,
        })));
        let mut sleeper =
            Contained::spawn_listed(Command::new("sleep").arg("30"), None, list).expect("sleep starts");
        assert!(
            list.lock()
                .expect("the list")
                .groups
                .contains(&sleeper.child.id())
        );
        end_listed(list);
        assert!(
            sleeper.wait_for(Duration::from_secs(5)).is_some(),
            "the listed child was killed"
        );
        let refused = Contained::spawn_listed(Command::new("sleep").arg("30"), None, list);
        assert!(refused.is_err_and(|e| e.to_string().contains("ending")));
    }
}
