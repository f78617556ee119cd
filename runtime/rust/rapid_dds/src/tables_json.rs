//! An asset's tables from JSON: the form rapidgen's Rust back end writes beside a generated
//! bridge (rapidgen/backends/rust/tables.py: the Python package's asset_tables, in lists),
//! which tests/rust_runtime/test_spec_cases.py also writes from the Python runtime's tables
//! (no telemetry nor publications there). The bridge embeds it and reads it at start.
use std::collections::BTreeMap;

use rapid_runtime::*;
use serde_json::Value as Json;

fn s(j: &Json, key: &str) -> String {
    j.get(key).and_then(Json::as_str).unwrap_or_default().to_string()
}
fn strings(j: &Json) -> Vec<String> {
    j.as_array().map(|a| a.iter().filter_map(|x| x.as_str().map(String::from)).collect()).unwrap_or_default()
}
fn number(j: &Json) -> Result<f64, String> {
    j.as_f64().ok_or_else(|| format!("{j} is not a number"))
}
fn value_of(t: DataType, v: &Json) -> Result<Value, String> {
    let nums = |n: usize| -> Result<Vec<f64>, String> {
        let a = v.as_array().filter(|a| a.len() == n).ok_or_else(|| format!("{v} is not {n} numbers"))?;
        a.iter().map(number).collect()
    };
    Ok(match t {
        DataType::Bool => Value::Bool(v.as_bool().ok_or_else(|| format!("{v} is not a boolean"))?),
        DataType::Double => Value::Double(number(v)?),
        DataType::Float => Value::Float(number(v)? as f32),
        DataType::Int => Value::Int(v.as_i64().and_then(|x| i32::try_from(x).ok()).ok_or_else(|| format!("{v}: not an int"))?),
        DataType::LongLong => Value::LongLong(v.as_i64().ok_or_else(|| format!("{v}: not a long long"))?),
        DataType::String => Value::String(v.as_str().ok_or_else(|| format!("{v} is not a string"))?.to_string()),
        DataType::Vec3d => Value::Vec3d(nums(3)?.try_into().map_err(|_| "3 numbers")?),
        DataType::Mat33f => {
            let n = nums(9)?;
            Value::Mat33f(std::array::from_fn(|i| n[i] as f32))
        }
    })
}
fn data_type(name: &str) -> Result<DataType, String> {
    DataType::from_name(name).ok_or_else(|| format!("unknown DataType {name}"))
}
/// A seed's tables as tests/rust_runtime/test_spec_cases.py writes them from the Python runtime's.
pub fn tables_of(j: &Json) -> Result<Tables, String> {
    let mut t = Tables {
        name: s(j, "name"),
        kind: s(j, "kind"),
        domain: j.get("domain").and_then(Json::as_i64).unwrap_or(0) as i32,
        partition: s(j, "partition"),
        ..Tables::default()
    };
    for sub in j["subsystems"].as_array().ok_or("subsystems")? {
        t.subsystems.push(Subsystem { name: s(sub, "name"), type_name: s(sub, "type") });
    }
    for ty in j["types"].as_array().ok_or("types")? {
        let mut st = SubsystemType { name: s(ty, "name"), commands: Vec::new() };
        for c in ty["commands"].as_array().ok_or("commands")? {
            let mut spec = CommandSpec {
                name: s(c, "name"),
                abortable: c["abortable"].as_bool().unwrap_or(false),
                suspendable: c["suspendable"].as_bool().unwrap_or(false),
                standard: c["standard"].as_bool().unwrap_or(false),
                description: s(c, "description"),
                stop_timeout_ms: c["stop_timeout_ms"].as_u64().unwrap_or(0),
                params: Vec::new(),
            };
            for p in c["params"].as_array().ok_or("params")? {
                let dt = data_type(&s(p, "type"))?;
                let mut param = Param::new(&s(p, "name"), dt);
                param.unit = s(p, "unit");
                param.min = p["min"].as_f64();
                param.max = p["max"].as_f64();
                for a in p["allowed"].as_array().into_iter().flatten() {
                    param.allowed.push(value_of(dt, a)?);
                }
                if let Some(d) = p.get("default") {
                    param.default = Some(value_of(dt, d)?);
                }
                spec.params.push(param);
            }
            st.commands.push(spec);
        }
        t.types.push(st);
    }
    if let Some(acc) = j.get("access").filter(|a| !a.is_null()) {
        t.access = Some(AccessSpec {
            allow_by_default: s(acc, "default") == "allow",
            rules: acc["rules"]
                .as_array()
                .ok_or("rules")?
                .iter()
                .map(|r| AccessRule { source: s(r, "source"), allow: strings(&r["allow"]) })
                .collect(),
        });
    }
    Ok(t)
}

