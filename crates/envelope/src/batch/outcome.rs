//! What became of an item: its status and numbers, one line of `summary.jsonl`.

use serde::{Deserialize, Serialize};

/// An item's status.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Written and certified (or certification was not asked for).
    Ok,
    /// The output was made but its certificate found a violation (written as
    /// `*.failed.*` for inspection).
    Violated,
    /// The input cannot be read or is not acceptable (the message names the element).
    BadInput,
    /// Written, but the certificate could not decide every property.
    Undecided,
    /// Anything else: envelopes that could not be proved, outputs that could not be written,
    /// a cancelled run. Only the first is kept as final; the others are retried by the next
    /// run.
    Failed,
}

impl Status {
    /// `"ok"`, `"violated"`, `"bad_input"`, `"undecided"` or `"failed"`.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Violated => "violated",
            Status::BadInput => "bad_input",
            Status::Undecided => "undecided",
            Status::Failed => "failed",
        }
    }

    /// The worse of two statuses (a chain is as good as its worst level).
    pub(crate) fn worse(self, other: Status) -> Status {
        let rank = |s: Status| match s {
            Status::Ok => 0,
            Status::Undecided => 1,
            Status::Violated => 2,
            Status::BadInput => 3,
            Status::Failed => 4,
        };
        if rank(other) > rank(self) {
            other
        } else {
            self
        }
    }
}

/// One item's result: `OUTDIR/<id>/result.json` and its line of `summary.jsonl`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// The item's id.
    pub id: String,
    /// What became of it.
    pub status: Status,
    /// SHA-256 of the program version, the item's parameters and the input's bytes: an item
    /// whose key matches a final result is not run again.
    pub key: String,
    /// The input as the manifest wrote it.
    pub input: String,
    /// Faces of the input (after repair), when it could be read.
    pub input_faces: Option<usize>,
    /// Faces of each output (one, or one per level of a chain).
    pub faces: Vec<usize>,
    /// The absolute epsilon of each output.
    pub epsilon: Vec<f64>,
    /// Certified upper bound of the distance from the outputs to the input (the largest over
    /// the levels), when certified.
    pub approx_to_orig: Option<f64>,
    /// Certified upper bound of the distance from the input to the outputs.
    pub orig_to_approx: Option<f64>,
    /// Output files, in the item's folder.
    pub outputs: Vec<String>,
    /// Wall-clock seconds of the run that made it.
    pub seconds: f64,
    /// Why, when the status is not `ok`.
    pub message: Option<String>,
    /// Whether this run did the work (false: the result of an earlier run was reused).
    #[serde(default, skip_serializing)]
    pub ran: bool,
    /// Whether the status is final (kept by later runs); transient failures are retried.
    #[serde(default, skip_serializing)]
    pub(crate) transient: bool,
}

impl Outcome {
    pub(crate) fn new(id: &str, key: String, input: &str) -> Outcome {
        Outcome {
            id: id.to_string(),
            status: Status::Ok,
            key,
            input: input.to_string(),
            input_faces: None,
            faces: Vec::new(),
            epsilon: Vec::new(),
            approx_to_orig: None,
            orig_to_approx: None,
            outputs: Vec::new(),
            seconds: 0.0,
            message: None,
            ran: true,
            transient: false,
        }
    }

    /// The outcome of an item whose run was lost for good outside the library (an engine's
    /// worker that died every time): `failed`, not final, so the next run tries again.
    #[must_use]
    pub fn lost(item: &super::Item, message: String) -> Outcome {
        let mut o = Outcome::new(&item.id, String::new(), &item.input_as_written);
        o.status = Status::Failed;
        o.message = Some(message);
        o.transient = true;
        o
    }

    /// One line of JSON (no newline).
    #[must_use]
    pub fn to_json_line(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// Whether it is final: kept by later runs (every status but a failure that another run
    /// could avoid: an output that could not be written, a cancellation, a crash).
    #[must_use]
    pub fn is_final(&self) -> bool {
        !self.transient
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_result_line_reads_back() {
        let mut o = Outcome::new("a", "k".into(), "x.off");
        o.status = Status::BadInput;
        o.message = Some("x.off: line 3: ...".into());
        let line = o.to_json_line();
        assert!(line.contains(r#""status":"bad_input""#), "{line}");
        let back: Outcome = serde_json::from_str(&line).unwrap();
        assert_eq!(back.status, Status::BadInput);
        assert!(!back.ran && back.is_final());
        assert_eq!(Status::Ok.worse(Status::Undecided), Status::Undecided);
        assert_eq!(Status::Violated.worse(Status::Undecided), Status::Violated);
    }
}
