//! A received Command as plain data: what the protocol logic sees (a DDS layer builds it and,
//! for QueueState records, turns it back into a rapid::Command).

use crate::value::Value;
use crate::vocabulary::QueueAction;

#[derive(Clone, Debug, PartialEq)]
pub struct Cmd {
    pub cmd_id: String,
    pub cmd_src: String,
    pub subsystem: String,
    pub name: String,
    /// in the order sent; a Value's variant is its union discriminator
    pub args: Vec<Value>,
    pub action: QueueAction,
    /// targetCmdId
    pub target: String,
    /// hdr.srcName: the commander
    pub src_name: String,
    /// hdr.assetName: the addressed asset
    pub asset_name: String,
    pub serial: i32,
    /// hdr.timeStamp as sent
    pub stamp: i64,
}

impl Default for Cmd {
    fn default() -> Cmd {
        Cmd {
            cmd_id: String::new(),
            cmd_src: String::new(),
            subsystem: String::new(),
            name: String::new(),
            args: Vec::new(),
            action: QueueAction::Bypass,
            target: String::new(),
            src_name: String::new(),
            asset_name: String::new(),
            serial: 0,
            stamp: 0,
        }
    }
}

impl Cmd {
    /// What an ack's key needs (header names, serial, cmdId; the names for logs), without the
    /// arguments the command window would otherwise keep alive.
    pub fn key(&self) -> Cmd {
        Cmd {
            cmd_id: self.cmd_id.clone(),
            cmd_src: self.cmd_src.clone(),
            subsystem: self.subsystem.clone(),
            name: self.name.clone(),
            src_name: self.src_name.clone(),
            asset_name: self.asset_name.clone(),
            serial: self.serial,
            ..Cmd::default()
        }
    }
}
