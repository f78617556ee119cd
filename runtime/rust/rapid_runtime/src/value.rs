//! RAPID DataType values (ParameterUnion) and the checks a command's values get: shape, then
//! the descriptor's range and allowed values (runtime/rapid_runtime/values.py is the
//! reference; the C++ runtime's value.cpp does the same). Reasons quote values as Python's
//! repr and bounds as its `{:g}`, so every runtime writes the same words.

use crate::tables::Param;
use crate::texts;

/// In the IDL's order (rapid-protocol.md section 2): `as i32` is the union discriminator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DataType {
    Bool,
    Double,
    Float,
    Int,
    LongLong,
    String,
    Vec3d,
    Mat33f,
}

pub const DATA_TYPES: [DataType; 8] = [
    DataType::Bool,
    DataType::Double,
    DataType::Float,
    DataType::Int,
    DataType::LongLong,
    DataType::String,
    DataType::Vec3d,
    DataType::Mat33f,
];

/// ParameterUnion.s is a String128: at most 127 bytes.
pub const STRING_BYTES: usize = 127;

impl DataType {
    pub fn name(self) -> &'static str {
        match self {
            DataType::Bool => "RAPID_BOOL",
            DataType::Double => "RAPID_DOUBLE",
            DataType::Float => "RAPID_FLOAT",
            DataType::Int => "RAPID_INT",
            DataType::LongLong => "RAPID_LONGLONG",
            DataType::String => "RAPID_STRING",
            DataType::Vec3d => "RAPID_VEC3d",
            DataType::Mat33f => "RAPID_MAT33f",
        }
    }

    pub fn from_name(name: &str) -> Option<DataType> {
        DATA_TYPES.into_iter().find(|t| t.name() == name)
    }
}

/// One ParameterUnion: its variant is its DataType.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Bool(bool),
    Double(f64),
    Float(f32),
    Int(i32),
    LongLong(i64),
    String(String),
    Vec3d([f64; 3]),
    Mat33f([f32; 9]),
}

impl Value {
    pub fn data_type(&self) -> DataType {
        match self {
            Value::Bool(_) => DataType::Bool,
            Value::Double(_) => DataType::Double,
            Value::Float(_) => DataType::Float,
            Value::Int(_) => DataType::Int,
            Value::LongLong(_) => DataType::LongLong,
            Value::String(_) => DataType::String,
            Value::Vec3d(_) => DataType::Vec3d,
            Value::Mat33f(_) => DataType::Mat33f,
        }
    }

    /// A numeric value as f64 (what range checks and conversions read); None for the rest.
    pub(crate) fn number(&self) -> Option<f64> {
        match *self {
            Value::Double(x) => Some(x),
            Value::Float(x) => Some(x as f64),
            Value::Int(x) => Some(x as f64),
            Value::LongLong(x) => Some(x as f64),
            _ => None,
        }
    }

    fn integer(&self) -> Option<i64> {
        match *self {
            Value::Int(x) => Some(x as i64),
            Value::LongLong(x) => Some(x),
            _ => None,
        }
    }

    /// Numerically equal (a float 0.5 equals a double 0.5, an int 0 equals 0.0), strings and
    /// vectors exactly: how Python's `value in allowed` compares.
    pub fn same(&self, other: &Value) -> bool {
        if let (Some(a), Some(b)) = (self.integer(), other.integer()) {
            return a == b;
        }
        if let (Some(a), Some(b)) = (self.number(), other.number()) {
            return a == b;
        }
        self == other
    }

    /// As Python's repr (values in reasons).
    pub fn repr(&self) -> String {
        match self {
            Value::Bool(b) => (if *b { "True" } else { "False" }).to_string(),
            Value::Double(x) => py_float(*x),
            Value::Float(x) => py_float(*x as f64),
            Value::Int(x) => x.to_string(),
            Value::LongLong(x) => x.to_string(),
            Value::String(s) => py_string(s),
            Value::Vec3d(v) => py_list(v.iter().copied()),
            Value::Mat33f(m) => py_list(m.iter().map(|x| *x as f64)),
        }
    }

    /// As Python's str (a string as it is; anything else as repr): echo's answer, allowed values listed.
    pub fn str(&self) -> String {
        match self {
            Value::String(s) => s.clone(),
            other => other.repr(),
        }
    }

    /// The elements a range applies to (a vector's each, a number itself).
    fn elements(&self) -> Vec<Value> {
        match self {
            Value::Vec3d(v) => v.iter().map(|x| Value::Double(*x)).collect(),
            Value::Mat33f(m) => m.iter().map(|x| Value::Float(*x)).collect(),
            v if v.number().is_some() => vec![v.clone()],
            _ => Vec::new(),
        }
    }
}

/// Why the value cannot be sent as its DataType (a string over 127 bytes), or None.
pub fn shape_error(v: &Value) -> Option<String> {
    match v {
        Value::String(s) if s.len() > STRING_BYTES => Some(texts::string_too_long(s.len(), STRING_BYTES)),
        _ => None,
    }
}

