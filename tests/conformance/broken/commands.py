"""Broken assets: command intake and acks (conformance/commands.py)."""
from __future__ import annotations

import dataclasses
import math
import os
import sys

from rapid_runtime.acks import COMPLETED, EXEC_FAILED, EXECUTING, NOT, OK

from . import kind


def _wrap_ack(a, change):
    """bridge.ack through change(ack, cmd, status, completed, message)."""
    ack = a.bridge.ack
    a.bridge.ack = lambda cmd, status, completed, message: change(ack, cmd, status, completed, message)


def _wrap_check(a, change):
    """The manager's command validation, with the command first passed through change(cmd)."""
    check = a.manager_module.check_command
    a.manager_module.check_command = lambda cmd, tables: check(change(cmd, tables), tables)


@kind("ack-topic-suffixed", "CMD-01")
def ack_topic_suffixed(a):
    """Acks on rapid_ack-<asset> (a per-asset suffix; 5b: the Ack topic is plain rapid_ack).
    Every command check is then BLOCKED."""
    topic = f"rapid_ack-{a.tables.name}"
    a.patch_qos(alias={topic: "rapid_ack"})
    a.B.ACK_TOPIC = topic


@kind("noop-unimplemented", "CMD-02")
def noop_unimplemented(a):
    """Admin/noOp is in the CommandConfig but answered EXEC_FAILED (checks that need a
    valid command answered OK are BLOCKED)."""
    a.manager_module.BUILTINS[("Admin", "noOp")] = lambda m, run: (EXEC_FAILED, "not implemented")


@kind("wrong-ack-order", "CMD-03")
def wrong_ack_order(a):
    def change(ack, cmd, status, completed, message):
        if status == EXECUTING:
            ack(cmd, status, completed, message)
            return ack(cmd, "ACK_QUEUED", NOT, "")
        return ack(cmd, status, completed, message)
    _wrap_ack(a, change)


@kind("ack-after-final", "CMD-04")
def ack_after_final(a):
    """An EXECUTING ack after a command's COMPLETED, once per cmdId: the stored final ack the
    runtime sends again for a resent cmdId (issue 42; CMD-10 accepts it) goes out as it was."""
    done: set[str] = set()

    def change(ack, cmd, status, completed, message):
        ack(cmd, status, completed, message)
        if status == COMPLETED and cmd.cmd_id not in done:
            done.add(cmd.cmd_id)
            ack(cmd, EXECUTING, NOT, "")
    _wrap_ack(a, change)


@kind("any-subsystem", "CMD-05")
def any_subsystem(a):
    """Commands dispatched by name alone: an unknown subsystem runs the first command of
    that name in any subsystem."""
    def change(cmd, tables):
        if tables.type_of(cmd.subsystem) is None:
            owner = next((s for s, e in tables.entries() if e.name == cmd.name), None)
            if owner is not None:
                return dataclasses.replace(cmd, subsystem=owner)
        return cmd
    _wrap_check(a, change)


@kind("unknown-command-ok", "CMD-06")
def unknown_command_ok(a):
    """A subsystem's dispatcher whose default case answers OK: an unknown command name in a
    known subsystem completes OK, doing nothing."""
    m, tables = a.manager, a.tables
    intake = m._intake

    def catch_all(cmd):
        if tables.type_of(cmd.subsystem) is not None and tables.command(cmd.subsystem, cmd.name) is None:
            m._ack(cmd, EXECUTING, NOT, "")
            m._ack(cmd, COMPLETED, OK, "")
            return None
        return intake(cmd)
    m._intake = catch_all


@kind("extra-args-ignored", "CMD-07")
def extra_args_ignored(a):
    """Arguments read by position up to the parameter count; extra ones are ignored."""
    def change(cmd, tables):
        entry = tables.command(cmd.subsystem, cmd.name)
        if entry is not None and len(cmd.args) > len(entry.params):
            return dataclasses.replace(cmd, args=cmd.args[:len(entry.params)])
        return cmd
    _wrap_check(a, change)


def _as(dtype: str, value):
    """value read as a dtype, whatever the union said (as a C++ bridge calling the union's
    accessor for the declared type would); unchanged when it cannot be."""
    if dtype == "RAPID_STRING":
        return dtype, str(value)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        if dtype in ("RAPID_FLOAT", "RAPID_DOUBLE"):
            return dtype, float(value)
        if dtype in ("RAPID_INT", "RAPID_LONGLONG") and float(value).is_integer():
            return dtype, int(value)
    return None


@kind("args-converted", "CMD-08")
def args_converted(a):
    """The union's discriminator is not checked: each value is converted to the parameter's type."""
    def change(cmd, tables):
        entry = tables.command(cmd.subsystem, cmd.name)
        if entry is None or len(cmd.args) != len(entry.params):
            return cmd
        args = tuple(arg if arg[0] == p.type else (_as(p.type, arg[1]) or arg)
                     for p, arg in zip(entry.params, cmd.args))
        return dataclasses.replace(cmd, args=args)
    _wrap_check(a, change)


@kind("other-asset-accepted", "CMD-09")
def other_asset_accepted(a):
    receive = a.manager.receive
    a.manager.receive = lambda cmd: receive(dataclasses.replace(cmd, asset_name=a.tables.name))


@kind("no-dedup", "CMD-10")
def no_dedup(a):
    seen = a.manager.seen  # the manager's window of cmdIds, whatever its class: it never says "seen"

    class Forgetful(type(seen)):
        def __contains__(self, key) -> bool:
            return False
    a.manager.seen = Forgetful(seen.size)


