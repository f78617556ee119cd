#include "rapid_runtime/args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "rapid_runtime/text.hpp"

namespace rapid_runtime {
namespace {

std::string trimmed(std::string_view text) {
    auto begin = text.find_first_not_of(" \t\n\r\f\v");
    if (begin == std::string_view::npos) return {};
    auto end = text.find_last_not_of(" \t\n\r\f\v");
    return std::string(text.substr(begin, end - begin + 1));
}

std::optional<double> number(const std::string& t) {
    if (t.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    double x = std::strtod(t.c_str(), &end);
    if (end == nullptr || *end != '\0' || errno == ERANGE) return std::nullopt;
    return x;
}

std::optional<long long> integer(const std::string& t) {
    if (t.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    long long x = std::strtoll(t.c_str(), &end, 0);
    if (end == nullptr || *end != '\0' || errno == ERANGE) return std::nullopt;
    return x;
}

template <std::size_t N>
std::optional<std::array<double, N>> numbers(const std::string& t) {
    std::string text = t;
    while (!text.empty() && (text.front() == '[' || text.front() == '(')) text.erase(0, 1);
    while (!text.empty() && (text.back() == ']' || text.back() == ')')) text.pop_back();
    std::array<double, N> out{};
    std::size_t n = 0;
    std::string part;
    auto flush = [&]() -> bool {
        if (part.empty()) return true;
        auto x = number(part);
        part.clear();
        if (!x || n >= N) return false;
        out[n++] = *x;
        return true;
    };
    for (char c : text) {
        if (c == ',' || c == ' ') {
            if (!flush()) return std::nullopt;
        } else {
            part += c;
        }
    }
    if (!flush() || n != N) return std::nullopt;
    return out;
}

bool is_number(const Value& v) {
    return std::holds_alternative<double>(v) || std::holds_alternative<float>(v) ||
           std::holds_alternative<std::int32_t>(v) || std::holds_alternative<std::int64_t>(v);
}

double as_double(const Value& v) {
    if (auto* d = std::get_if<double>(&v)) return *d;
    if (auto* f = std::get_if<float>(&v)) return *f;
    if (auto* i = std::get_if<std::int32_t>(&v)) return *i;
    return static_cast<double>(std::get<std::int64_t>(v));
}

const Param* find(const CommandSpec& spec, const std::string& name) {
    for (const auto& p : spec.params)
        if (p.name == name) return &p;
    return nullptr;
}

std::string known(const CommandSpec& spec) {
    if (spec.params.empty()) return "no arguments";
    std::string out;
    for (const auto& p : spec.params) out += (out.empty() ? "" : ", ") + p.name + "=...";
    return out;
}

// The given values checked, then the defaults: shared by the two front doors.
// given[i] empty and reported[i]: a value already said to be wrong.
Arguments finish(const CommandSpec& spec, std::vector<std::optional<Value>>& given, const std::vector<bool>& reported,
                 Arguments out, bool limits) {
    std::string missing;
    for (std::size_t i = 0; i < spec.params.size(); ++i) {
        const Param& p = spec.params[i];
        if (reported[i]) continue;
        if (!given[i]) {
            if (!p.default_value) {
                missing += (missing.empty() ? "" : ", ") + p.name + " (" + std::string(name_of(p.type)) + ")";
                continue;
            }
            given[i] = coerce(p.type, *p.default_value);
            if (!given[i]) {
                out.errors.push_back(p.name + ": the default does not fit " + std::string(name_of(p.type)));
                continue;
            }
        }
        auto why = shape_error(*given[i]);
        if (!why && limits) why = limit_error(p, *given[i]);
        if (why) out.errors.push_back(p.name + ": " + *why);
    }
    if (!missing.empty()) out.errors.push_back(spec.name + " needs " + missing);
    if (out.errors.empty())
        for (auto& v : given) out.values.push_back(std::move(*v));
    return out;
}

}  // namespace

std::string_view kind_of(DataType t) {
    switch (t) {
        case DataType::Bool: return "a boolean (true/false)";
        case DataType::Int: return "a 32-bit integer";
        case DataType::LongLong: return "a 64-bit integer";
        case DataType::Float:
        case DataType::Double: return "a number";
        case DataType::String: return "a string";
        case DataType::Vec3d: return "3 numbers (x,y,z)";
        case DataType::Mat33f: return "9 numbers (row by row)";
    }
    return "a value";
}

std::optional<Value> parse_text(DataType t, std::string_view text) {
    const std::string s = trimmed(text);
    switch (t) {
        case DataType::Bool: {
            std::string low;
            for (char c : s) low += static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
            if (low == "true" || low == "1" || low == "yes" || low == "on") return Value(true);
            if (low == "false" || low == "0" || low == "no" || low == "off") return Value(false);
            return std::nullopt;
        }
        case DataType::Int:
        case DataType::LongLong: {
            auto x = integer(s);
            if (!x) return std::nullopt;
            return coerce(t, Value(static_cast<std::int64_t>(*x)));
        }
        case DataType::Float:
        case DataType::Double: {
            auto x = number(s);
            if (!x) return std::nullopt;
            return coerce(t, Value(*x));
        }
        case DataType::String: return Value(std::string(text));
        case DataType::Vec3d: {
            auto x = numbers<3>(s);
            if (!x) return std::nullopt;
            return Value(Vec3d{(*x)[0], (*x)[1], (*x)[2]});
        }
        case DataType::Mat33f: {
            auto x = numbers<9>(s);
            if (!x) return std::nullopt;
            Mat33f m{};
            for (std::size_t i = 0; i < 9; ++i) m[i] = static_cast<float>((*x)[i]);
            return Value(m);
        }
    }
    return std::nullopt;
}

std::optional<Value> coerce(DataType t, const Value& v) {
    if (type_of(v) == t) return v;
    switch (t) {
        case DataType::Double:
            if (is_number(v)) return Value(as_double(v));
            break;
        case DataType::Float:
            if (is_number(v)) {
                double x = as_double(v);
                // a finite double beyond float's range would become inf: refused, not changed
                if (std::isfinite(x) && std::fabs(x) > std::numeric_limits<float>::max()) return std::nullopt;
                return Value(static_cast<float>(x));
            }
            break;
        case DataType::Int:
            if (auto* l = std::get_if<std::int64_t>(&v);
                l != nullptr && *l >= std::numeric_limits<std::int32_t>::min() &&
                *l <= std::numeric_limits<std::int32_t>::max())
                return Value(static_cast<std::int32_t>(*l));
            break;
        case DataType::LongLong:
            if (auto* i = std::get_if<std::int32_t>(&v)) return Value(static_cast<std::int64_t>(*i));
            break;
        default: break;
    }
    return std::nullopt;
}

Arguments complete(const CommandSpec& spec, const std::vector<NamedValue>& named, bool limits) {
    Arguments out;
    std::vector<std::optional<Value>> given(spec.params.size());
    std::vector<bool> reported(spec.params.size(), false);
    for (const auto& [key, value] : named) {
        const Param* p = find(spec, key);
        if (p == nullptr) {
            out.errors.push_back(spec.name + " has no parameter '" + visible(key, 64) + "' (it takes " + known(spec) +
                                 ")");
            continue;
        }
        auto i = static_cast<std::size_t>(p - spec.params.data());
        if (given[i] || reported[i]) {
            out.errors.push_back("'" + p->name + "' given twice");
            continue;
        }
        given[i] = coerce(p->type, value);
        if (!given[i]) {
            out.errors.push_back(p->name + ": " + std::string(name_of(type_of(value))) + " given, " + p->name + " is " +
                                 std::string(kind_of(p->type)) + " (" + std::string(name_of(p->type)) + ")");
            reported[i] = true;
        }
    }
    return finish(spec, given, reported, std::move(out), limits);
}

Arguments complete_text(const CommandSpec& spec, const std::vector<std::string>& words, bool limits) {
    Arguments out;
    std::vector<std::optional<Value>> given(spec.params.size());
    std::vector<bool> reported(spec.params.size(), false);
    for (const auto& word : words) {
        auto eq = word.find('=');
        if (eq == std::string::npos || eq == 0) {
            out.errors.push_back("'" + visible(word, 64) + "' is not key=value (" + spec.name + " takes " +
                                 known(spec) + ")");
            continue;
        }
        std::string key = word.substr(0, eq);
        const Param* p = find(spec, key);
        if (p == nullptr) {
            out.errors.push_back(spec.name + " has no parameter '" + visible(key, 64) + "' (it takes " + known(spec) +
                                 ")");
            continue;
        }
        auto i = static_cast<std::size_t>(p - spec.params.data());
        if (given[i] || reported[i]) {
            out.errors.push_back("'" + p->name + "' given twice");
            continue;
        }
        given[i] = parse_text(p->type, std::string_view(word).substr(eq + 1));
        if (!given[i]) {
            out.errors.push_back(p->name + ": '" + visible(word.substr(eq + 1), 64) + "' is not " +
                                 std::string(kind_of(p->type)));
            reported[i] = true;
        }
    }
    return finish(spec, given, reported, std::move(out), limits);
}

}  // namespace rapid_runtime
