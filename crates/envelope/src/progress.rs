//! Progress reports and cancellation: one callback, told what happens, that may ask to stop.

use std::ops::ControlFlow;

pub use envelope_simplify::Stage;

/// What a long call is doing, told to the callback given to
/// [`Simplifier::progress`](crate::Simplifier::progress) or [`Lod::progress`](crate::Lod::progress).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Event {
    /// A level of a chain begins (`index` from 1 to `count`); its stages follow.
    Level {
        /// This level, from 1.
        index: usize,
        /// Levels in the chain.
        count: usize,
    },
    /// A stage begins.
    Stage(Stage),
    /// During [`Stage::Simplify`]: removal attempts and vertices removed so far.
    Removed {
        /// Attempts so far.
        attempts: usize,
        /// Vertices removed so far.
        removed: usize,
    },
}

/// The callback: return [`ControlFlow::Break`] to cancel (the call then ends with
/// [`Error::Cancelled`](crate::Error::Cancelled) at its next check, and makes no output).
pub type Callback<'a> = dyn Fn(Event) -> ControlFlow<()> + Send + Sync + 'a;

/// The engine's progress trait over a callback, remembering a request to stop.
pub(crate) struct Relay<'a> {
    callback: Option<&'a Callback<'a>>,
    stop: bool,
}

impl<'a> Relay<'a> {
    pub(crate) fn new(callback: Option<&'a Callback<'a>>) -> Self {
        Relay {
            callback,
            stop: false,
        }
    }

    pub(crate) fn tell(&mut self, event: Event) {
        if let Some(cb) = self.callback {
            self.stop |= cb(event).is_break();
        }
    }
}

impl envelope_simplify::Progress for Relay<'_> {
    fn stage(&mut self, stage: Stage) {
        self.tell(Event::Stage(stage));
    }

    fn step(&mut self, attempts: usize, removed: usize) {
        self.tell(Event::Removed { attempts, removed });
    }

    fn cancelled(&mut self) -> bool {
        self.stop
    }
}
