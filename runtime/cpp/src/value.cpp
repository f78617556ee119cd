#include "rapid_runtime/value.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "rapid_runtime/tables.hpp"
#include "rapid_runtime/text.hpp"
#include "rapid_runtime/texts.hpp"

namespace rapid_runtime {
namespace {

bool numeric(const Value& v) {
    return std::holds_alternative<double>(v) || std::holds_alternative<float>(v) ||
           std::holds_alternative<std::int32_t>(v) || std::holds_alternative<std::int64_t>(v);
}

bool integral(const Value& v) { return std::holds_alternative<std::int32_t>(v) || std::holds_alternative<std::int64_t>(v); }

double as_double(const Value& v) {
    if (auto* d = std::get_if<double>(&v)) return *d;
    if (auto* f = std::get_if<float>(&v)) return *f;
    if (auto* i = std::get_if<std::int32_t>(&v)) return *i;
    if (auto* l = std::get_if<std::int64_t>(&v)) return static_cast<double>(*l);
    return 0.0;
}

std::int64_t as_int(const Value& v) {
    if (auto* i = std::get_if<std::int32_t>(&v)) return *i;
    if (auto* l = std::get_if<std::int64_t>(&v)) return *l;
    return 0;
}

// Python's repr of a float: the shortest digits that read back, positional between 1e-4
// and 1e16, scientific outside, ".0" on whole numbers.
std::string py_float(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x < 0 ? "-inf" : "inf";
    char buf[64];
    auto res = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::scientific);
    std::string sci(buf, res.ptr);  // -d.ddde+XX
    bool negative = sci[0] == '-';
    std::string mant = sci.substr(negative ? 1 : 0, sci.find('e') - (negative ? 1 : 0));
    int exp = std::atoi(sci.c_str() + sci.find('e') + 1);
    std::string digits;
    for (char c : mant)
        if (c != '.') digits += c;
    std::string out = negative ? "-" : "";
    if (exp < -4 || exp >= 16) {
        out += digits.substr(0, 1);
        if (digits.size() > 1) out += "." + digits.substr(1);
        char e[16];
        std::snprintf(e, sizeof e, "e%c%02d", exp < 0 ? '-' : '+', std::abs(exp));
        return out + e;
    }
    if (exp < 0) return out + "0." + std::string(static_cast<std::size_t>(-exp - 1), '0') + digits;
    auto point = static_cast<std::size_t>(exp) + 1;
    if (digits.size() <= point) return out + digits + std::string(point - digits.size(), '0') + ".0";
    return out + digits.substr(0, point) + "." + digits.substr(point);
}

// Python's repr of a str: single quotes unless the text holds one and no double quote.
std::string py_string(const std::string& s) {
    char quote = s.find('\'') != std::string::npos && s.find('"') == std::string::npos ? '"' : '\'';
    std::string out(1, quote);
    for (char ch : s) {
        auto c = static_cast<unsigned char>(ch);
        if (ch == quote || ch == '\\') {
            out += '\\';
            out += ch;
        } else if (ch == '\n') {
            out += "\\n";
        } else if (ch == '\r') {
            out += "\\r";
        } else if (ch == '\t') {
            out += "\\t";
        } else if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
        } else {
            out += ch;
        }
    }
    return out + quote;
}

template <class A>
std::string py_list(const A& items) {
    std::string out = "[";
    for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + py_float(items[i]);
    return out + "]";
}

// Python's f"{x:g}" for floats, str for integers.
std::string fmt_g(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x < 0 ? "-inf" : "inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

}  // namespace

std::string_view name_of(DataType t) {
    static constexpr std::string_view names[] = {"RAPID_BOOL",     "RAPID_DOUBLE", "RAPID_FLOAT", "RAPID_INT",
                                                 "RAPID_LONGLONG", "RAPID_STRING", "RAPID_VEC3d", "RAPID_MAT33f"};
    auto i = static_cast<std::size_t>(t);
    return i < DATA_TYPES ? names[i] : "";
}

bool same_value(const Value& a, const Value& b) {
    if (numeric(a) && numeric(b)) return integral(a) && integral(b) ? as_int(a) == as_int(b) : as_double(a) == as_double(b);
    if (a.index() != b.index()) return false;
    if (auto* v = std::get_if<Vec3d>(&a)) return *v == std::get<Vec3d>(b);
    if (auto* m = std::get_if<Mat33f>(&a)) return *m == std::get<Mat33f>(b);
    return a == b;
}

std::string repr(const Value& v) {
    switch (type_of(v)) {
        case DataType::Bool: return std::get<bool>(v) ? "True" : "False";
        case DataType::Double: return py_float(std::get<double>(v));
        case DataType::Float: return py_float(std::get<float>(v));
        case DataType::Int: return std::to_string(std::get<std::int32_t>(v));
        case DataType::LongLong: return std::to_string(std::get<std::int64_t>(v));
        case DataType::String: return py_string(std::get<std::string>(v));
        case DataType::Vec3d: return py_list(std::get<Vec3d>(v));
        case DataType::Mat33f: return py_list(std::get<Mat33f>(v));
    }
    return "";
}

std::string str(const Value& v) { return type_of(v) == DataType::String ? std::get<std::string>(v) : repr(v); }

std::optional<std::string> shape_error(const Value& v) {
    if (auto* s = std::get_if<std::string>(&v); s != nullptr && s->size() > STRING_BYTES)
        return texts::string_too_long(static_cast<long long>(s->size()), static_cast<long long>(STRING_BYTES));
    return std::nullopt;
}

std::optional<std::string> limit_error(const Param& p, const Value& v) {
    if (!p.allowed.empty()) {
        bool found = false;
        for (const auto& a : p.allowed) found = found || same_value(v, a);
        if (!found) {
            std::string shown;
            for (std::size_t i = 0; i < p.allowed.size(); ++i) shown += (i ? "|" : "") + str(p.allowed[i]);
            return texts::not_one_of(repr(v), shown);
        }
    }
    if (!p.min && !p.max) return std::nullopt;
    std::vector<Value> items;
    if (auto* vec = std::get_if<Vec3d>(&v)) items.assign(vec->begin(), vec->end());
    else if (auto* mat = std::get_if<Mat33f>(&v)) items.assign(mat->begin(), mat->end());
    else if (numeric(v)) items.push_back(v);
    for (const auto& item : items) {
        double x = as_double(item);
        bool out = std::isnan(x) || (p.min && x < *p.min) || (p.max && x > *p.max);
        if (integral(item)) out = (p.min && static_cast<double>(as_int(item)) < *p.min) ||
                                  (p.max && static_cast<double>(as_int(item)) > *p.max);
        if (out) {
            std::string shown = integral(item) ? std::to_string(as_int(item)) : fmt_g(x);
            return texts::out_of_range(shown, p.min ? fmt_g(*p.min) : "-inf", p.max ? fmt_g(*p.max) : "inf");
        }
    }
    return std::nullopt;
}

}  // namespace rapid_runtime
