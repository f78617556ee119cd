//! The restart journal: what the asset promised, on disk before the ack that promises it. The
//! same file format as the Python runtime's (runtime/rapid_runtime/journal.py, the reference)
//! and the C++ runtime's: text lines `<crc32 of the JSON, 8 hex digits> <JSON object>\n`
//! with records {"k":"q"|"x"|"c","id","src","asset","serial"[,"c","m"]}, {"k":"s","serial"},
//! {"k":"start","serial","t"}, {"k":"stop"}, written as Python's json.dumps(separators=(",",
//! ":"), ensure_ascii=True) writes them. A bridge of any runtime reads the others'.
//!
//! Use (the manager's): note() each step before its ack, sync() before writing the acks of a
//! batch, restore what open() recovered before reading commands, close(true) on a clean stop.
//! A damaged line is skipped; the file is then reported in one log line, renamed
//! `<name>.damaged-<time>-<pid>` and rewritten from the sound lines. Never panics: a journal
//! that cannot be used is reported and open() gives none. A write or sync that fails (a full
//! disk) is logged once until one succeeds again; the asset goes on answering.

use std::collections::VecDeque;
use std::fs::{self, File, OpenOptions};
use std::io::{Read, Write};
use std::os::unix::fs::OpenOptionsExt;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{SystemTime, UNIX_EPOCH};

/// compact once the file holds this many times `window` lines (plus the live ones)
const COMPACT_FACTOR: usize = 4;
/// a journal never grows past a few MB (compaction); a bigger file is set aside unread
const MAX_READ: u64 = 64 * 1024 * 1024;
/// the journal's default folder, before XDG_STATE_HOME
pub const STATE_ENV: &str = "RAPID_STATE_DIR";

pub type Log = Arc<dyn Fn(&str) + Send + Sync>;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JournalEntry {
    pub cmd_id: String,
    pub src_name: String,
    pub asset_name: String,
    pub serial: i64,
    /// 'q' accepted into the queue, 'x' running, 'c' finished
    pub state: char,
    /// "ACK_COMPLETED_OK", ... (state c)
    pub completion: String,
    pub message: String,
}

#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Recovered {
    /// in the order they were accepted
    pub unfinished: Vec<JournalEntry>,
    /// oldest first, the last `window`
    pub finished: Vec<JournalEntry>,
    pub last_serial: i64,
    /// the journal did not end with a clean stop
    pub crashed: bool,
}

/// The configs' serial for this start: `requested` when one was asked for; after a journal
/// that recorded serials, one above the last it recorded (`now`, seconds, unless the clock has
/// not passed it: a restart within the second of the last serial, or a clock set back), so a
/// reader keeping the last config by serial takes the new ones; else None (the caller's
/// default, the start time). As the C++ runtime's restart_serial and the Python bridge.
pub fn restart_serial(requested: Option<i64>, recovered: &Recovered, now: i64) -> Option<i64> {
    if requested.is_some() || recovered.last_serial <= 0 {
        return requested;
    }
    Some(now.max(recovered.last_serial + 1))
}

/// The configs' first serial at a start, as every bridge chooses it: restart_serial's, else
/// `now`; recorded as the start record of `journal` (if any).
pub fn start_serial(requested: Option<i64>, recovered: &Recovered, now: i64, journal: Option<&mut Journal>) -> i64 {
    let serial = restart_serial(requested, recovered, now).unwrap_or(now);
    if let Some(j) = journal {
        j.start(serial);
    }
    serial
}

/// A JSON value of a journal record: the format holds strings and integers only.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Field {
    Str(String),
    Int(i64),
}

pub type Record = Vec<(String, Field)>;

fn get_str<'a>(rec: &'a Record, key: &str) -> Option<&'a str> {
    rec.iter().find(|(k, _)| k == key).and_then(|(_, v)| match v {
        Field::Str(s) => Some(s.as_str()),
        Field::Int(_) => None,
    })
}

fn get_int(rec: &Record, key: &str) -> Option<i64> {
    rec.iter().find(|(k, _)| k == key).and_then(|(_, v)| match v {
        Field::Int(n) => Some(*n),
        Field::Str(_) => None,
    })
}

