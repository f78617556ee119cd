// RAPID DataType values (ParameterUnion) as a std::variant whose index is the DataType,
// and the checks a command's values get: shape, then the descriptor's range and allowed
// values (runtime/rapid_runtime/values.py is the reference).
#ifndef RAPID_RUNTIME_VALUE_HPP
#define RAPID_RUNTIME_VALUE_HPP

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rapid_runtime {

// In the IDL's order (rapid-protocol.md section 2): the variant index below is the DataType.
enum class DataType : std::int32_t { Bool, Double, Float, Int, LongLong, String, Vec3d, Mat33f };
inline constexpr int DATA_TYPES = 8;

using Vec3d = std::array<double, 3>;
using Mat33f = std::array<float, 9>;
using Value = std::variant<bool, double, float, std::int32_t, std::int64_t, std::string, Vec3d, Mat33f>;

// ParameterUnion.s is a String128: at most 127 bytes.
inline constexpr std::size_t STRING_BYTES = 127;

inline DataType type_of(const Value& v) { return static_cast<DataType>(v.index()); }
std::string_view name_of(DataType t);  // "RAPID_FLOAT"; "" outside the enum

// Numerically equal (a float 0.5 equals a double 0.5 or an int 0 equals 0.0), strings and
// vectors exactly: how Python's `value in allowed` compares.
bool same_value(const Value& a, const Value& b);

// As Python's repr (values in reasons) and str (allowed values listed).
std::string repr(const Value& v);
std::string str(const Value& v);

struct Param;
// Why the value cannot be sent as its DataType (a string over 127 bytes), or nothing.
std::optional<std::string> shape_error(const Value& v);
// Why the value is outside the parameter's range (element-wise for vectors; NaN is outside
// every range) or not one of its allowed values, or nothing.
std::optional<std::string> limit_error(const Param& p, const Value& v);

}  // namespace rapid_runtime

#endif
