//! No panic reaches the user: a failure inside one input's work becomes that input's `error:`
//! line, and a batch finishes its other inputs before reporting it.
//!
//! Validation (`scene::SceneLimits`) keeps the inputs we know of away from the collision library's
//! and rasteriser's limits; this is the net under what validation does not know yet. It does not
//! retry, and it does not hide the failure: the exit status is 2, as for any bad input.

use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

/// Replaces the default panic message (several lines on stderr) by a debug log line: the error
/// line the caller prints is the message.
pub fn quiet_panics() {
    std::panic::set_hook(Box::new(|info| tracing::debug!("panic: {info}")));
}

/// The text of a panic's payload.
pub fn panic_message(payload: &(dyn Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic".to_string()
    }
}

/// Runs `work` on behalf of `input`; a panic inside it becomes `<input>: internal error: <what>`.
pub fn guarded<T>(input: &Path, work: impl FnOnce() -> anyhow::Result<T>) -> anyhow::Result<T> {
    catch_unwind(AssertUnwindSafe(work)).unwrap_or_else(|payload| {
        Err(anyhow::anyhow!("{}: internal error: {}", input.display(), panic_message(payload.as_ref())))
    })
}

/// Every result, or the first failure in input order once all are done.
pub fn all_or_first_error<T>(results: Vec<anyhow::Result<T>>) -> anyhow::Result<Vec<T>> {
    results.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_an_error_naming_the_input() {
        quiet_panics();
        let r: anyhow::Result<()> = guarded(Path::new("rooms/a.json"), || panic!("GJK did not converge"));
        assert_eq!(r.unwrap_err().to_string(), "rooms/a.json: internal error: GJK did not converge");
        let n = 3;
        let r: anyhow::Result<()> = guarded(Path::new("b.json"), || panic!("index {n} out of range"));
        assert_eq!(r.unwrap_err().to_string(), "b.json: internal error: index 3 out of range");
        assert_eq!(guarded(Path::new("c.json"), || Ok(7)).unwrap(), 7);
    }

    #[test]
    fn a_batch_reports_its_first_failure_in_input_order() {
        let results = vec![Ok(1), Err(anyhow::anyhow!("b.json: bad")), Err(anyhow::anyhow!("c.json: bad"))];
        assert_eq!(all_or_first_error(results).unwrap_err().to_string(), "b.json: bad");
        assert_eq!(all_or_first_error(vec![Ok(1), Ok(2)]).unwrap(), vec![1, 2]);
    }
}
