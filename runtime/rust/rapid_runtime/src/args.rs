//! A command's arguments as a ground-side client gives them, by name (values, or the command
//! line's `key=value` words): each matched to its parameter, parsed or converted to its
//! DataType, checked for shape and (unless told not to) the descriptor's range and allowed
//! values, the defaults filled in. The C++ runtime's args.cpp and `rapidgen cmd`
//! (rapidgen/cmd/arguments.py) do the same in the same words.

use crate::tables::{CommandSpec, Param};
use crate::text::visible;
use crate::value::{limit_error, shape_error, DataType, Value};

/// What a DataType's value looks like, for errors (as arguments.py's KIND).
pub fn kind_of(t: DataType) -> &'static str {
    match t {
        DataType::Bool => "a boolean (true/false)",
        DataType::Int => "a 32-bit integer",
        DataType::LongLong => "a 64-bit integer",
        DataType::Float | DataType::Double => "a number",
        DataType::String => "a string",
        DataType::Vec3d => "3 numbers (x,y,z)",
        DataType::Mat33f => "9 numbers (row by row)",
    }
}

fn number(t: &str) -> Option<f64> {
    let x: f64 = t.parse().ok()?;
    // "1e400" parses as inf: refused as strtod's ERANGE is (an infinity must be asked for)
    (x.is_finite() || t.to_ascii_lowercase().contains("inf") || t.to_ascii_lowercase().contains("nan")).then_some(x)
}

/// An integer as Python's int(text, 0): decimal, or 0x / 0o / 0b with an optional sign.
fn integer(t: &str) -> Option<i64> {
    let (neg, digits) = match t.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    let low = digits.to_ascii_lowercase();
    let (radix, body) = match low.get(..2) {
        Some("0x") => (16, &digits[2..]),
        Some("0o") => (8, &digits[2..]),
        Some("0b") => (2, &digits[2..]),
        _ => (10, digits),
    };
    if body.is_empty() || body.starts_with(['+', '-']) {
        return None;
    }
    let magnitude = i128::from_str_radix(body, radix).ok()?;
    i64::try_from(if neg { -magnitude } else { magnitude }).ok()
}

fn numbers<const N: usize>(t: &str) -> Option<[f64; N]> {
    let inner = t.trim_start_matches(['[', '(']).trim_end_matches([']', ')']);
    let parts: Vec<&str> = inner.split([',', ' ']).filter(|p| !p.is_empty()).collect();
    if parts.len() != N {
        return None;
    }
    let mut out = [0.0; N];
    for (o, p) in out.iter_mut().zip(parts) {
        *o = number(p)?;
    }
    Some(out)
}

/// A command-line argument (the text after `key=`) as a value of `t`; None when it is not one.
pub fn parse_text(t: DataType, text: &str) -> Option<Value> {
    let s = text.trim();
    match t {
        DataType::Bool => match s.to_ascii_lowercase().as_str() {
            "true" | "1" | "yes" | "on" => Some(Value::Bool(true)),
            "false" | "0" | "no" | "off" => Some(Value::Bool(false)),
            _ => None,
        },
        DataType::Int | DataType::LongLong => coerce(t, &Value::LongLong(integer(s)?)),
        DataType::Float | DataType::Double => coerce(t, &Value::Double(number(s)?)),
        DataType::String => Some(Value::String(text.to_string())),
        DataType::Vec3d => numbers::<3>(s).map(Value::Vec3d),
        DataType::Mat33f => numbers::<9>(s).map(|m| Value::Mat33f(m.map(|x| x as f32))),
    }
}

/// `v` as a value of `t` where that loses nothing a caller meant: any number as a float or
/// double (a finite double beyond float's range refused, not made infinite), a 64-bit
/// integer that fits as a 32-bit one, a 32-bit one as 64; None for anything else.
pub fn coerce(t: DataType, v: &Value) -> Option<Value> {
    if v.data_type() == t {
        return Some(v.clone());
    }
    let x = v.number();
    match (t, v) {
        (DataType::Double, _) => x.map(Value::Double),
        (DataType::Float, _) => {
            let x = x?;
            (!x.is_finite() || x.abs() <= f32::MAX as f64).then_some(Value::Float(x as f32))
        }
        (DataType::Int, Value::LongLong(l)) => i32::try_from(*l).ok().map(Value::Int),
        (DataType::LongLong, Value::Int(i)) => Some(Value::LongLong(*i as i64)),
        _ => None,
    }
}

fn known(spec: &CommandSpec) -> String {
    if spec.params.is_empty() {
        return "no arguments".into();
    }
    spec.params.iter().map(|p| format!("{}=...", p.name)).collect::<Vec<_>>().join(", ")
}

/// The values given so far, one slot per parameter: None not given, Some(None) given and
/// already said to be wrong.
type Given = Vec<Option<Option<Value>>>;

/// The parameter named `key` and its index; the error when there is none or it came before.
fn slot<'a>(spec: &'a CommandSpec, given: &Given, key: &str) -> Result<(usize, &'a Param), String> {
    let Some(i) = spec.params.iter().position(|p| p.name == key) else {
        return Err(format!("{} has no parameter '{}' (it takes {})", spec.name, visible(key, 64), known(spec)));
    };
    let p = &spec.params[i];
    if given[i].is_some() {
        return Err(format!("'{}' given twice", p.name));
    }
    Ok((i, p))
}

