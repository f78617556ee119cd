//! `<crate>_cmd`, the ground-side program of a generated bridge crate, on the client
//! (client.rs): the command line, output and exit statuses of the C++ runtime's rapid_cmd
//! (runtime/cpp/dds/src/cmd.cpp) and `rapidgen cmd`, so their runs compare line by line:
//!
//!   <crate>_cmd [options] SUBSYSTEM COMMAND [key=value ...]
//!
//! A header line (`K10Red <- Admin/echo text='hi'  [cmdId ..., QUEUE_BYPASS, from NAME]`),
//! then one line per ack as it comes (`  EXECUTING`, `  COMPLETED OK  hi`); after a DELETE,
//! `target ID:` and the target's acks. Exit 0 on COMPLETED/OK, 1 otherwise (a refused
//! command, no asset, no final ack), 2 for a usage error.
use std::time::{Duration, Instant};

use rapid_runtime::text::visible;
use rapid_runtime::value::{fmt_g, py_float};
use rapid_runtime::{QueueAction, Tables, Value};

use crate::client::{AckEvent, Client, ClientError, ClientOptions, SendOptions};
use crate::dds::use_transport;
use crate::tables_json;

/// What the generated crate gives the program.
pub struct CmdProgram {
    /// the asset's tables (the bridge's tables.rs): the dictionary until the live one is
    /// read, and the limits, units and defaults the CommandConfig does not carry
    pub tables_json: &'static str,
    /// transport name -> Cyclone DDS XML (the bridge's transports.rs)
    pub transports: &'static [(&'static str, &'static str)],
}

const USAGE: &str = "[options] SUBSYSTEM COMMAND [key=value ...]