pub fn crc32(data: &[u8]) -> u32 {
    // zlib's polynomial, reflected
    let mut crc = 0xFFFF_FFFFu32;
    for &b in data {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 { 0xEDB8_8320 ^ (crc >> 1) } else { crc >> 1 };
        }
    }
    crc ^ 0xFFFF_FFFF
}

/// A JSON string as Python's json.dumps(ensure_ascii=True) writes it.
fn quote(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '\u{8}' => out.push_str("\\b"),
            '\u{c}' => out.push_str("\\f"),
            ' '..='~' => out.push(c),
            _ => {
                let mut units = [0u16; 2];
                for u in c.encode_utf16(&mut units) {
                    out.push_str(&format!("\\u{:04x}", u));
                }
            }
        }
    }
    out.push('"');
    out
}

/// One line of the file: the record's JSON (keys in the order given) behind its CRC.
pub fn line_of(rec: &[(&str, Field)]) -> String {
    let body: Vec<String> = rec
        .iter()
        .map(|(k, v)| {
            let value = match v {
                Field::Str(s) => quote(s),
                Field::Int(n) => n.to_string(),
            };
            format!("{}:{}", quote(k), value)
        })
        .collect();
    let json = format!("{{{}}}", body.join(","));
    format!("{:08x} {}\n", crc32(json.as_bytes()), json)
}

/// A flat JSON object of strings and integers (what the journals write); None otherwise.
struct Flat<'a> {
    t: &'a [u8],
    i: usize,
}

impl Flat<'_> {
    fn space(&mut self) {
        while self.i < self.t.len() && matches!(self.t[self.i], b' ' | b'\t') {
            self.i += 1;
        }
    }
    fn eat(&mut self, c: u8) -> bool {
        if self.t.get(self.i) == Some(&c) {
            self.i += 1;
            true
        } else {
            false
        }
    }
    fn hex4(&mut self) -> Option<u32> {
        let s = std::str::from_utf8(self.t.get(self.i..self.i + 4)?).ok()?;
        let v = u32::from_str_radix(s, 16).ok()?;
        self.i += 4;
        Some(v)
    }
    fn string(&mut self) -> Option<String> {
        if !self.eat(b'"') {
            return None;
        }
        let mut out: Vec<u8> = Vec::new();
        while self.i < self.t.len() {
            let c = self.t[self.i];
            self.i += 1;
            match c {
                b'"' => return String::from_utf8(out).ok(),
                0..=0x1f => return None,
                b'\\' => {
                    let e = *self.t.get(self.i)?;
                    self.i += 1;
                    let ch = match e {
                        b'"' => '"',
                        b'\\' => '\\',
                        b'/' => '/',
                        b'b' => '\u{8}',
                        b'f' => '\u{c}',
                        b'n' => '\n',
                        b'r' => '\r',
                        b't' => '\t',
                        b'u' => {
                            let mut cp = self.hex4()?;
                            if (0xD800..0xDC00).contains(&cp) && self.t.get(self.i..self.i + 2) == Some(b"\\u") {
                                let back = self.i;
                                self.i += 2;
                                match self.hex4() {
                                    Some(lo) if (0xDC00..0xE000).contains(&lo) => {
                                        cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00)
                                    }
                                    _ => self.i = back,
                                }
                            }
                            char::from_u32(cp).unwrap_or('\u{fffd}') // a lone surrogate: not UTF-8
                        }
                        _ => return None,
                    };
                    let mut buf = [0u8; 4];
                    out.extend_from_slice(ch.encode_utf8(&mut buf).as_bytes());
                }
                _ => out.push(c),
            }
        }
        None
    }
    fn number(&mut self) -> Option<i64> {
        let start = self.i;
        self.eat(b'-');
        while self.i < self.t.len() && self.t[self.i].is_ascii_digit() {
            self.i += 1;
        }
        std::str::from_utf8(&self.t[start..self.i]).ok()?.parse().ok()
    }
    fn parse(mut self) -> Option<Record> {
        let mut rec = Record::new();
        self.space();
        if !self.eat(b'{') {
            return None;
        }
        self.space();
        if !self.eat(b'}') {
            loop {
                self.space();
                let key = self.string()?;
                self.space();
                if !self.eat(b':') {
                    return None;
                }
                self.space();
                let value = if self.t.get(self.i) == Some(&b'"') {
                    Field::Str(self.string()?)
                } else {
                    Field::Int(self.number()?)
                };
                rec.retain(|(k, _)| *k != key); // (a repeated key: the last one, as json.loads)
                rec.push((key, value));
                self.space();
                if self.eat(b',') {
                    continue;
                }
                if self.eat(b'}') {
                    break;
                }
                return None;
            }
        }
        self.space();
        (self.i == self.t.len()).then_some(rec)
    }
}

