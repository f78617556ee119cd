//! An asset's tables from JSON, in the form tests/rust_runtime/test_spec_cases.py writes from
//! the Python runtime's (rapidgen.protocol_cases.seed_tables): until the generated crate
//! carries the whole dictionary (defaults, allowed values, access rules), the bridge reads it.
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