/// The given values checked (shape; range and allowed values when `limits`), then the
/// defaults: every value in parameter order, or every problem found.
fn finish(spec: &CommandSpec, given: Given, mut errors: Vec<String>, limits: bool) -> Result<Vec<Value>, Vec<String>> {
    let mut missing = Vec::new();
    let mut values = Vec::new();
    for (p, g) in spec.params.iter().zip(given) {
        let v = match g {
            Some(Some(v)) => v,
            Some(None) => continue, // already reported
            None => match &p.default {
                None => {
                    missing.push(format!("{} ({})", p.name, p.data_type.name()));
                    continue;
                }
                Some(d) => match coerce(p.data_type, d) {
                    Some(v) => v,
                    None => {
                        errors.push(format!("{}: the default does not fit {}", p.name, p.data_type.name()));
                        continue;
                    }
                },
            },
        };
        let why = shape_error(&v).or_else(|| if limits { limit_error(p, &v) } else { None });
        match why {
            Some(why) => errors.push(format!("{}: {why}", p.name)),
            None => values.push(v),
        }
    }
    if !missing.is_empty() {
        errors.push(format!("{} needs {}", spec.name, missing.join(", ")));
    }
    if errors.is_empty() {
        Ok(values)
    } else {
        Err(errors)
    }
}

/// Named values (converted as `coerce` does) as the command's arguments in parameter order.
pub fn complete(spec: &CommandSpec, named: &[(&str, Value)], limits: bool) -> Result<Vec<Value>, Vec<String>> {
    let mut given: Given = vec![None; spec.params.len()];
    let mut errors = Vec::new();
    for (key, value) in named {
        match slot(spec, &given, key) {
            Err(e) => errors.push(e),
            Ok((i, p)) => {
                let v = coerce(p.data_type, value);
                if v.is_none() {
                    errors.push(format!("{}: {} given, {} is {} ({})", p.name, value.data_type().name(), p.name,
                                        kind_of(p.data_type), p.data_type.name()));
                }
                given[i] = Some(v);
            }
        }
    }
    finish(spec, given, errors, limits)
}

/// `key=value` words (the command line's) as the command's arguments in parameter order.
pub fn complete_text(spec: &CommandSpec, words: &[String], limits: bool) -> Result<Vec<Value>, Vec<String>> {
    let mut given: Given = vec![None; spec.params.len()];
    let mut errors = Vec::new();
    for word in words {
        let Some((key, text)) = word.split_once('=').filter(|(k, _)| !k.is_empty()) else {
            errors.push(format!("'{}' is not key=value ({} takes {})", visible(word, 64), spec.name, known(spec)));
            continue;
        };
        match slot(spec, &given, key) {
            Err(e) => errors.push(e),
            Ok((i, p)) => {
                let v = parse_text(p.data_type, text);
                if v.is_none() {
                    errors.push(format!("{}: '{}' is not {}", p.name, visible(text, 64), kind_of(p.data_type)));
                }
                given[i] = Some(v);
            }
        }
    }
    finish(spec, given, errors, limits)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> CommandSpec {
        let mut pan = Param::new("pan", DataType::Float);
        pan.min = Some(-3.05);
        pan.max = Some(3.05);
        let mut mode = Param::new("mode", DataType::String);
        mode.allowed = vec![Value::String("left".into()), Value::String("right".into())];
        mode.default = Some(Value::String("left".into()));
        let mut n = Param::new("n", DataType::Int);
        n.default = Some(Value::LongLong(3));
        CommandSpec { name: "point".into(), params: vec![pan, mode, n, Param::new("at", DataType::Vec3d)],
                      ..CommandSpec::default() }
    }

    fn words(w: &[&str]) -> Vec<String> {
        w.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn words_parse_by_type_and_defaults_fill_the_rest() {
        let got = complete_text(&spec(), &words(&["at=[1, 2,3]", "pan=0.5"]), true).unwrap();
        assert_eq!(got, vec![Value::Float(0.5), Value::String("left".into()), Value::Int(3), Value::Vec3d([1.0, 2.0, 3.0])]);
        assert_eq!(parse_text(DataType::LongLong, "0x10"), Some(Value::LongLong(16)));
        assert_eq!(parse_text(DataType::Int, "4294967296"), None);
        assert_eq!(parse_text(DataType::Bool, " Yes "), Some(Value::Bool(true)));
        assert_eq!(parse_text(DataType::Double, "1e400"), None);
        assert_eq!(parse_text(DataType::Float, "1e39"), None);
    }

    #[test]
    fn every_problem_is_said_in_the_other_clients_words() {
        let e = complete_text(&spec(), &words(&["pan=abc", "zoom=2", "mode=up", "mode=left", "x"]), true).unwrap_err();
        assert_eq!(e, vec![
            "pan: 'abc' is not a number".to_string(),
            "point has no parameter 'zoom' (it takes pan=..., mode=..., n=..., at=...)".into(),
            "'mode' given twice".into(),
            "'x' is not key=value (point takes pan=..., mode=..., n=..., at=...)".into(),
            "mode: 'up' not one of left|right".into(),
            "point needs at (RAPID_VEC3d)".into(),
        ]);
        let e = complete_text(&spec(), &words(&["pan=9", "at=1,2,3"]), true).unwrap_err();
        assert_eq!(e, vec!["pan: 9 not in [-3.05, 3.05]".to_string()]);
        assert!(complete_text(&spec(), &words(&["pan=9", "at=1,2,3"]), false).is_ok());
        let e = complete(&spec(), &[("pan", Value::String("x".into())), ("at", Value::Int(1))], true).unwrap_err();
        assert_eq!(e[0], "pan: RAPID_STRING given, pan is a number (RAPID_FLOAT)");
        assert_eq!(e[1], "at: RAPID_INT given, at is 3 numbers (x,y,z) (RAPID_VEC3d)");
        let ok = complete(&spec(), &[("pan", Value::Int(1)), ("at", Value::Vec3d([0.0; 3]))], true).unwrap();
        assert_eq!(ok[0], Value::Float(1.0));
    }
}