/// A sound line's record, or None (wrong CRC, not JSON, wrong shape, no newline).
pub fn parse_line(raw: &[u8]) -> Option<Record> {
    if raw.len() < 11 || raw.last() != Some(&b'\n') || raw[8] != b' ' {
        return None;
    }
    let head = std::str::from_utf8(&raw[..8]).ok()?;
    let want = u32::from_str_radix(head, 16).ok()?;
    let body = &raw[9..raw.len() - 1];
    if want != crc32(body) || !body.is_ascii() {
        return None;
    }
    let rec = Flat { t: body, i: 0 }.parse()?;
    let kind = get_str(&rec, "k")?;
    let ok = match kind {
        "q" | "x" | "c" => {
            ["id", "src", "asset"].iter().all(|f| get_str(&rec, f).is_some())
                && get_int(&rec, "serial").is_some()
                && (kind != "c" || (get_str(&rec, "c").is_some() && get_str(&rec, "m").is_some()))
        }
        "s" => get_int(&rec, "serial").is_some(),
        "start" | "stop" => true,
        _ => false,
    };
    ok.then_some(rec)
}

fn record_of(e: &JournalEntry) -> String {
    let mut rec = vec![
        ("k", Field::Str(e.state.to_string())),
        ("id", Field::Str(e.cmd_id.clone())),
        ("src", Field::Str(e.src_name.clone())),
        ("asset", Field::Str(e.asset_name.clone())),
        ("serial", Field::Int(e.serial)),
    ];
    if e.state == 'c' {
        rec.push(("c", Field::Str(e.completion.clone())));
        rec.push(("m", Field::Str(e.message.clone())));
    }
    line_of(&rec)
}

fn now_s() -> i64 {
    SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs() as i64)
}

/// The local time as %Y%m%dT%H%M%S would print it, in UTC (std has no time zones).
fn stamp() -> String {
    let s = now_s();
    let (days, rest) = (s.div_euclid(86400), s.rem_euclid(86400));
    // civil from days (Howard Hinnant's algorithm)
    let z = days + 719468;
    let era = z.div_euclid(146097);
    let doe = z - era * 146097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}{m:02}{d:02}T{:02}{:02}{:02}", rest / 3600, rest / 60 % 60, rest % 60)
}

fn errno_text(e: &std::io::Error) -> String {
    // "No such file or directory (os error 2)" -> its words, as strerror
    let s = e.to_string();
    s.split(" (os error").next().unwrap_or(&s).to_string()
}

pub struct Journal {
    path: PathBuf,
    file: Option<File>,
    window: usize,
    log: Log,
    /// accepted or running, in order (a few: the queue's)
    live: Vec<JournalEntry>,
    /// the last `window` outcomes, oldest first
    done: VecDeque<JournalEntry>,
    last_serial: i64,
    lines: usize,
    syncs: usize,
    unsynced: bool,
    failing: bool,
}

impl Journal {
    /// $RAPID_STATE_DIR, else $XDG_STATE_HOME/rapid_runtime, else ~/.local/state/rapid_runtime.
    pub fn default_dir() -> PathBuf {
        if let Some(dir) = std::env::var_os(STATE_ENV).filter(|d| !d.is_empty()) {
            return dir.into();
        }
        if let Some(xdg) = std::env::var_os("XDG_STATE_HOME").filter(|d| !d.is_empty()) {
            return PathBuf::from(xdg).join("rapid_runtime");
        }
        let home = std::env::var_os("HOME").unwrap_or_default();
        PathBuf::from(home).join(".local/state/rapid_runtime")
    }

