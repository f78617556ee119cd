//! Config serials (docs/runtime.md, "Configs"): every config starts with the start serial
//! (the start time in seconds, or `journal::restart_serial`'s after a crash); a config
//! published again with other content gets a new serial, larger than any given out before
//! (the next second, or the clock when it has passed that), and the same content keeps its
//! serial. Samples and states carry their config's serial (`of`). As the Python runtime's
//! configs.Serials and the C++ runtime's Serials.

use std::collections::BTreeMap;
use std::time::{SystemTime, UNIX_EPOCH};

/// Seconds since the epoch, the default clock.
pub fn now_seconds() -> i64 {
    SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs() as i64)
}

pub struct Serials {
    start: i32,
    last: i32,
    /// topic -> (its content as last published, its serial)
    topics: BTreeMap<String, (Vec<u8>, i32)>,
    now: Box<dyn Fn() -> i64 + Send>,
    /// told of every serial given out, the start one first (the restart journal records
    /// the highest: a restarted bridge's serials are larger)
    issued: Option<Box<dyn FnMut(i32) + Send>>,
}

impl Serials {
    /// start: the first serial (None: now). Header.serial is 32 bits.
    pub fn new(start: Option<i64>, now: Box<dyn Fn() -> i64 + Send>, mut issued: Option<Box<dyn FnMut(i32) + Send>>) -> Serials {
        let start = start.unwrap_or_else(&now) as i32;
        if let Some(f) = issued.as_mut() {
            f(start);
        }
        Serials { start, last: start, topics: BTreeMap::new(), now, issued }
    }

    pub fn start(&self) -> i32 {
        self.start
    }

    /// The serial of the topic's config (the start serial before it was published).
    pub fn of(&self, topic: &str) -> i32 {
        self.topics.get(topic).map_or(self.start, |(_, s)| *s)
    }

    /// (serial, changed): a new serial only when the content differs from the last one.
    pub fn update(&mut self, topic: &str, content: &[u8]) -> (i32, bool) {
        if let Some((old, serial)) = self.topics.get(topic) {
            if old.as_slice() == content {
                return (*serial, false);
            }
            self.last = (self.last + 1).max((self.now)() as i32);
        }
        self.topics.insert(topic.to_string(), (content.to_vec(), self.last));
        if let Some(f) = self.issued.as_mut() {
            f(self.last);
        }
        (self.last, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::journal::{restart_serial, Journal, Log};
    use std::sync::atomic::{AtomicI64, Ordering};
    use std::sync::{Arc, Mutex};

    fn clock(at: &Arc<AtomicI64>) -> Box<dyn Fn() -> i64 + Send> {
        let at = at.clone();
        Box::new(move || at.load(Ordering::SeqCst))
    }

    #[test]
    fn a_serial_changes_with_the_content_only() {
        let at = Arc::new(AtomicI64::new(1000));
        let seen = Arc::new(Mutex::new(Vec::new()));
        let s2 = seen.clone();
        let mut s = Serials::new(None, clock(&at), Some(Box::new(move |n| s2.lock().unwrap().push(n))));
        assert_eq!((s.start(), s.of("cfg")), (1000, 1000));
        assert_eq!(s.update("cfg", b"a"), (1000, true)); // the first content: the start serial
        assert_eq!(s.update("other", b"x"), (1000, true));
        assert_eq!(s.update("cfg", b"a"), (1000, false)); // the same content keeps its serial
        assert_eq!(s.update("cfg", b"b"), (1001, true)); // within the second: the next one
        assert_eq!(s.update("cfg", b"c"), (1002, true));
        assert_eq!(s.of("other"), 1000);
        at.store(5000, Ordering::SeqCst);
        assert_eq!(s.update("other", b"y"), (5000, true)); // the clock passed it
        assert_eq!(s.update("cfg", b"c"), (1002, false));
        at.store(10, Ordering::SeqCst); // a clock set back: still larger
        assert_eq!(s.update("cfg", b"d"), (5001, true));
        assert_eq!(*seen.lock().unwrap(), [1000, 1000, 1000, 1001, 1002, 5000, 5001]);
        assert_eq!(Serials::new(Some(42), clock(&at), None).start(), 42);
    }

    #[test]
    fn a_restart_comes_back_above_the_serials_issued() {
        let dir = std::env::temp_dir().join(format!("rapid-serials-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let log: Log = Arc::new(|_: &str| {});
        let at = Arc::new(AtomicI64::new(1000));
        {
            let (j, rec) = Journal::open(&dir, "A", 1, 64, log.clone());
            let j = Arc::new(Mutex::new(j.unwrap()));
            let j2 = j.clone();
            let mut s = Serials::new(restart_serial(None, &rec, 1000), clock(&at),
                                     Some(Box::new(move |n| j2.lock().unwrap().serial(n as i64))));
            j.lock().unwrap().start(s.start() as i64);
            s.update("cfg", b"a");
            s.update("cfg", b"b"); // 1001
            s.update("cfg", b"c"); // 1002, less than a second after the start
            j.lock().unwrap().sync();
        } // a crash: no stop record
        let (_, rec) = Journal::open(&dir, "A", 1, 64, log);
        assert_eq!(rec.last_serial, 1002);
        let s = Serials::new(restart_serial(None, &rec, 1000), clock(&at), None);
        assert_eq!(s.start(), 1003);
        let _ = std::fs::remove_dir_all(&dir);
    }

    struct Quiet;
    impl crate::Outbox for Quiet {
        fn ack(&self, _: &crate::Cmd, _: crate::AckStatus, _: crate::Completion, _: &str) {}
        fn queue_state(&self, _: i32, _: &[crate::Record], _: &[crate::Record], _: &[crate::Record]) {}
        fn access_state(&self, _: &str, _: &[String]) {}
        fn retire(&self, _: &crate::Cmd) {}
        fn log(&self, _: &str) {}
    }
    struct Idle;
    impl crate::Handlers for Idle {
        fn execute(&self, _: &crate::Context) -> crate::Outcome {
            crate::Outcome::Ok(String::new())
        }
    }

    #[test]
    fn a_serial_issued_while_running_is_in_the_managers_journal() {
        // (the Rust bridge's republished configs: the journal is the manager's by then)
        let dir = std::env::temp_dir().join(format!("rapid-serials-manager-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let log: Log = Arc::new(|_: &str| {});
        let (j, _) = Journal::open(&dir, "A", 1, 64, log.clone());
        let mut j = j.unwrap();
        j.start(1000);
        let options = crate::Options { journal: Some(j), ..Default::default() };
        let m = crate::CommandManager::new(Arc::new(crate::Tables::default()), Arc::new(Idle), Arc::new(Quiet), options).unwrap();
        m.journal_serial(1500);
        m.journal_serial(1200); // below the last one: nothing to record
        drop(m.release_journal()); // a crash: no stop record
        let (_, rec) = Journal::open(&dir, "A", 1, 64, log);
        assert_eq!(rec.last_serial, 1500);
        assert_eq!(restart_serial(None, &rec, 1000), Some(1501));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
