//! Ctrl-C: SIGINT, SIGTERM and SIGHUP set a flag instead of ending the
//! process, so that a command can stop at a point of its choosing and
//! leave its `--out` directory as it was ([`super::out_dir`]).
//!
//! Once [`Interrupt::install`] has run, the signals no longer end the
//! process: the code that installed it must ask [`Interrupt::requested`]
//! (the solve does before every attempt and Newton iteration, through
//! [`solver::monitor::Monitor::stop_requested`]; [`super::out_dir`] does
//! before it moves a result set into place). A command that has not
//! installed it is ended by the signal as usual.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};

/// The signals [`Interrupt`] catches.
const SIGNALS: [i32; 3] = [SIGINT, SIGTERM, SIGHUP];

/// A stop request from a signal (module docs).
#[derive(Debug, Clone)]
pub struct Interrupt {
    flag: Arc<AtomicBool>,
}

impl Interrupt {
    /// Catches [`SIGNALS`] from now on.
    pub fn install() -> std::io::Result<Interrupt> {
        let flag = Arc::new(AtomicBool::new(false));
        for s in SIGNALS {
            signal_hook::flag::register(s, Arc::clone(&flag))?;
        }
        Ok(Interrupt { flag })
    }

    /// Whether a signal has arrived since [`Interrupt::install`].
    pub fn requested(&self) -> bool {
        self.flag.load(Ordering::Relaxed)
    }
}
