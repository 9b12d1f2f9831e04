//! What the Rust runtime's start-up did for the binary and it still needs, where it starts at
//! its own C `main` instead (GNU/Linux: `main.rs` says why).
//!
//! The runtime's start-up, before `fn main`, made sure descriptors 0-2 are open, ignored
//! SIGPIPE, and installed a handler that reports a thread's stack overflow. To find the main
//! thread's stack for that handler, glibc reads `/proc/self/maps` line by line with `sscanf`:
//! with the alternate signal stack it set up, ~21 system calls and ~0.1 ms of every run
//! (`dqsym -e 1`: 1.31 -> 1.21 ms wall at best, 230 -> 206 page faults). What the binary needs
//! of it is here, for the threads that evaluate (the main thread only waits for them):
//! [`open_standard_descriptors`] and [`watch_stack`]. SIGPIPE is set by `main.rs`
//! (`quiet_on_closed_pipe`) either way. The engine's helper threads watch theirs too: `main`
//! sets [`watch_stack`] as their start hook (`dqsym::scalar::on_helper_start`).

use std::cell::Cell;
use std::ffi::{c_int, c_void};

/// Opens `/dev/null` on each of descriptors 0, 1 and 2 that is closed, as the runtime did, so
/// that a file the command opens never becomes its standard output. Aborts if it cannot.
#[cfg_attr(test, allow(dead_code))]
pub(crate) fn open_standard_descriptors() {
    for fd in 0..=2 {
        // SAFETY: F_GETFD only reads the descriptor's flags.
        let closed = unsafe { libc::fcntl(fd, libc::F_GETFD) } == -1
            && std::io::Error::last_os_error().raw_os_error() == Some(libc::EBADF);
        // SAFETY: a NUL-terminated path; `open` returns the lowest free descriptor, `fd`.
        if closed && unsafe { libc::open(c"/dev/null".as_ptr(), libc::O_RDWR) } == -1 {
            std::process::abort();
        }
    }
}

/// Makes glibc's `malloc` keep one arena for every thread. Rust's allocations are
/// mimalloc's (`allocator.rs`); glibc's `malloc` serves glibc itself, once per thread
/// (`pthread_getattr_np`'s CPU set, for [`watch_stack`]), and its first call on each new
/// thread made an arena of its own: 128 MB of address space mapped and trimmed, its header
/// touched (four system calls and a page fault), on the worker before its first step.
#[cfg_attr(test, allow(dead_code))]
pub(crate) fn one_malloc_arena() {
    // SAFETY: a setting of glibc's allocator, made before any other thread exists.
    unsafe { libc::mallopt(libc::M_ARENA_MAX, 1) };
}

thread_local! {
    /// The guard area below this thread's stack (start, end), empty unless watched.
    static GUARD: Cell<(usize, usize)> = const { Cell::new((0, 0)) };
}

/// The size of a watched thread's alternate signal stack (the handler's only frame runs
/// there; AVX-512 signal frames take ~3.5 KB).
const ALT_STACK: usize = 64 << 10;

/// While alive, a stack overflow of this thread ends the process with a message on stderr
/// (status 134, SIGABRT) instead of a bare SIGSEGV.
pub(crate) struct Watch {
    /// The alternate stack's memory, kept until the stack is disabled.
    _alt: Vec<u8>,
}

/// Watches this thread's stack (see [`Watch`]); `None` where the stack's bounds or the
/// handler cannot be had (the thread runs unwatched then).
pub(crate) fn watch_stack() -> Option<Watch> {
    static INSTALLED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    if !*INSTALLED.get_or_init(install_handler) {
        return None;
    }
    let (low, guard) = this_stack()?;
    // Never written before a fault: its pages are not touched.
    let alt = Vec::<u8>::with_capacity(ALT_STACK);
    let stack = libc::stack_t {
        ss_sp: alt.as_ptr().cast_mut().cast::<c_void>(),
        ss_flags: 0,
        ss_size: ALT_STACK,
    };
    // SAFETY: the alternate stack lives as long as the `Watch`, which disables it on drop.
    if unsafe { libc::sigaltstack(&stack, std::ptr::null_mut()) } != 0 {
        return None;
    }
    // As the runtime did: a page either side of the start of the stack, since glibc once
    // counted the guard inside the stack.
    GUARD.with(|g| g.set((low - guard, low + guard)));
    Some(Watch { _alt: alt })
}

impl Drop for Watch {
    fn drop(&mut self) {
        GUARD.with(|g| g.set((0, 0)));
        let off = libc::stack_t {
            ss_sp: std::ptr::null_mut(),
            ss_flags: libc::SS_DISABLE,
            ss_size: 0,
        };
        // SAFETY: disables this thread's alternate stack before its memory (`alt`) is freed.
        unsafe { libc::sigaltstack(&off, std::ptr::null_mut()) };
    }
}

/// The lowest address of this thread's stack and the size of its guard (glibc's thread
/// attributes: no `/proc` read for a thread other than the main one).
fn this_stack() -> Option<(usize, usize)> {
    // SAFETY: the attributes are initialised by `pthread_getattr_np`, read, then destroyed.
    unsafe {
        let mut attr: libc::pthread_attr_t = std::mem::zeroed();
        if libc::pthread_getattr_np(libc::pthread_self(), &mut attr) != 0 {
            return None;
        }
        let mut addr: *mut c_void = std::ptr::null_mut();
        let mut size = 0;
        let mut guard = 0;
        let ok = libc::pthread_attr_getstack(&attr, &mut addr, &mut size) == 0
            && libc::pthread_attr_getguardsize(&attr, &mut guard) == 0;
        libc::pthread_attr_destroy(&mut attr);
        let page = usize::try_from(libc::sysconf(libc::_SC_PAGESIZE)).ok()?;
        (ok && !addr.is_null()).then(|| (addr as usize, guard.max(page)))
    }
}