/// A value key of a telemetry entry (agent and position values).
#[derive(Clone, Debug)]
pub struct TelemetryValue {
    pub name: String,
    pub data_type: DataType,
    pub min: Option<f64>,
    pub max: Option<f64>,
    pub allowed: Vec<Value>,
    pub default: Option<Value>,
}

/// A joint of a joint entry.
#[derive(Clone, Debug)]
pub struct Joint {
    pub frame: String,
    pub min: Option<f64>,
    pub max: Option<f64>,
}

/// One telemetry entry of the descriptor (kind position, agent, joint, image, text, custom).
#[derive(Clone, Debug, Default)]
pub struct Telemetry {
    pub kind: String,
    /// role (config, sample, state) -> topic
    pub topics: BTreeMap<String, String>,
    /// Hz; None: none declared
    pub rate: Option<f64>,
    pub subsystem: String,
    pub values: Vec<TelemetryValue>,
    pub pose_encoding: String,
    pub velocity_encoding: String,
    /// a joint entry's JointSample fields
    pub fields: Vec<String>,
    pub joints: Vec<Joint>,
    pub sensor: String,
    pub sensor_type: String,
    pub mime: String,
    pub width: i32,
    pub height: i32,
    pub categories: Vec<String>,
    /// a custom entry's role -> DDS type name
    pub types: BTreeMap<String, String>,
}

/// A topic the asset publishes.
#[derive(Clone, Debug)]
pub struct Publication {
    pub role: String,
    pub type_name: String,
    pub topic: String,
    pub qos: String,
    pub rate: Option<f64>,
}

/// The tables, the telemetry entries and the publications.
pub struct Asset {
    pub tables: Tables,
    pub telemetry: Vec<Telemetry>,
    pub publications: Vec<Publication>,
}

fn string_map(j: &Json) -> BTreeMap<String, String> {
    j.as_object()
        .map(|m| m.iter().filter_map(|(k, v)| v.as_str().map(|v| (k.clone(), v.to_string()))).collect())
        .unwrap_or_default()
}

fn telemetry_of(t: &Json) -> Result<Telemetry, String> {
    let mut values = Vec::new();
    for v in t["values"].as_array().into_iter().flatten() {
        let dt = data_type(&s(v, "type"))?;
        let mut allowed = Vec::new();
        for a in v["allowed"].as_array().into_iter().flatten() {
            allowed.push(value_of(dt, a)?);
        }
        let has_default = v["has_default"].as_bool().unwrap_or(false);
        values.push(TelemetryValue {
            name: s(v, "name"),
            data_type: dt,
            min: v["min"].as_f64(),
            max: v["max"].as_f64(),
            allowed,
            default: if has_default { Some(value_of(dt, &v["default"])?) } else { None },
        });
    }
    let joints = t["joints"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|j| Joint { frame: s(j, "frame"), min: j["min"].as_f64(), max: j["max"].as_f64() })
        .collect();
    Ok(Telemetry {
        kind: s(t, "kind"),
        topics: string_map(&t["topics"]),
        rate: t["rate"].as_f64().filter(|r| *r > 0.0),
        subsystem: s(t, "subsystem"),
        values,
        pose_encoding: s(t, "pose_encoding"),
        velocity_encoding: s(t, "velocity_encoding"),
        fields: strings(&t["fields"]),
        joints,
        sensor: s(t, "sensor"),
        sensor_type: s(t, "sensor_type"),
        mime: s(t, "mime"),
        width: t["width"].as_i64().unwrap_or(640) as i32,
        height: t["height"].as_i64().unwrap_or(480) as i32,
        categories: strings(&t["categories"]),
        types: string_map(&t["types"]),
    })
}

/// A generated bridge's tables.json (rapidgen/backends/rust/tables.py).
pub fn asset_of(j: &Json) -> Result<Asset, String> {
    let tables = tables_of(j)?;
    let mut telemetry = Vec::new();
    for (i, t) in j["telemetry"].as_array().into_iter().flatten().enumerate() {
        telemetry.push(telemetry_of(t).map_err(|e| format!("telemetry entry {}: {e}", i + 1))?);
    }
    let publications = j["publications"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|p| Publication {
            role: s(p, "role"),
            type_name: s(p, "type"),
            topic: s(p, "topic"),
            qos: s(p, "qos"),
            rate: p["rate"].as_f64(),
        })
        .collect();
    Ok(Asset { tables, telemetry, publications })
}
