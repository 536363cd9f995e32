//! Progress of the report on stderr: an `indicatif` bar (position, percentage,
//! elapsed time, ETA, current job) when stderr is a terminal and the
//! `progress-bar` feature is on; one plain line per 10 % otherwise (CI logs),
//! since a bar redrawn in place is unreadable there.

#[cfg(feature = "progress-bar")]
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
#[cfg(feature = "progress-bar")]
use std::io::IsTerminal;
use std::io::Write;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// Thread-safe progress over `total` jobs.
pub struct Progress {
    enabled: bool,
    #[cfg(feature = "progress-bar")]
    bar: Option<ProgressBar>,
    total: usize,
    done: AtomicUsize,
    start: Instant,
    last_decile: AtomicUsize,
}

impl Progress {
    /// Progress over `total` jobs; `enabled = false` shows nothing.
    pub fn new(enabled: bool, total: usize) -> Self {
        #[cfg(feature = "progress-bar")]
        let bar = (enabled && std::io::stderr().is_terminal()).then(|| {
            let bar = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
            let style = ProgressStyle::with_template(
                "[{bar:30}] {pos}/{len} {percent:>3}% {elapsed_precise} elapsed, ~{eta} left  {wide_msg}",
            )
            .map(|s| s.progress_chars("#>-"))
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            bar.set_style(style);
            bar
        });
        Progress {
            enabled,
            #[cfg(feature = "progress-bar")]
            bar,
            total,
            done: AtomicUsize::new(0),
            start: Instant::now(),
            last_decile: AtomicUsize::new(usize::MAX),
        }
    }

    /// One job finished; `what` names it.
    pub fn tick(&self, what: &str) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if !self.enabled {
            return;
        }
        #[cfg(feature = "progress-bar")]
        if let Some(bar) = &self.bar {
            bar.set_message(what.to_string());
            bar.inc(1);
            return;
        }
        let frac = done as f64 / self.total.max(1) as f64;
        let decile = (frac * 10.0) as usize;
        if self.last_decile.swap(decile, Ordering::Relaxed) == decile && done != self.total {
            return;
        }
        let el = self.start.elapsed().as_secs_f64();
        let eta = if frac > 0.0 { el / frac - el } else { 0.0 };
        let mut err = std::io::stderr().lock();
        let _ = writeln!(
            err,
            "{done}/{} {:3}% {el:6.1}s elapsed, ~{eta:5.0}s left  {what}",
            self.total,
            (frac * 100.0) as usize
        );
    }

    /// Clears the bar.
    pub fn finish(&self) {
        #[cfg(feature = "progress-bar")]
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