@kind("long-ack-message", "CMD-11")
def long_ack_message(a):
    def change(ack, cmd, status, completed, message):
        if message:
            # Astrobee's bug: 128 bytes, no terminator (bytes, cut on a character boundary: a
            # message of 128 characters, some of two bytes, could not be written at all)
            message = (message + " " + "x" * 128).encode()[:128].decode(errors="ignore")
        return ack(cmd, status, completed, message)
    _wrap_ack(a, change)


@kind("ack-names-commander", "CMD-12")
def ack_names_commander(a):
    """Ack headers with the commander's name as assetName (srcName and assetName swapped)."""
    def change(ack, cmd, status, completed, message):
        return ack(dataclasses.replace(cmd, asset_name=cmd.src_name), status, completed, message)
    _wrap_ack(a, change)


@kind("volatile-acks", "CMD-13")
def volatile_acks(a):
    from cyclonedds.qos import Policy, Qos
    a.patch_qos({"rapid_ack": Qos(Policy.Durability.Volatile)})


@kind("ack-ids-truncated", "CMD-12")
def ack_ids_truncated(a):
    """Acks carry the command's cmdId cut to 12 characters (a fixed-size buffer in a
    bridge): no ack carries a cmdId that was sent. Every check that waits for an answer is
    then BLOCKED; CMD-12 names the cmdIds seen that nobody sent."""
    def change(ack, cmd, status, completed, message):
        return ack(dataclasses.replace(cmd, cmd_id=cmd.cmd_id[:12]), status, completed, message)
    _wrap_ack(a, change)


@kind("crash-on-bad-input", "CMD-14")
def crash_on_bad_input(a):
    on_command = a.bridge._on_command

    def fragile(sample, *args, **kw):  # (the reader may pass more: whatever it passes goes on)
        if any(isinstance(x.value, float) and math.isnan(x.value) for x in sample.arguments):
            os._exit(70)  # what an unchecked float conversion in a robot's C++ bridge does
        on_command(sample, *args, **kw)
    a.bridge._on_command = fragile


@kind("ranges-unchecked", "CMD-15")
def ranges_unchecked(a):
    """Numeric parameter ranges are not enforced (allowed values still are)."""
    import rapid_runtime.validate as V
    limit = V.limit_error
    V.limit_error = lambda p, value: limit(dataclasses.replace(p, min=None, max=None), value)


@kind("astrobee-acks", None)
def astrobee_acks(a):
    """Never QUEUED; the asset's own header on acks (rapid-protocol.md 5b): must pass."""
    def change(ack, cmd, status, completed, message):
        if status == "ACK_QUEUED":
            return None
        return ack(dataclasses.replace(cmd, src_name=a.tables.name), status, completed, message)
    _wrap_ack(a, change)



@kind("odd-ack-text", None)
def odd_ack_text(a):
    """Command results cyclonedds cannot encode as Ack.message: the runtime's own commands'
    are 300 characters long, the handlers' (Mobility/stopAllMotion's, say) short but with a
    lone surrogate (text decoded with surrogateescape). The runtime clips every message
    before writing it (rapid_runtime/acks.py clip): must pass (before, ACC-06's ack was lost)."""
    long = "\udcff" + "\u00fc" * 150

    def longer(fn):
        def run(m, r):
            out = fn(m, r)
            return out if out is None else (out[0], long + out[1])
        return run
    builtins = a.manager_module.BUILTINS
    for key in list(builtins):
        builtins[key] = longer(builtins[key])
    sim = a.bridge.handlers
    run = sim.run
    sim.run = lambda ctx, entry, kw: "\udcff " + str(run(ctx, entry, kw))


@kind("allowed-unchecked", "CMD-15")
def allowed_unchecked(a):
    """Allowed values are not enforced (a string outside the list runs); ranges still are."""
    import rapid_runtime.validate as V
    limit = V.limit_error
    V.limit_error = lambda p, value: limit(dataclasses.replace(p, allowed=()), value)


@kind("minimum-unchecked", "CMD-15")
def minimum_unchecked(a):
    """Only the maximum of a range is enforced (a bridge that tests `x > max` alone)."""
    import rapid_runtime.validate as V
    limit = V.limit_error
    V.limit_error = lambda p, value: limit(dataclasses.replace(p, min=None), value)


LOST_EVERY = 20


@kind("every-20th-lost", "CMD-16")
def every_20th_lost(a):
    """Every 20th command read is lost between the reader and the manager (a ring buffer's
    off-by-one): never run, never answered. The checks that sent one are BLOCKED; CMD-16
    names each with the check that sent it."""
    intake = a.bridge.intake
    offer, count = intake.offer, [0]

    def lossy(cmd, *args, **kw):
        count[0] += 1
        if count[0] % LOST_EVERY:
            return offer(cmd, *args, **kw)
        print(f"broken: lost command {count[0]} {cmd.cmd_id!r}", file=sys.stderr, flush=True)
        return None
    intake.offer = lossy


@kind("nan-unanswered", "CMD-16")
def nan_unanswered(a):
    """A command with a NaN argument is dropped at the reader without an ack (no crash):
    only CMD-14's burst sends one, so CMD-16 names CMD-14 as its sender."""
    on_command = a.bridge._on_command

    def drop_nan(sample, *args, **kw):
        if any(isinstance(x.value, float) and math.isnan(x.value) for x in sample.arguments):
            return None
        return on_command(sample, *args, **kw)
    a.bridge._on_command = drop_nan
