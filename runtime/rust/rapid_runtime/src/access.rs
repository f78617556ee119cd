//! Who may command the asset (docs/runtime.md, "Access control"), two gates:
//! - the descriptor's allow-list (`access_control`): which cmdSrc may send which
//!   `Subsystem/command`, checked on every command;
//! - the controller (assets with an AccessControl subsystem): only the source holding control
//!   may command, except AccessControl's own commands and the asset itself.
//!
//! Mobility/stopAllMotion passes both: stopping is always allowed.

use crate::tables::AccessSpec;
use crate::texts;

/// AccessControlState.requestors is a String32Sequence16.
pub const MAX_REQUESTORS: usize = 16;

pub fn always_allowed(type_name: &str, command: &str) -> bool {
    type_name == "Mobility" && command == "stopAllMotion"
}

fn matches(pattern: &str, subsystem: &str, command: &str) -> bool {
    if pattern == "*" {
        return true;
    }
    let (sub, cmd) = pattern.split_once('/').unwrap_or((pattern, ""));
    (sub == "*" || sub == subsystem) && (cmd == "*" || cmd == command)
}

/// The allow-list's answer; no access_control section allows every source.
pub fn allowed(spec: Option<&AccessSpec>, source: &str, subsystem: &str, command: &str) -> bool {
    let Some(spec) = spec else { return true };
    let mut rules = spec.rules.iter().filter(|r| r.source == source).peekable();
    if rules.peek().is_none() {
        return spec.allow_by_default;
    }
    rules.any(|r| r.allow.iter().any(|p| matches(p, subsystem, command)))
}

/// The controller and the queue of requestors. Each operation returns Ok(what happened) or
/// Err(why it failed: EXEC_FAILED).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Control {
    pub controller: String,
    pub requestors: Vec<String>,
}

impl Control {
    pub fn holds(&self, source: &str) -> bool {
        !self.controller.is_empty() && source == self.controller
    }

    pub fn request(&mut self, source: &str) -> Result<String, String> {
        if self.controller.is_empty() || self.controller == source {
            self.give(source);
            return Ok(texts::control_granted(source));
        }
        if self.requestors.iter().any(|r| r == source) {
            return Ok(texts::request_already_queued(&self.controller));
        }
        if self.requestors.len() >= MAX_REQUESTORS {
            return Err(texts::requests_full(MAX_REQUESTORS));
        }
        self.requestors.push(source.into());
        Ok(texts::request_queued(&self.controller))
    }

    pub fn grab(&mut self, source: &str) -> Result<String, String> {
        let before = std::mem::take(&mut self.controller);
        self.give(source);
        Ok(if before.is_empty() || before == source {
            texts::CONTROL_TAKEN.to_string()
        } else {
            texts::control_taken_from(&before)
        })
    }

    pub fn release(&mut self, source: &str) -> Result<String, String> {
        if !self.holds(source) {
            return Err(texts::no_control(source));
        }
        self.controller = if self.requestors.is_empty() { String::new() } else { self.requestors.remove(0) };
        Ok(if self.controller.is_empty() {
            texts::CONTROL_RELEASED.to_string()
        } else {
            texts::control_released_to(&self.controller)
        })
    }

    pub fn transfer(&mut self, source: &str, new: &str) -> Result<String, String> {
        if !self.holds(source) {
            return Err(texts::no_control(source));
        }
        if new.trim().is_empty() {
            return Err(texts::NEW_CONTROLLER_EMPTY.into());
        }
        if new.len() > 31 {
            return Err(texts::NEW_CONTROLLER_TOO_LONG.into());
        }
        self.give(new);
        Ok(texts::control_transferred(new))
    }

    fn give(&mut self, source: &str) {
        self.controller = source.into();
        self.requestors.retain(|r| r != source);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tables::AccessRule;

    #[test]
    fn allow_list_patterns() {
        let spec = AccessSpec {
            allow_by_default: false,
            rules: vec![AccessRule { source: "A".into(), allow: vec!["PanCam/*".into(), "*/echo".into()] }],
        };
        assert!(allowed(Some(&spec), "A", "PanCam", "x"));
        assert!(allowed(Some(&spec), "A", "Admin", "echo"));
        assert!(!allowed(Some(&spec), "A", "Admin", "noOp"));
        assert!(!allowed(Some(&spec), "B", "PanCam", "x"));
        assert!(allowed(None, "B", "PanCam", "x"));
    }

    #[test]
    fn control_moves() {
        let mut c = Control::default();
        assert_eq!(c.request("A").unwrap(), "control granted to A");
        assert_eq!(c.request("B").unwrap(), "request queued; A has control");
        assert!(c.release("B").is_err());
        assert_eq!(c.release("A").unwrap(), "control released to B");
        assert_eq!(c.grab("A").unwrap(), "control taken from B");
        assert_eq!(c.transfer("A", " ").unwrap_err(), "newController is empty");
    }
}