    /// One journal per asset and domain (a test bridge on another domain has its own).
    pub fn file_name(asset: &str, domain: i32) -> String {
        let name: String = asset
            .chars()
            .take(64)
            .map(|c| if c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '-') { c } else { '_' })
            .collect();
        format!("{name}-domain{domain}.journal")
    }

    /// folder/<asset>-domain<N>.journal, locked against another bridge, and what it recovered.
    /// None (said in the log) when it cannot be used.
    pub fn open(folder: &Path, asset: &str, domain: i32, window: usize, log: Log) -> (Option<Journal>, Recovered) {
        let path = folder.join(Journal::file_name(asset, domain));
        let shown = path.display().to_string();
        let file = fs::create_dir_all(folder).and_then(|_| {
            OpenOptions::new().read(true).append(true).create(true).mode(0o600).open(&path)
        });
        let file = match file {
            Ok(f) => f,
            Err(e) => {
                log(&format!(
                    "journal {shown}: cannot be opened ({}); running without one: commands in flight at a crash will have no outcome",
                    errno_text(&e)
                ));
                return (None, Recovered::default());
            }
        };
        if file.try_lock().is_err() {
            log(&format!("journal {shown}: in use by another bridge of this asset and domain; running without one"));
            return (None, Recovered::default());
        }
        let mut j = Journal {
            path,
            file: Some(file),
            window: window.max(1),
            log,
            live: Vec::new(),
            done: VecDeque::new(),
            last_serial: 0,
            lines: 0,
            syncs: 0,
            unsynced: false,
            failing: false,
        };
        match j.recover() {
            Ok(rec) if j.file.is_some() => (Some(j), rec),
            Ok(_) => (None, Recovered::default()),
            Err(e) => {
                (j.log)(&format!("journal {shown}: cannot be read ({}); running without one", errno_text(&e)));
                (None, Recovered::default())
            }
        }
    }

    fn recover(&mut self) -> std::io::Result<Recovered> {
        let mut raw = Vec::new();
        File::open(&self.path)?.take(MAX_READ + 1).read_to_end(&mut raw)?;
        let (mut bad, mut first_bad, mut sound) = (0usize, 0usize, 0usize);
        if raw.len() as u64 > MAX_READ {
            raw.clear();
            bad = 1;
            first_bad = 1;
        }
        let mut last_stop = false;
        for (n, line) in raw.split_inclusive(|b| *b == b'\n').enumerate() {
            let Some(rec) = parse_line(line) else {
                bad += 1;
                if first_bad == 0 {
                    first_bad = n + 1;
                }
                continue;
            };
            sound += 1;
            let k = get_str(&rec, "k").unwrap_or("");
            last_stop = k == "stop";
            if k == "s" || k == "start" {
                if let Some(s) = get_int(&rec, "serial") {
                    self.last_serial = self.last_serial.max(s);
                }
            }
            if matches!(k, "q" | "x" | "c") {
                let s = |f| get_str(&rec, f).unwrap_or("").to_string();
                self.apply(JournalEntry {
                    cmd_id: s("id"),
                    src_name: s("src"),
                    asset_name: s("asset"),
                    serial: get_int(&rec, "serial").unwrap_or(0),
                    state: k.chars().next().unwrap_or('q'),
                    completion: s("c"),
                    message: s("m"),
                });
            }
        }
        let mut out = Recovered { last_serial: self.last_serial, ..Recovered::default() };
        let mut crashed = sound > 0 && !last_stop;
        if bad > 0 {
            let name = self.path.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
            let aside_name = format!("{name}.damaged-{}-{}", stamp(), std::process::id());
            let aside = self.path.with_file_name(&aside_name);
            if let Err(e) = fs::rename(&self.path, &aside) {
                (self.log)(&format!(
                    "journal {}: damaged and cannot be set aside ({}); running without one",
                    self.path.display(),
                    errno_text(&e)
                ));
                self.file = None;
                return Ok(out);
            }
            (self.log)(&format!(
                "journal {}: {bad} damaged line(s) (first: line {first_bad}), set aside as {aside_name}; {sound} sound record(s) kept",
                self.path.display()
            ));
            crashed = true; // whatever it said, its commands are answered again
        }
        if crashed {
            out.crashed = true;
            out.unfinished = self.live.clone();
            out.finished = self.done.iter().cloned().collect();
        } else {
            self.live.clear();
            self.done.clear();
        }
        self.rewrite();
        Ok(out)
    }

    fn apply(&mut self, e: JournalEntry) {
        if e.state == 'c' {
            self.live.retain(|o| o.cmd_id != e.cmd_id);
            self.done.retain(|o| o.cmd_id != e.cmd_id);
            self.done.push_back(e);
            while self.done.len() > self.window {
                self.done.pop_front();
            }
        } else if let Some(o) = self.live.iter_mut().find(|o| o.cmd_id == e.cmd_id) {
            *o = e;
        } else {
            self.live.push(e);
        }
    }

    fn failed(&mut self, what: &str, e: &std::io::Error) {
        if !self.failing {
            self.failing = true;
            (self.log)(&format!(
                "journal {}: {what} ({}): a crash now would leave commands without an outcome",
                self.path.display(),
                errno_text(e)
            ));
        }
    }

    fn append(&mut self, line: &str) {
        // O_APPEND: a kill -9 loses nothing written; a power cut, what was not synced
        let Some(file) = self.file.as_mut() else { return };
        if let Err(e) = file.write_all(line.as_bytes()) {
            self.failed("a record not written", &e);
        }
        self.lines += 1;
        self.unsynced = true;
    }

    pub fn start(&mut self, serial: i64) {
        self.append(&line_of(&[("k", Field::Str("start".into())), ("serial", Field::Int(serial)), ("t", Field::Int(now_s()))]));
        self.last_serial = self.last_serial.max(serial);
    }

    /// A config serial issued: recorded when above the last one recorded.
    pub fn serial(&mut self, serial: i64) {
        if serial > self.last_serial {
            self.last_serial = serial;
            self.append(&line_of(&[("k", Field::Str("s".into())), ("serial", Field::Int(serial))]));
        }
    }

    /// The command's step (q, x or c) before its ack; a repeated step (progress acks, REQUEUED
    /// then EXECUTING again) is not written again.
    pub fn note(&mut self, entry: JournalEntry) {
        if entry.state != 'c' {
            if let Some(o) = self.live.iter().find(|o| o.cmd_id == entry.cmd_id) {
                if o.state == entry.state || o.state == 'x' {
                    return;
                }
            }
        }
        let line = record_of(&entry);
        self.apply(entry);
        self.append(&line);
    }

    /// Make what was written durable (before the acks that promise it); compacts when due.
    /// False (logged once) when the disk refused.
    pub fn sync(&mut self) -> bool {
        if !self.unsynced {
            return true;
        }
        let Some(file) = self.file.as_ref() else { return true };
        if let Err(e) = file.sync_data() {
            self.failed("not synced", &e);
            return false;
        }
        self.failing = false;
        self.unsynced = false;
        self.syncs += 1;
        if self.lines > COMPACT_FACTOR * self.window + self.live.len() + 16 {
            self.rewrite();
        }
        true
    }

    /// clean: every command was answered; the next start begins afresh.
    pub fn close(mut self, clean: bool) {
        if clean {
            self.append(&line_of(&[("k", Field::Str("stop".into()))]));
        }
        if let Some(f) = self.file.take() {
            let _ = f.sync_data();
        }
    }

    /// Compaction: the serial, the last `window` outcomes and the live commands in a new file,
    /// fsynced, renamed over the journal, the folder fsynced; the lock moves to the new file.
    fn rewrite(&mut self) {
        let mut data = String::new();
        let mut count = 0;
        if self.last_serial != 0 {
            data += &line_of(&[("k", Field::Str("s".into())), ("serial", Field::Int(self.last_serial))]);
            count += 1;
        }
        for e in self.done.iter().chain(self.live.iter()) {
            data += &record_of(e);
            count += 1;
        }
        let tmp = self.path.with_file_name(format!(
            "{}.new",
            self.path.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default()
        ));
        let written = (|| -> std::io::Result<File> {
            let _ = fs::remove_file(&tmp); // (a compaction cut short earlier)
            let mut f = OpenOptions::new().append(true).create_new(true).mode(0o600).open(&tmp)?;
            f.try_lock().map_err(|_| std::io::Error::from(std::io::ErrorKind::WouldBlock))?;
            f.write_all(data.as_bytes())?;
            f.sync_all()?;
            fs::rename(&tmp, &self.path)?;
            Ok(f)
        })();
        match written {
            Ok(f) => {
                if let Some(dir) = self.path.parent().and_then(|d| File::open(d).ok()) {
                    let _ = dir.sync_all();
                }
                self.file = Some(f);
                self.lines = count;
                self.unsynced = false;
            }
            Err(e) => (self.log)(&format!("journal {}: not compacted ({})", self.path.display(), errno_text(&e))),
        }
    }

    pub fn path(&self) -> &Path {
        &self.path
    }
    pub fn lines(&self) -> usize {
        self.lines
    }
    /// fdatasyncs done by sync() (one per batch)
    pub fn syncs(&self) -> usize {
        self.syncs
    }
    pub fn unsynced(&self) -> bool {
        self.unsynced
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_as_python_writes_them() {
        // zlib.crc32(b'{"k":"stop"}') and json.dumps's escapes
        let line = line_of(&[("k", Field::Str("stop".into()))]);
        assert_eq!(line, format!("{:08x} {{\"k\":\"stop\"}}\n", crc32(b"{\"k\":\"stop\"}")));
        assert_eq!(crc32(b"123456789"), 0xCBF43926);
        assert_eq!(quote("é\"\u{1F600}\u{7f}\u{8}\u{1}"), "\"\\u00e9\\\"\\ud83d\\ude00\\u007f\\b\\u0001\"");
        let rec = parse_line(line_of(&[("k", Field::Str("c".into())), ("id", Field::Str("a\u{1F600}".into())),
            ("src", Field::Str("s".into())), ("asset", Field::Str("A".into())), ("serial", Field::Int(-3)),
            ("c", Field::Str("ACK_COMPLETED_OK".into())), ("m", Field::Str("x\ny".into()))]).as_bytes()).unwrap();
        assert_eq!(get_str(&rec, "id"), Some("a\u{1F600}"));
        assert_eq!(get_str(&rec, "m"), Some("x\ny"));
        assert_eq!(get_int(&rec, "serial"), Some(-3));
        assert!(parse_line(b"00000000 {\"k\":\"stop\"}\n").is_none());
    }

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("rapid-journal-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        dir
    }

    fn logs() -> (Log, Arc<std::sync::Mutex<Vec<String>>>) {
        let seen = Arc::new(std::sync::Mutex::new(Vec::new()));
        let s = seen.clone();
        (Arc::new(move |t: &str| s.lock().unwrap().push(t.to_string())), seen)
    }

    fn entry(id: &str, state: char) -> JournalEntry {
        let c = state == 'c';
        JournalEntry {
            cmd_id: id.into(),
            src_name: "src".into(),
            asset_name: "A".into(),
            serial: 1,
            state,
            completion: if c { "ACK_COMPLETED_OK".into() } else { String::new() },
            message: if c { "fine".into() } else { String::new() },
        }
    }

    #[test]
    fn a_crash_is_recovered_a_clean_stop_is_not_and_the_file_is_locked() {
        let dir = folder("crash");
        let (log, seen) = logs();
        let (j, _) = Journal::open(&dir, "A", 1, 4, log.clone());
        let mut j = j.unwrap();
        j.start(7);
        j.note(entry("a", 'q'));
        j.note(entry("b", 'q'));
        j.note(entry("b", 'x'));
        j.note(entry("b", 'x')); // (progress: not written again)
        j.note(entry("c", 'q'));
        j.note(entry("c", 'c'));
        assert!(j.sync());
        assert_eq!(j.lines(), 6);
        let (other, _) = Journal::open(&dir, "A", 1, 4, log.clone());
        assert!(other.is_none() && seen.lock().unwrap().last().unwrap().contains("in use by another bridge"));
        drop(j); // killed: no stop record
        let (j, rec) = Journal::open(&dir, "A", 1, 4, log.clone());
        assert!(rec.crashed);
        assert_eq!(rec.last_serial, 7);
        let states: Vec<(String, char)> = rec.unfinished.iter().map(|e| (e.cmd_id.clone(), e.state)).collect();
        assert_eq!(states, [("a".to_string(), 'q'), ("b".to_string(), 'x')]);
        assert_eq!(rec.finished, [entry("c", 'c')]);
        j.unwrap().close(true);
        let (_, rec) = Journal::open(&dir, "A", 1, 4, log);
        assert!(!rec.crashed && rec.unfinished.is_empty() && rec.last_serial == 7);
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn damaged_lines_are_set_aside_and_the_sound_ones_kept() {
        let dir = folder("damaged");
        let (log, seen) = logs();
        let (j, _) = Journal::open(&dir, "A", 1, 4, log.clone());
        let mut j = j.unwrap();
        j.note(entry("a", 'q'));
        j.sync();
        let path = j.path().to_path_buf();
        drop(j);
        let mut f = OpenOptions::new().append(true).open(&path).unwrap();
        f.write_all(b"00000000 {\"k\":\"q\"}\n{torn").unwrap();
        drop(f);
        let (j, rec) = Journal::open(&dir, "A", 1, 4, log);
        assert!(j.is_some() && rec.crashed);
        assert_eq!(rec.unfinished, [entry("a", 'q')]);
        let said = seen.lock().unwrap().join("\n");
        assert!(said.contains("2 damaged line(s) (first: line 2)") && said.contains("1 sound record(s) kept"), "{said}");
        let aside = fs::read_dir(&dir).unwrap().filter(|e| {
            e.as_ref().unwrap().file_name().to_string_lossy().contains(".damaged-")
        });
        assert_eq!(aside.count(), 1);
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_file_is_compacted_to_the_window() {
        let dir = folder("compact");
        let (log, _) = logs();
        let (j, _) = Journal::open(&dir, "A", 1, 2, log.clone());
        let mut j = j.unwrap();
        for n in 0..200 {
            let id = format!("c{n}");
            j.note(entry(&id, 'x'));
            j.note(entry(&id, 'c'));
            j.sync();
        }
        assert!(j.lines() <= 4 * 2 + 16 + 2, "{} lines", j.lines());
        drop(j);
        let (_, rec) = Journal::open(&dir, "A", 1, 2, log);
        let ids: Vec<&str> = rec.finished.iter().map(|e| e.cmd_id.as_str()).collect();
        assert_eq!(ids, ["c198", "c199"]);
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn configs_come_back_above_the_highest_serial_recorded() {
        let dir = folder("serials");
        let (log, _) = logs();
        let now = 1000;
        {
            let (j, rec) = Journal::open(&dir, "A", 1, 64, log.clone());
            let mut j = j.unwrap();
            j.start(restart_serial(None, &rec, now).unwrap_or(now));
            j.serial(1001);
            j.serial(1002); // less than a second after the start
            j.sync();
            j.close(false); // a crash: no stop record
        }
        let (_, rec) = Journal::open(&dir, "A", 1, 64, log);
        assert_eq!(rec.last_serial, 1002);
        assert_eq!(restart_serial(None, &rec, now), Some(1003)); // the clock has not moved past it
        assert_eq!(restart_serial(None, &rec, 5000), Some(5000));
        assert_eq!(restart_serial(Some(42), &rec, 5000), Some(42)); // asked for: kept
        assert_eq!(restart_serial(Some(0), &rec, 5000), Some(0));
        assert_eq!(restart_serial(None, &Recovered::default(), 5000), None); // no journal: the start time
        let _ = fs::remove_dir_all(&dir);
    }
}
