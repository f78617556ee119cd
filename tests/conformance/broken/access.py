"""Broken assets: access control (conformance/access.py)."""
from __future__ import annotations

from rapid_runtime.acks import EXEC_FAILED, OK

from . import kind

REQUEST, GRAB = ("AccessControl", "requestControl"), ("AccessControl", "grabControl")
RELEASE = ("AccessControl", "releaseControl")


@kind("access-state-unwritten", "ACC-01")
def access_state_unwritten(a):
    """Control is tracked but AccessControlState never written (its writer exists).
    ACC-02..06 are then BLOCKED."""
    writer = a.writer("rapid_accesscontrol_state")
    a.bridge.access_state = lambda controller, requestors: writer


@kind("request-unpublished", "ACC-02")
def request_unpublished(a):
    """requestControl grants control without writing AccessControlState (only grab and
    release do): readers never see the grant, though control is held all the same."""
    def request(m, run):
        err, note = m.control.request(run.cmd.cmd_src)
        return (EXEC_FAILED, err) if err else (OK, note)
    a.manager_module.BUILTINS[REQUEST] = request


@kind("no-control-gate", "ACC-03")
def no_control_gate(a):
    """The allow-list still holds; control is never asked for."""
    m = a.manager
    authorize = m._authorize

    def no_gate(cmd, entry):
        why = authorize(cmd, entry)
        return None if why and "does not have control" in why else why
    m._authorize = no_gate


@kind("grab-refused", "ACC-04")
def grab_refused(a):
    """grabControl only takes control nobody holds (EXEC_FAILED otherwise)."""
    grab = a.manager_module.BUILTINS[GRAB]

    def polite(m, run):
        held = m.control.controller
        if held and held != run.cmd.cmd_src:
            return EXEC_FAILED, f"control is held by {held}"
        return grab(m, run)
    a.manager_module.BUILTINS[GRAB] = polite


@kind("release-by-anyone", "ACC-05")
def release_by_anyone(a):
    """releaseControl releases whoever holds control, whoever sends it."""
    control = a.manager.control

    def release(source):
        if not control.controller:
            return "nobody has control", ""
        control.controller = control.requestors.pop(0) if control.requestors else ""
        return None, "control released"
    control.release = release


@kind("stop-needs-control", "ACC-06")
def stop_needs_control(a):
    """stopAllMotion goes through the allow-list and the control gate like any command."""
    import rapid_runtime.access as access_module  # the manager calls it through the module
    access_module.always_allowed = lambda subsystem_type, command: False


@kind("request-steals-control", "ACC-07")
def request_steals_control(a):
    """requestControl hands control to the requester even while another source holds it
    (soraCore queues the requester, Astrobee answers with a cookie: 5b)."""
    control = a.manager.control

    def request(source):
        before = control.controller
        control._give(source)
        return None, f"control granted to {source} (was {before or 'free'})"
    control.request = request


@kind("grab-unpublished", "ACC-04")
def grab_unpublished(a):
    """grabControl takes control but AccessControlState is not republished (the state keeps
    the previous controller): ACC-04 alone sees it; the runner must not trust that state when
    it takes control back later (CMD-14)."""
    def grab(m, run):
        err, note = m.control.grab(run.cmd.cmd_src)
        return (EXEC_FAILED, err) if err else (OK, note)
    a.manager_module.BUILTINS[GRAB] = grab


@kind("release-unpublished", "ACC-09")
def release_unpublished(a):
    """releaseControl works but AccessControlState is not republished: the state still names
    the source that released."""
    def release(m, run):
        err, note = m.control.release(run.cmd.cmd_src)
        return (EXEC_FAILED, err) if err else (OK, note)
    a.manager_module.BUILTINS[RELEASE] = release


@kind("former-controller-keeps-rights", "ACC-08")
def former_controller_keeps_rights(a):
    """The control gate asks whether the source ever held control: once control moved, the
    former controller's commands still run (release and transfer still need control)."""
    m, control = a.manager, a.manager.control
    ever: set[str] = set()
    give, authorize = control._give, m._authorize

    def remembered(source):
        ever.add(source)
        give(source)
    control._give = remembered

    def gate(cmd, entry):
        if cmd.cmd_src not in ever:
            return authorize(cmd, entry)
        holds = control.holds  # the gate alone asks "held it once?" (an instance attribute, removed after)
        control.holds = lambda source: source in ever or holds(source)
        try:
            return authorize(cmd, entry)
        finally:
            del control.holds
    m._authorize = gate


@kind("allow-list-ignored", "ACC-10")
def allow_list_ignored(a):
    """The descriptor's allow-list is never consulted: holding control is enough."""
    import rapid_runtime.access as access_module  # the manager calls it through the module
    access_module.allowed = lambda spec, source, subsystem, command: True
