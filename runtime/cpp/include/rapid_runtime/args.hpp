// A command's arguments as the ground side gives them (by parameter name, typed values or
// key=value text), checked against the dictionary entry and put in the order they are
// sent, defaults filled: what rapid_cmd and dds::Client do before writing a Command
// (rapidgen cmd's arguments.py is the reference: the same wording).
#ifndef RAPID_RUNTIME_ARGS_HPP
#define RAPID_RUNTIME_ARGS_HPP

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tables.hpp"
#include "value.hpp"

namespace rapid_runtime {

using NamedValue = std::pair<std::string, Value>;

// What a parameter of type t takes, for messages: "a number", "3 numbers (x,y,z)".
std::string_view kind_of(DataType t);

// key=value text as a value of type t (true/false/1/0/yes/no/on/off; integers in C's
// bases; numbers; strings as given; vectors as "1,2,3" or "[1 2 3]"), or nothing.
std::optional<Value> parse_text(DataType t, std::string_view text);

// A value given for a parameter of type t, in t's form: numbers converted when the
// conversion keeps the value (an int to a float, a double to a float when finite, a 64-bit
// integer to 32 bits when it fits); nothing when it cannot be.
std::optional<Value> coerce(DataType t, const Value& v);

struct Arguments {
    std::vector<Value> values;  // in the order sent: the command's parameters
    std::vector<std::string> errors;  // none: values are complete and checked
    explicit operator bool() const { return errors.empty(); }
};

// The values of `spec`'s parameters from `named` (each parameter at most once), defaults
// for those not given; shape always, range and allowed values when `limits`.
Arguments complete(const CommandSpec& spec, const std::vector<NamedValue>& named, bool limits = true);

// The same from key=value words.
Arguments complete_text(const CommandSpec& spec, const std::vector<std::string>& words, bool limits = true);

}  // namespace rapid_runtime

#endif
