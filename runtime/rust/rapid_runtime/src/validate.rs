//! A received command against the asset's dictionary, in soraCore's order: subsystem, command,
//! argument count, each argument's union discriminator, then the descriptor's limits (shape,
//! range, allowed values). runtime/rapid_runtime/validate.py is the reference.

use crate::command::Cmd;
use crate::tables::{CommandRef, Tables};
use crate::text::{short, shorten};
use crate::texts;
use crate::value::{limit_error, shape_error};

/// Ok(the command's entry) for a valid command, Err(reason for COMPLETED/BAD_SYNTAX).
pub fn check_command(cmd: &Cmd, tables: &Tables) -> Result<CommandRef, String> {
    if tables.type_of(&cmd.subsystem).is_none() {
        return Err(texts::unknown_subsystem(&short(&cmd.subsystem)));
    }
    let Some(r) = tables.command(&cmd.subsystem, &cmd.name) else {
        return Err(texts::unknown_command(&short(&cmd.name), &short(&cmd.subsystem)));
    };
    let spec = tables.spec(r);
    let params = &spec.params;
    if cmd.args.len() != params.len() {
        return Err(if params.len() == 1 {
            texts::argument_count_one(&spec.name, cmd.args.len())
        } else {
            texts::argument_count(&spec.name, params.len(), cmd.args.len())
        });
    }
    for (i, (p, v)) in params.iter().zip(&cmd.args).enumerate() {
        if v.data_type() != p.data_type {
            return Err(texts::argument_type(i + 1, &shorten(&p.name, 16), p.data_type.name(), v.data_type().name()));
        }
    }
    for (i, (p, v)) in params.iter().zip(&cmd.args).enumerate() {
        if let Some(why) = shape_error(v).or_else(|| limit_error(p, v)) {
            return Err(texts::argument_invalid(i + 1, &shorten(&p.name, 16), &why));
        }
    }
    Ok(r)
}