/// Installs [`on_fault`] for SIGSEGV and SIGBUS, on the alternate stack; whether it could.
fn install_handler() -> bool {
    [libc::SIGSEGV, libc::SIGBUS].into_iter().all(|signum| {
        // SAFETY: a zeroed `sigaction` with the handler, flags and an empty mask set.
        unsafe {
            let mut action: libc::sigaction = std::mem::zeroed();
            action.sa_sigaction = on_fault as *const () as usize;
            action.sa_flags = libc::SA_SIGINFO | libc::SA_ONSTACK;
            libc::sigemptyset(&mut action.sa_mask);
            libc::sigaction(signum, &action, std::ptr::null_mut()) == 0
        }
    })
}

/// A fault in the watched guard is a stack overflow: the message, then abort. Any other fault
/// gets the default action back and happens again on return (the process ends by it).
extern "C" fn on_fault(signum: c_int, info: *mut libc::siginfo_t, _: *mut c_void) {
    // SAFETY: the kernel passes a valid `siginfo_t` for SA_SIGINFO handlers of these signals.
    let addr = unsafe { (*info).si_addr() } as usize;
    let (start, end) = GUARD.with(Cell::get);
    if start <= addr && addr < end {
        const MESSAGE: &[u8] = b"error: internal failure: the evaluation overflowed its stack\n";
        // SAFETY: `write` and `abort` are async-signal-safe.
        unsafe {
            libc::write(2, MESSAGE.as_ptr().cast(), MESSAGE.len());
            libc::abort();
        }
    }
    // SAFETY: restores the default disposition (async-signal-safe).
    unsafe {
        let mut action: libc::sigaction = std::mem::zeroed();
        action.sa_sigaction = libc::SIG_DFL;
        libc::sigaction(signum, &action, std::ptr::null_mut());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::process::ExitStatusExt;
    use std::process::{Command, Output};

    /// Set in the child process of each test below: the child does the part that ends it.
    const CHILD: &str = "DQSYM_START_TEST_CHILD";

    fn is_child() -> bool {
        std::env::var_os(CHILD).is_some()
    }

    /// Runs the test `name` of this binary alone, in a child process, as the child.
    fn in_child(name: &str) -> Output {
        Command::new(std::env::current_exe().expect("the test binary"))
            .args([name, "--exact", "--nocapture", "--test-threads=1"])
            .env(CHILD, "1")
            .output()
            .expect("runs")
    }

    /// Runs `work` on a thread with a small stack that watches it; returns if `work` does.
    fn on_watched_thread(work: fn() -> u64) {
        let thread = std::thread::Builder::new()
            .stack_size(1 << 20)
            .spawn(move || {
                let _watch = watch_stack().expect("the stack is watched");
                work()
            })
            .expect("spawns");
        let _ = thread.join();
    }

    /// Recurses without end; each frame keeps a buffer, so the calls cannot become a loop.
    #[allow(unconditional_recursion)]
    fn recurse(n: u64) -> u64 {
        let frame = std::hint::black_box([n; 32]);
        recurse(n + 1).wrapping_add(frame[usize::try_from(n % 32).expect("small")])
    }

    #[test]
    fn a_stack_overflow_of_a_watched_thread_is_reported() {
        if is_child() {
            on_watched_thread(|| recurse(0));
            return;
        }
        let out = in_child("start::tests::a_stack_overflow_of_a_watched_thread_is_reported");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.signal(), Some(libc::SIGABRT), "{out:?}");
        assert!(
            stderr.contains("error: internal failure: the evaluation overflowed its stack"),
            "{stderr}"
        );
    }

    #[test]
    fn another_fault_of_a_watched_thread_is_not_called_an_overflow() {
        if is_child() {
            // SAFETY: none: the read faults (address 8 is never mapped), which is the test.
            on_watched_thread(|| unsafe { std::ptr::read_volatile(std::ptr::dangling::<u64>()) });
            return;
        }
        let out =
            in_child("start::tests::another_fault_of_a_watched_thread_is_not_called_an_overflow");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.signal(), Some(libc::SIGSEGV), "{out:?}");
        assert!(!stderr.contains("overflowed"), "{stderr}");
    }

    /// The binary's unwinder (`main.rs`: libgcc's static one where the C compiler has it)
    /// unwinds a panic to where it is caught, as the REPL catches a failed statement's.
    #[test]
    fn a_panic_unwinds_to_where_it_is_caught() {
        let caught = std::panic::catch_unwind(|| {
            let _watch = watch_stack();
            std::panic::panic_any(42_u8)
        });
        let payload = caught.expect_err("the panic is caught");
        assert_eq!(payload.downcast_ref::<u8>(), Some(&42));
    }

    #[test]
    fn closed_standard_descriptors_are_opened_on_dev_null() {
        if is_child() {
            // SAFETY: closes standard input, which nothing of this child reads.
            assert_eq!(unsafe { libc::close(0) }, 0);
            open_standard_descriptors();
            let target = std::fs::read_link("/proc/self/fd/0").expect("descriptor 0 is open");
            assert_eq!(target, std::path::Path::new("/dev/null"));
            return;
        }
        let out = in_child("start::tests::closed_standard_descriptors_are_opened_on_dev_null");
        assert!(out.status.success(), "{out:?}");
        // The child ran the test (it was not filtered out).
        assert!(
            String::from_utf8_lossy(&out.stdout).contains("1 passed"),
            "{out:?}"
        );
    }
}
