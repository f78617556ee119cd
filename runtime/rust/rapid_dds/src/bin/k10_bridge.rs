//! A minimal K10 bridge on the Rust runtime and its DDS layer (issue 38, second stage):
//! simulated handlers (every command OK; a Mobility move drives 10 m/s, 500 m in 50 s, until
//! told to stop: the queue checks need a command that holds the queue), the asset's configs published transient-local,
//! commands read from its partition. Telemetry is not published yet.
//!   k10_bridge --tables FILE [--domain N]
//! FILE: the asset's tables as JSON (rapid_dds::tables_json). Loopback only unless
//! CYCLONEDDS_URI says otherwise: it defaults to K10's generated qos/cyclonedds/local.xml.
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use rapid_dds::dds::Side;
use rapid_dds::{convert, tables_json, DdsOutbox, Participant};
use rapid_runtime::{CommandManager, Context, Handlers, Options, Outcome, Value};

struct Simulated;

impl Handlers for Simulated {
    fn execute(&self, ctx: &Context) -> Outcome {
        let metres = ctx.args().iter().find_map(|v| match v {
            Value::Vec3d(x) => Some((x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()),
            _ => None,
        });
        match metres {
            Some(m) if ctx.subsystem() == "Mobility" => {
                if ctx.sleep(Duration::from_secs_f64(m / 10.0)) {
                    Outcome::Ok(format!("{m:.0} m driven (simulated)"))
                } else {
                    Outcome::Canceled
                }
            }
            _ => Outcome::Ok(String::new()),
        }
    }
}

fn arg(args: &[String], name: &str) -> Option<String> {
    args.iter().position(|a| a == name).and_then(|i| args.get(i + 1).cloned())
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().collect();
    let tables_file = arg(&args, "--tables").ok_or("usage: k10_bridge --tables FILE [--domain N]")?;
    let text = std::fs::read_to_string(&tables_file).map_err(|e| format!("{tables_file}: {e}"))?;
    let json: serde_json::Value = serde_json::from_str(&text).map_err(|e| format!("{tables_file}: {e}"))?;
    let tables = tables_json::tables_of(&json).map_err(|e| format!("{tables_file}: {e}"))?;
    let domain: u32 = match arg(&args, "--domain") {
        Some(d) => d.parse().map_err(|_| format!("--domain {d:?}: not a domain id"))?,
        None => rapid_k10red::asset::DOMAIN,
    };
    if std::env::var_os("CYCLONEDDS_URI").is_none() {
        let local = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../generated/k10/qos/cyclonedds/local.xml");
        std::env::set_var("CYCLONEDDS_URI", format!("file://{local}"));
    }
    let name = tables.name.clone();
    let serial = convert::now_us().div_euclid(1_000_000) as i32; // (as Python: the start time)
    let dp = Participant::new(domain, &tables.partition).map_err(|e| e.to_string())?;
    let outbox = Arc::new(DdsOutbox::new(&dp, &name, serial).map_err(|e| e.to_string())?);

    // configs first (transient-local): commanders read the CommandConfig to find the asset
    let hdr = convert::header(&name, &name, serial, 0);
    let mut config_writers = Vec::new();
    let configs = rapid_k10red::asset::configs().map_err(|e| format!("configs: {e}"))?;
    for (topic, bytes) in configs {
        let t = rapid_k10red::asset::TOPICS.iter().find(|t| t.topic == topic).ok_or(format!("config {topic}"))?;
        let w = dp
            .writer(&dp.topic(topic, t.type_name, true).map_err(|e| e.to_string())?,
                    Side { reliable: true, transient_local: true, depth: Some(1) })
            .map_err(|e| e.to_string())?;
        w.write(&convert::with_header(&bytes, &hdr)?).map_err(|e| format!("{topic}: {e}"))?;
        config_writers.push(w);
    }

    let stop = Arc::new(AtomicBool::new(false));
    let on_shutdown = {
        let stop = stop.clone();
        Arc::new(move || stop.store(true, Ordering::SeqCst)) as Arc<dyn Fn() + Send + Sync>
    };
    let manager = CommandManager::new(Arc::new(tables), Arc::new(Simulated), outbox.clone(),
                                      Options { on_shutdown: Some(on_shutdown), ..Options::default() })?;
    manager.publish_states();
    let commands = dp.topic("rapid_command", "rapid::Command", true).map_err(|e| e.to_string())?;
    let reader = dp
        .reader(&commands, Side { reliable: true, transient_local: false, depth: None })
        .map_err(|e| e.to_string())?;
    println!("{name} ready on domain {domain}");
    while !stop.load(Ordering::SeqCst) {
        let mut idle = true;
        while let Some(bytes) = reader.take() {
            idle = false;
            match convert::command_in(&bytes) {
                Ok(cmd) => manager.receive(cmd),
                Err(e) => eprintln!("[{name}] a Command not decoded: {e}"),
            }
        }
        if idle {
            std::thread::sleep(Duration::from_micros(500));
        }
    }
    manager.shutdown(None);
    Ok(())
}

fn main() {
    if let Err(e) = run() {
        eprintln!("k10_bridge: {e}");
        std::process::exit(1);
    }
}
