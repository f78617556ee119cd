//! An asset as plain data: what generated code fills in (the Rust twin of the Python runtime's
//! asset_tables.py and the C++ runtime's tables.hpp). Lookups are the runtime's.

use crate::value::{DataType, Value};

#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// as in the descriptor (KeyTypePair.key); arguments are matched by position
    pub name: String,
    pub data_type: DataType,
    pub unit: String,
    pub min: Option<f64>,
    pub max: Option<f64>,
    /// empty: any value
    pub allowed: Vec<Value>,
    pub default: Option<Value>,
    pub description: String,
}

impl Param {
    pub fn new(name: &str, data_type: DataType) -> Param {
        Param {
            name: name.into(),
            data_type,
            unit: String::new(),
            min: None,
            max: None,
            allowed: Vec::new(),
            default: None,
            description: String::new(),
        }
    }
}

#[derive(Clone, Debug, PartialEq, Default)]
pub struct CommandSpec {
    pub name: String,
    /// in the order arguments are sent
    pub params: Vec<Param>,
    pub abortable: bool,
    pub suspendable: bool,
    /// a standard RAPID subsystem type's command (the built-ins apply)
    pub standard: bool,
    pub description: String,
    /// how long [ms] the handler may run on once told to stop; 0: the manager's default
    pub stop_timeout_ms: u64,
}

#[derive(Clone, Debug, PartialEq, Default)]
pub struct SubsystemType {
    pub name: String,
    pub commands: Vec<CommandSpec>,
}

#[derive(Clone, Debug, PartialEq, Default)]
pub struct Subsystem {
    pub name: String,
    /// a SubsystemType's name
    pub type_name: String,
}

/// The descriptor's allow-list: which cmdSrc may send which "Subsystem/command" (patterns
/// "*", "Sub/*", "*/cmd", "Sub/cmd").
#[derive(Clone, Debug, PartialEq, Default)]
pub struct AccessRule {
    pub source: String,
    pub allow: Vec<String>,
}

#[derive(Clone, Debug, PartialEq, Default)]
pub struct AccessSpec {
    /// for sources no rule names
    pub allow_by_default: bool,
    pub rules: Vec<AccessRule>,
}

/// A command of the dictionary as found for a subsystem: indices into Tables.types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CommandRef {
    pub type_index: usize,
    pub command_index: usize,
}

#[derive(Clone, Debug, PartialEq, Default)]
pub struct Tables {
    /// the asset (hdr.assetName of its commands)
    pub name: String,
    pub kind: String,
    pub domain: i32,
    pub partition: String,
    /// in CommandConfig order
    pub subsystems: Vec<Subsystem>,
    pub types: Vec<SubsystemType>,
    /// None: any source may command
    pub access: Option<AccessSpec>,
}

impl Tables {
    pub fn type_of(&self, subsystem: &str) -> Option<&str> {
        self.subsystems.iter().find(|s| s.name == subsystem).map(|s| s.type_name.as_str())
    }

    pub fn subsystem_type(&self, type_name: &str) -> Option<&SubsystemType> {
        self.types.iter().find(|t| t.name == type_name)
    }

    pub fn command(&self, subsystem: &str, name: &str) -> Option<CommandRef> {
        let type_name = self.type_of(subsystem)?;
        let type_index = self.types.iter().position(|t| t.name == type_name)?;
        let command_index = self.types[type_index].commands.iter().position(|c| c.name == name)?;
        Some(CommandRef { type_index, command_index })
    }

    pub fn spec(&self, r: CommandRef) -> &CommandSpec {
        &self.types[r.type_index].commands[r.command_index]
    }

    pub fn type_name(&self, r: CommandRef) -> &str {
        &self.types[r.type_index].name
    }

    pub fn has_type(&self, type_name: &str) -> bool {
        self.subsystems.iter().any(|s| s.type_name == type_name)
    }

    pub fn subsystems_of_type(&self, type_name: &str) -> Vec<String> {
        self.subsystems.iter().filter(|s| s.type_name == type_name).map(|s| s.name.clone()).collect()
    }
}
