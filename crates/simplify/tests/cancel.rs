//! Cancellation: a [`Progress`] whose `cancelled` says yes stops `simplify_with` with
//! `DriverError::Cancelled`, between stages or during the local algorithm's run.

use envelope_mesh::generate;
use envelope_offset::EpsilonField;
use envelope_simplify::{DriverError, LocalStep, Progress, SimplifyOptions, Stage, simplify_with};

/// Cancels once it has seen its trigger: the first step, or a stage.
struct CancelAt {
    stage: Option<Stage>,
    at_first_step: bool,
    cancel: bool,
    steps: usize,
    stages: Vec<Stage>,
}

impl CancelAt {
    fn new(stage: Option<Stage>, at_first_step: bool) -> Self {
        Self {
            stage,
            at_first_step,
            cancel: false,
            steps: 0,
            stages: Vec::new(),
        }
    }
}

impl Progress for CancelAt {
    fn stage(&mut self, stage: Stage) {
        self.cancel |= self.stage == Some(stage);
        self.stages.push(stage);
    }
    fn step(&mut self, _attempts: usize, _removed: usize) {
        self.steps += 1;
        self.cancel |= self.at_first_step;
    }
    fn cancelled(&mut self) -> bool {
        self.cancel
    }
}

/// A sphere with enough vertices for the local algorithm to report steps (every 256
/// attempts) well before it ends.
fn job() -> (envelope_mesh::TriangleSoup, SimplifyOptions) {
    (
        generate::icosphere(4, 1.0),
        SimplifyOptions::new(EpsilonField::Constant(0.01)),
    )
}

#[test]
fn cancelling_at_the_first_step_stops_the_run() {
    let (soup, options) = job();
    // Without cancelling, the run reports several steps.
    let mut counting = CancelAt::new(None, false);
    simplify_with(&soup, &options, &LocalStep, &mut counting).unwrap();
    assert!(counting.steps >= 2, "{} steps", counting.steps);
    let mut progress = CancelAt::new(None, true);
    let outcome = simplify_with(&soup, &options, &LocalStep, &mut progress);
    assert_eq!(outcome.err(), Some(DriverError::Cancelled));
    // Stopped at the round after the first step, not at the end of the run.
    assert!(progress.steps < counting.steps, "{} steps", progress.steps);
}

#[test]
fn cancelling_at_the_envelopes_stage_stops_before_simplifying() {
    let (soup, options) = job();
    let mut progress = CancelAt::new(Some(Stage::Envelopes), false);
    let outcome = simplify_with(&soup, &options, &LocalStep, &mut progress);
    assert_eq!(outcome.err(), Some(DriverError::Cancelled));
    assert_eq!(progress.stages, vec![Stage::Check, Stage::Envelopes]);
    assert_eq!(progress.steps, 0);
}
