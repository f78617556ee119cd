// A received command against the asset's dictionary, in soraCore's order: subsystem,
// command, argument count, each argument's union discriminator, then the descriptor's
// limits (shape, range, allowed values). runtime/rapid_runtime/validate.py is the reference.
#ifndef RAPID_RUNTIME_VALIDATE_HPP
#define RAPID_RUNTIME_VALIDATE_HPP

#include <optional>
#include <string>

#include "command.hpp"
#include "tables.hpp"

namespace rapid_runtime {

struct Checked {
    CommandRef ref;  // found when the subsystem and command are known
    std::optional<std::string> why;  // the BAD_SYNTAX reason, or nothing: valid
};

Checked check_command(const Cmd& cmd, const Tables& tables);

}  // namespace rapid_runtime

#endif
