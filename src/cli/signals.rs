//! What SIGINT, SIGTERM and SIGHUP do to a headless run: no temporary is left behind.
//!
//! Outputs are written to hidden temporaries and renamed into place at the end
//! ([`crate::io::atomic`]). Without a handler a signal ends the process at once and every
//! temporary stays on disk. The handler (ctrlc's thread, not signal context, so it may
//! take locks and remove files) removes them and exits with 130, the shell's code for an
//! interrupted command. A `batch` asks first to stop gently: the first signal lets the
//! images in progress finish and the summary be written (listing the rest as not done);
//! a second one ends it at once, as for any other command.

use std::sync::atomic::{AtomicBool, Ordering};

/// Set by a run that stops by itself at the next image when asked.
static GENTLE: AtomicBool = AtomicBool::new(false);
/// Set by the first signal of a gentle run.
static ASKED: AtomicBool = AtomicBool::new(false);

/// Installs the handler; once per process, before any output is prepared. A signal the
/// process was started ignoring stays ignored, as shells expect: `nohup` ignores SIGHUP,
/// and a job run in the background of a script starts with SIGINT ignored, so a Ctrl+C
/// meant for the script's foreground command must not stop it.
pub fn install() {
    let ignored: Vec<libc::c_int> = [libc::SIGINT, libc::SIGTERM, libc::SIGHUP]
        .into_iter()
        .filter(|&s| is_ignored(s))
        .collect();
    // The ignored signals are blocked until they are ignored again: one arriving while
    // the handler is briefly theirs stays pending, and setting SIG_IGN discards it.
    // SAFETY: plain calls on a local signal set; the old mask is restored below.
    let mut old: libc::sigset_t = unsafe { std::mem::zeroed() };
    unsafe {
        let mut block: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut block);
        for &s in &ignored {
            libc::sigaddset(&mut block, s);
        }
        libc::pthread_sigmask(libc::SIG_BLOCK, &block, &mut old);
    }
    // Another handler already installed (a library user's) stays theirs.
    let _ = ctrlc::set_handler(on_signal);
    for s in ignored {
        // SAFETY: setting a disposition to SIG_IGN has no handler to be unsafe in.
        unsafe { libc::signal(s, libc::SIG_IGN) };
    }
    // SAFETY: the mask saved above.
    unsafe { libc::pthread_sigmask(libc::SIG_SETMASK, &old, std::ptr::null_mut()) };
}

/// Whether signal `sig` is ignored now.
fn is_ignored(sig: libc::c_int) -> bool {
    // SAFETY: with a null new action, sigaction only writes the old one into `old`.
    let mut old: libc::sigaction = unsafe { std::mem::zeroed() };
    let read = unsafe { libc::sigaction(sig, std::ptr::null(), &mut old) };
    read == 0 && old.sa_sigaction == libc::SIG_IGN
}

fn on_signal() {
    if GENTLE.load(Ordering::SeqCst) && !ASKED.swap(true, Ordering::SeqCst) {
        return;
    }
    crate::io::atomic::remove_temporaries();
    super::note("interrupted: outputs not yet written were removed");
    std::process::exit(130);
}

/// From now on the first signal only asks the run to stop; [`stop_asked`] tells.
pub(crate) fn stop_gently() {
    GENTLE.store(true, Ordering::SeqCst);
}

/// Whether a signal asked a gentle run to stop.
pub(crate) fn stop_asked() -> bool {
    ASKED.load(Ordering::SeqCst)
}