Send a command to a live RAPID asset, arguments by name, checked against its dictionary;
print its acks. Exit 0 on COMPLETED/OK, else 1 (2: usage).
  --asset NAME        the asset (default: the built-in tables')
  --partition P       its DDS partition (default: its own)
  --domain N          DDS domain (default: the asset's)
  --transport NAME    local (loopback only, default), lan, wan: the bridge's Cyclone
                      configurations, used when CYCLONEDDS_URI is not set
  --source NAME       cmdSrc and srcName (default rapid_cmd)
  --action A          BYPASS (default), APPEND, INSERT, REPLACE, DELETE
  --target CMDID      the queued command INSERT, REPLACE or DELETE acts on
  --id CMDID          this command's cmdId (default: a fresh one)
  --timeout S         seconds to wait for the asset, then for completion (default 30)
  --discover S        seconds to wait for the live CommandConfig (default 2)
  --rtt S             the link's round trip (0..600): the waits grow by 2 of them for
                      an answer, 6 for finding the asset and its CommandConfig
  --no-check          send values outside their range or allowed values
  --no-wait           return after the first ack
  --repeat N          benchmark: N commands one after the other; JSON latency figures";

// A command lost at first contact (the writer matched the asset's reader before that reader
// knew the writer: a volatile reader need not deliver what was written before) is sent again
// with the same cmdId when no ack at all came UNANSWERED s after the send, at most
// MAX_RESENDS times, as the other clients do (rapidgen/cmd/recover.py); a RAPID asset answers
// at once and drops a repeated cmdId.
const UNANSWERED: f64 = 5.0;
const MAX_RESENDS: u32 = 3;

// As `rapidgen cmd --rtt` (rapidgen/cmd/timing.py): a loopback wait over a link grows by what
// the link costs: an answer a round trip, a lost packet's repair another; a late joiner's
// first durable sample (participants, endpoints, request, history, one loss) 6.
const ANSWER_TRIPS: f64 = 2.0;
const DISCOVERY_TRIPS: f64 = 6.0;
const MAX_RTT: f64 = 600.0;

fn allow(seconds: f64, rtt: f64, trips: f64) -> f64 {
    seconds + trips * rtt
}

struct Args {
    asset: String,
    partition: String,
    transport: String,
    source: String,
    target: String,
    id: String,
    domain: Option<u32>,
    action: QueueAction,
    timeout: f64,
    discover: f64,
    rtt: f64,
    no_check: bool,
    no_wait: bool,
    repeat: u64,
    words: Vec<String>,
}

fn action_of(text: &str) -> Option<QueueAction> {
    let up = text.to_ascii_uppercase();
    let name = up.strip_prefix("QUEUE_").unwrap_or(&up);
    QueueAction::from_name(&format!("QUEUE_{name}"))
}

fn seconds(text: &str, zero_ok: bool) -> Option<f64> {
    text.parse::<f64>().ok().filter(|x| x.is_finite() && (*x > 0.0 || (zero_ok && *x == 0.0)))
}

/// The arguments; None for --help.
fn parse(argv: &[String]) -> Result<Option<Args>, String> {
    let mut a = Args {
        asset: String::new(),
        partition: String::new(),
        transport: "local".into(),
        source: "rapid_cmd".into(),
        target: String::new(),
        id: String::new(),
        domain: None,
        action: QueueAction::Bypass,
        timeout: 30.0,
        discover: 2.0,
        rtt: 0.0,
        no_check: false,
        no_wait: false,
        repeat: 0,
        words: Vec::new(),
    };
    let mut it = argv.iter().skip(1);
    while let Some(key) = it.next() {
        match key.as_str() {
            "-h" | "--help" => return Ok(None),
            "--no-check" => a.no_check = true,
            "--no-wait" => a.no_wait = true,
            k if !k.starts_with("--") => a.words.push(key.clone()),
            k => {
                let value = it.next().ok_or(format!("{} needs a value", visible(k, 64)))?.clone();
                let bad = || format!("bad value for {k}: {}", visible(&value, 64));
                match k {
                    "--asset" => a.asset = Some(value.clone()).filter(|v| !v.is_empty()).ok_or_else(bad)?,
                    "--partition" => a.partition = Some(value.clone()).filter(|v| !v.is_empty()).ok_or_else(bad)?,
                    "--transport" => a.transport = Some(value.clone()).filter(|v| !v.is_empty()).ok_or_else(bad)?,
                    "--source" => a.source = Some(value.clone()).filter(|v| !v.is_empty()).ok_or_else(bad)?,
                    "--id" => a.id = Some(value.clone()).filter(|v| !v.is_empty()).ok_or_else(bad)?,
                    "--target" => a.target = value.clone(),
                    "--domain" => a.domain = Some(value.parse().ok().filter(|d| *d <= 232).ok_or_else(bad)?),
                    "--timeout" => a.timeout = seconds(&value, false).ok_or_else(bad)?,
                    "--discover" => a.discover = seconds(&value, true).ok_or_else(bad)?,
                    "--rtt" => a.rtt = seconds(&value, true).filter(|r| *r <= MAX_RTT).ok_or_else(bad)?,
                    "--action" => a.action = action_of(&value).ok_or_else(bad)?,
                    "--repeat" => a.repeat = value.parse().ok().filter(|n| *n > 0).ok_or_else(bad)?,
                    _ => return Err(format!("unknown option {}", visible(k, 64))),
                }
            }
        }
    }
    if a.words.len() < 2 {
        return Err("SUBSYSTEM and COMMAND are needed".into());
    }
    Ok(Some(a))
}

/// A value as the header line shows it (as rapid_cmd: numbers as %g, strings quoted).
fn shown(v: &Value) -> String {
    let list = |xs: &mut dyn Iterator<Item = f64>| xs.map(fmt_g).collect::<Vec<_>>().join(",");
    match v {
        Value::Bool(b) => b.to_string(),
        Value::String(s) => format!("'{}'", visible(s, 64)),
        Value::Vec3d(x) => list(&mut x.iter().copied()),
        Value::Mat33f(m) => list(&mut m.iter().map(|x| *x as f64)),
        // a float as the shortest text that reads back as that float (0.2, not 0.2000000029...)
        Value::Float(x) => py_float(x.to_string().parse().unwrap_or(*x as f64)),
        other => other.repr(),
    }
}

fn secs(s: f64) -> Duration {
    Duration::from_secs_f64(s)
}

/// cmd_id's acks printed as they come, until the final one (or the first, with
/// `first_only`), or `timeout`. `resend`: the command to send again when unanswered.
fn follow(client: &Client, cmd_id: &str, timeout: Duration, first_only: bool, resend: Option<(&rapid_runtime::Cmd, Duration)>) -> Vec<AckEvent> {
    let mut end = Instant::now() + timeout;
    let mut sent = Instant::now();
    let mut resends = 0;
    let mut printed = 0;
    loop {
        let slice = end.saturating_duration_since(Instant::now()).min(Duration::from_millis(250));
        let acks = client.wait_count(cmd_id, printed + 1, slice);
        for a in &acks[printed..] {
            println!("  {}", a.describe());
        }
        printed = acks.len();
        if !acks.is_empty() && (first_only || acks.iter().any(AckEvent::is_final)) {
            return acks;
        }
        let now = Instant::now();
        if let Some((cmd, unanswered)) = resend {
            if acks.is_empty() && resends < MAX_RESENDS && now - sent >= unanswered && client.asset_matched() {
                resends += 1;
                sent = now;
                end = end.max(now + timeout);
                eprintln!("rapid_cmd: {} has not answered within {} s: the command did not reach it; sending it \
                           again with the same cmdId ({resends} of {MAX_RESENDS})", visible(client.asset(), 64),
                          fmt_g(unanswered.as_secs_f64()));
                if let Err(e) = client.send_raw(cmd.clone()) {
                    eprintln!("rapid_cmd: {e}");
                }
            }
        }
        if now >= end {
            return acks;
        }
    }
}

/// The program: the exit status.
pub fn main(program: CmdProgram) -> i32 {
    let argv: Vec<String> = std::env::args().collect();
    let prog = argv.first().cloned().unwrap_or_else(|| "rapid_cmd".into());
    match parse(&argv) {
        Ok(None) => {
            println!("usage: {prog} {USAGE}");
            0
        }
        Err(e) => {
            eprintln!("{prog}: {e}\nusage: {prog} {USAGE}");
            2
        }
        Ok(Some(a)) => match run(&program, &a) {
            Ok(code) => code,
            Err(ClientError::Refused(e)) => {
                eprintln!("rapid_cmd: error: {e}");
                1
            }
            Err(ClientError::Dds(e)) => {
                eprintln!("{prog}: {e}");
                1
            }
        },
    }
}

fn run(program: &CmdProgram, a: &Args) -> Result<i32, ClientError> {
    if !program.transports.iter().any(|(n, _)| *n == a.transport) && !program.transports.is_empty() {
        let names: Vec<&str> = program.transports.iter().map(|(n, _)| *n).collect();
        return Err(ClientError::Refused(format!("--transport {}: one of {}", visible(&a.transport, 64), names.join(", "))));
    }
    use_transport(program.transports, &a.transport);
    let json: serde_json::Value = serde_json::from_str(program.tables_json)
        .map_err(|e| ClientError::Dds(format!("the built-in tables: {e}")))?;
    let tables: Tables = tables_json::asset_of(&json).map_err(|e| ClientError::Dds(format!("the built-in tables: {e}")))?.tables;
    let own = a.asset.is_empty() || a.asset == tables.name; // else another asset: no built-in dictionary
    let options = ClientOptions { asset: a.asset.clone(), partition: a.partition.clone(), source: a.source.clone(), domain: a.domain };
    let mut client = Client::new(options, Some(tables).filter(|_| own))?;
    let (discover, find, answer) = (allow(a.discover, a.rtt, DISCOVERY_TRIPS), allow(a.timeout, a.rtt, DISCOVERY_TRIPS),
                                    allow(a.timeout, a.rtt, ANSWER_TRIPS));
    if a.discover > 0.0 && !client.read_dictionary(secs(discover)) {
        eprintln!("rapid_cmd: no CommandConfig from {} within {} s (domain {}){}", visible(client.asset(), 64),
                  fmt_g(discover), client.domain(), if own { "; using the built-in tables" } else { "" });
    }
    if client.dictionary().is_none() {
        eprintln!("rapid_cmd: no command dictionary for {}: the asset publishes none (is it running? --domain, \
                   --transport)", visible(client.asset(), 64));
        return Ok(1);
    }
    let how = SendOptions { action: a.action, target: a.target.clone(), cmd_id: a.id.clone(), limits: !a.no_check };
    let (subsystem, command) = (&a.words[0], &a.words[1]);
    let mut cmd = client.prepare_text(subsystem, command, &a.words[2..], &how)?; // checked before waiting
    if !client.wait_for_asset(secs(find)) {
        eprintln!("rapid_cmd: no asset {} reads commands on domain {}, partition '{}' (waited {} s)",
                  visible(client.asset(), 64), client.domain(), visible(client.partition(), 64), fmt_g(find));
        return Ok(1);
    }
    if a.repeat > 0 {
        return Ok(repeat(&client, &cmd, a, secs(answer)));
    }
    if !a.target.is_empty() {
        client.follow(&a.target);
    }
    let id = client.send_raw(cmd.clone())?;
    cmd.cmd_id = id.clone();
    let spec = client.entry(subsystem, command)?;
    let mut line = format!("{} <- {}/{}", visible(client.asset(), 64), visible(subsystem, 64), visible(command, 64));
    for (p, v) in spec.params.iter().zip(&cmd.args) {
        line += &format!(" {}={}", p.name, shown(v)); // the values as sent, defaults included
    }
    line += &format!("  [cmdId {}, {}{}, from {}]", visible(&id, 64), a.action.name().unwrap_or("QUEUE_?"),
                     if a.target.is_empty() { String::new() } else { format!(" {}", visible(&a.target, 64)) },
                     visible(&a.source, 64));
    println!("{line}");
    let unanswered = secs(allow(UNANSWERED, a.rtt, ANSWER_TRIPS));
    let acks = follow(&client, &id, secs(answer), a.no_wait, Some((&cmd, unanswered)));
    let writers = client.writers(&id);
    if writers > 1 {
        eprintln!("rapid_cmd: warning: acks of {} came from {writers} writers; only the asset should answer (a \
                   second bridge or a stranger on the domain? DDS Security keeps strangers out)", visible(&id, 64));
    }
    let Some(last) = acks.last() else {
        println!("  no ack within {} s", fmt_g(answer));
        return Ok(1);
    };
    if a.action == QueueAction::Delete && last.is_final() {
        println!("target {}:", visible(&a.target, 64));
        follow(&client, &a.target, secs(allow(3.0, a.rtt, ANSWER_TRIPS)), false, None);
    }
    if a.no_wait {
        return Ok(if !last.is_final() || last.ok() { 0 } else { 1 });
    }
    Ok(if last.ok() { 0 } else { 1 })
}

/// The q-th quantile (nearest rank) of sorted values.
fn percentile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    let i = (q * sorted.len() as f64).ceil() as usize;
    sorted[i.clamp(1, sorted.len()) - 1]
}

/// `--repeat N`: the command N times, each awaited to its final ack (a fresh cmdId each);
/// one JSON line as rapid_cmd's: send-to-final-ack latency, commands per second.
fn repeat(client: &Client, cmd: &rapid_runtime::Cmd, a: &Args, answer: Duration) -> i32 {
    let mut us = Vec::with_capacity(a.repeat as usize);
    let start = Instant::now();
    for _ in 0..a.repeat {
        let t0 = Instant::now();
        let mut c = cmd.clone();
        c.cmd_id.clear();
        c.stamp = 0;
        let Ok(id) = client.send_raw(c) else { continue };
        let acks = client.wait_final(&id, answer);
        client.forget(&id);
        if acks.iter().any(AckEvent::is_final) {
            us.push(t0.elapsed().as_secs_f64() * 1e6);
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    let answered = us.len();
    us.sort_by(f64::total_cmp);
    println!("{{\"count\": {}, \"answered\": {answered}, \"p50_us\": {:.1}, \"p99_us\": {:.1}, \"max_us\": {:.1}, \
              \"per_s\": {:.1}}}", a.repeat, percentile(&us, 0.5), percentile(&us, 0.99), percentile(&us, 1.0),
             answered as f64 / seconds);
    if answered as u64 == a.repeat { 0 } else { 1 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn argv(words: &[&str]) -> Vec<String> {
        std::iter::once("x").chain(words.iter().copied()).map(String::from).collect()
    }

    #[test]
    fn the_command_line_reads_as_rapid_cmds() {
        let Ok(Some(a)) = parse(&argv(&["Admin", "echo", "text=hi", "--action", "queue_append", "--domain", "4"]))
        else {
            panic!("not parsed")
        };
        assert_eq!((a.action, a.domain, a.words.len()), (QueueAction::Append, Some(4), 3));
        assert_eq!(parse(&argv(&["Admin"])).err().as_deref(), Some("SUBSYSTEM and COMMAND are needed"));
        assert_eq!(parse(&argv(&["A", "b", "--action", "SIDEWAYS"])).err().as_deref(),
                   Some("bad value for --action: SIDEWAYS"));
        assert_eq!(parse(&argv(&["A", "b", "--timeout", "0"])).err().as_deref(), Some("bad value for --timeout: 0"));
        assert_eq!(parse(&argv(&["A", "b", "--domain"])).err().as_deref(), Some("--domain needs a value"));
        assert_eq!(parse(&argv(&["A", "b", "--rtt", "601"])).err().as_deref(), Some("bad value for --rtt: 601"));
        let Ok(Some(a)) = parse(&argv(&["A", "b", "--rtt", "2.6"])) else { panic!("--rtt 2.6") };
        assert_eq!(allow(a.timeout, a.rtt, ANSWER_TRIPS), 35.2);
        assert!(matches!(parse(&argv(&["--help"])), Ok(None)));
        assert_eq!(shown(&Value::Vec3d([40.0, 0.5, -1.0])), "40,0.5,-1");
        assert_eq!(shown(&Value::Float(0.5)), "0.5");
        assert_eq!(shown(&Value::Float(0.2)), "0.2");
        assert_eq!(shown(&Value::Float(9.0)), "9.0");
        assert_eq!(shown(&Value::String("hi".into())), "'hi'");
        assert_eq!(percentile(&[1.0, 2.0, 3.0, 4.0], 0.5), 2.0);
        assert_eq!(percentile(&[1.0, 2.0, 3.0, 4.0], 0.99), 4.0);
    }
}