/// Why the value is outside the parameter's allowed values or its range (element-wise for
/// vectors; NaN is outside every range), or None.
pub fn limit_error(p: &Param, v: &Value) -> Option<String> {
    if !p.allowed.is_empty() && !p.allowed.iter().any(|a| v.same(a)) {
        let shown: Vec<String> = p.allowed.iter().map(Value::str).collect();
        return Some(texts::not_one_of(&v.repr(), &shown.join("|")));
    }
    if p.min.is_none() && p.max.is_none() {
        return None;
    }
    for item in v.elements() {
        let outside = match item.integer() {
            Some(i) => p.min.is_some_and(|lo| (i as f64) < lo) || p.max.is_some_and(|hi| (i as f64) > hi),
            None => {
                let x = item.number().unwrap_or(0.0);
                x.is_nan() || p.min.is_some_and(|lo| x < lo) || p.max.is_some_and(|hi| x > hi)
            }
        };
        if outside {
            let shown = match item.integer() {
                Some(i) => i.to_string(),
                None => fmt_g(item.number().unwrap_or(0.0)),
            };
            let lo = p.min.map_or_else(|| "-inf".to_string(), fmt_g);
            let hi = p.max.map_or_else(|| "inf".to_string(), fmt_g);
            return Some(texts::out_of_range(&shown, &lo, &hi));
        }
    }
    None
}

/// (digits without the point, decimal exponent) of x's shortest round-trip form; x finite.
fn shortest(x: f64) -> (String, i32) {
    let sci = format!("{:e}", x.abs()); // "1.5e-5", "3e0"
    let (mant, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    (mant.replace('.', ""), exp.parse().unwrap_or(0))
}

/// Python's repr of a float: the shortest digits that read back, positional between 1e-4 and
/// 1e16, scientific outside, ".0" on whole numbers.
pub fn py_float(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    if x.is_infinite() {
        return (if x < 0.0 { "-inf" } else { "inf" }).into();
    }
    let sign = if x.is_sign_negative() { "-" } else { "" };
    let (digits, exp) = shortest(x);
    if !(-4..16).contains(&exp) {
        let mut out = format!("{sign}{}", &digits[..1]);
        if digits.len() > 1 {
            out += &format!(".{}", &digits[1..]);
        }
        return format!("{out}e{}{:02}", if exp < 0 { '-' } else { '+' }, exp.abs());
    }
    if exp < 0 {
        return format!("{sign}0.{}{digits}", "0".repeat((-exp - 1) as usize));
    }
    let point = exp as usize + 1;
    if digits.len() <= point {
        return format!("{sign}{digits}{}.0", "0".repeat(point - digits.len()));
    }
    format!("{sign}{}.{}", &digits[..point], &digits[point..])
}

/// Python's `f"{x:g}"`: six significant digits, trailing zeros dropped, scientific below 1e-4
/// and from 1e6.
pub fn fmt_g(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    if x.is_infinite() {
        return (if x < 0.0 { "-inf" } else { "inf" }).into();
    }
    let sci = format!("{:.5e}", x); // rounded to six digits: its exponent decides the form
    let (mant, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    fn trim(s: &str) -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    }
    if (-4..6).contains(&exp) {
        trim(&format!("{:.*}", (5 - exp) as usize, x))
    } else {
        format!("{}e{}{:02}", trim(mant), if exp < 0 { '-' } else { '+' }, exp.abs())
    }
}

/// Python's repr of a str: single quotes unless the text holds one and no double quote.
pub fn py_string(s: &str) -> String {
    let quote = if s.contains('\'') && !s.contains('"') { '"' } else { '\'' };
    let mut out = String::new();
    out.push(quote);
    for ch in s.chars() {
        match ch {
            c if c == quote || c == '\\' => {
                out.push('\\');
                out.push(c);
            }
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 || c as u32 == 0x7f => out.push_str(&format!("\\x{:02x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push(quote);
    out
}

fn py_list(items: impl Iterator<Item = f64>) -> String {
    let parts: Vec<String> = items.map(py_float).collect();
    format!("[{}]", parts.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_print_as_python_does() {
        assert_eq!(py_float(0.1), "0.1");
        assert_eq!(py_float(5.0), "5.0");
        assert_eq!(py_float(1e16), "1e+16");
        assert_eq!(py_float(1.5e-5), "1.5e-05");
        assert_eq!(py_float(0.0001), "0.0001");
        assert_eq!(py_float(-123.25), "-123.25");
        assert_eq!(py_float(0.1f32 as f64), "0.10000000149011612");
        assert_eq!(fmt_g(5.0), "5");
        assert_eq!(fmt_g(-3.05), "-3.05");
        assert_eq!(fmt_g(2000.0), "2000");
        assert_eq!(fmt_g(1234567.0), "1.23457e+06");
        assert_eq!(fmt_g(0.00001), "1e-05");
        assert_eq!(fmt_g(0.5), "0.5");
        assert_eq!(fmt_g(100000.0), "100000");
    }

    #[test]
    fn strings_repr_as_python_does() {
        assert_eq!(py_string("up"), "'up'");
        assert_eq!(py_string("it's"), "\"it's\"");
        assert_eq!(py_string("a\nb"), "'a\\nb'");
    }
}
