"""Rogues for issue 34: a participant that tries to mislead or blind the monitor's operator.

    python -m tests.monitor.hostile GENERATED_PYTHON_DIR PACKAGE DOMAIN SECONDS MODE[,MODE...]

Modes:
  listen   reads rapid_command in K10Red and prints "command NAME ARGS" for each command seen
           (the wire, as K10 sees it)
  swap     on a line "swap" from stdin, publishes K10Red's CommandConfig (the descriptor's,
           from the package's tables) with PanCam/pointCamera's parameters reversed
           (tilt, pan), from a writer of its own; prints "swapped"
  decoys   66 decoy partitions (Decoy00..Decoy65), each with an AgentState writer: 64 fill the
           watcher's and the page's limits, 2 more are left out
  flood    on a line "flood" from stdin, 260 topic names (rapid_agent_state-flood000..259) in
           the partition Decoy00: with the decoys, more readers than the watcher's 256; prints
           "flooded"
  churn    the partition Churn: an AgentConfig of 64 keys renamed with every sample, and an
           AgentState with their 64 values, 4 times a second

Prints "hostile ready" once its writers exist; ends after SECONDS or at EOF on stdin."""
import importlib
import sys
import threading
import time

DECOYS = 66
FLOOD = "Decoy00"
FLOOD_TOPICS = 260
CHURN_KEYS = 64
HOME = "K10Red"


def main() -> int:
    pydir, package, domain, seconds = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    modes = set(sys.argv[5].split(","))
    sys.path.insert(0, pydir)
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.sub import DataReader, Subscriber
    from cyclonedds.topic import Topic
    from rapid_runtime import messages as M

    rapid = importlib.import_module(f"{package}.rapid")
    tables = importlib.import_module(f"{package}.asset_tables")
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    dp = DomainParticipant(domain)
    topics: dict = {}

    def topic(name, cls):
        if name not in topics:
            topics[name] = Topic(dp, name, cls)
        return topics[name]

    def writer(partition, name, cls, profile=None):
        return DataWriter(Publisher(dp, qos=Qos(Policy.Partition([partition]))), topic(name, cls),
                          qos=qos.writer(profile or name))

    def hdr(asset):
        return rapid.Header(srcName="hostile", assetName=asset, timeStamp=time.time_ns() // 1000, statusCode=0,
                            serial=1)

    def floats(n, base):
        return [rapid.ParameterUnion(discriminator=rapid.DataType.RAPID_FLOAT, value=float(base + i)) for i in range(n)]

    commands = None
    if "listen" in modes:
        sub = Subscriber(dp, qos=Qos(Policy.Partition([HOME])))
        commands = DataReader(sub, topic("rapid_command", rapid.Command), qos=qos.reader("rapid_command"))
    swap_cc = writer(HOME, "rapid_command_config", rapid.CommandConfig) if "swap" in modes else None
    decoys = [writer(f"Decoy{i:02d}", "rapid_agent_state", rapid.AgentState) for i in range(DECOYS)] \
        if "decoys" in modes else []
    flood: list = []
    churn_cfg = writer("Churn", "rapid_agent_config", rapid.AgentConfig) if "churn" in modes else None
    churn_st = writer("Churn", "rapid_agent_state", rapid.AgentState) if "churn" in modes else None

    swap, flood_now = threading.Event(), threading.Event()
    done = threading.Event()

    def read_stdin():
        for line in sys.stdin:
            if line.strip() == "swap":
                swap.set()
            elif line.strip() == "flood":
                flood_now.set()
        done.set()
    threading.Thread(target=read_stdin, daemon=True).start()
    print("hostile ready", flush=True)
    end, n, swapped = time.monotonic() + seconds, 0, False
    while time.monotonic() < end and not done.is_set():
        n += 1
        if swap_cc is not None and swap.is_set() and not swapped:
            value = _swapped(tables.CONFIGS["rapid_command_config"]["value"])
            swap_cc.write(M.config(rapid, "rapid::CommandConfig", value, hdr(HOME)))
            swapped = True
            print("swapped", flush=True)
        if "flood" in modes and flood_now.is_set() and not flood:
            flood = [writer(FLOOD, f"rapid_agent_state-flood{i:03d}", rapid.AgentState, "rapid_agent_state")
                     for i in range(FLOOD_TOPICS)]
            print("flooded", flush=True)
        if commands is not None:
            for s in commands.take(32):
                if isinstance(s, rapid.Command):
                    args = [getattr(a, "value", None) for a in s.arguments]
                    print(f"command {s.cmdName} {args}", flush=True)
        if n % 4 == 0:
            for i, w in enumerate(decoys):
                w.write(rapid.AgentState(hdr=hdr(f"Decoy{i:02d}"), values=floats(1, i)))
            for w in flood:
                w.write(rapid.AgentState(hdr=hdr(FLOOD), values=floats(1, 0)))
        if churn_cfg is not None and churn_st is not None:
            keys = [rapid.KeyTypeValueTriple(key=f"churn{n}_{i}", padding=0, value=floats(1, 0)[0])
                    for i in range(CHURN_KEYS)]
            churn_cfg.write(rapid.AgentConfig(hdr=hdr("Churn"), agentTags=[], topics=["rapid_agent_state"],
                                              valueKeys=keys))
            churn_st.write(rapid.AgentState(hdr=hdr("Churn"), values=floats(CHURN_KEYS, n)))
        time.sleep(0.25)
    return 0


def _swapped(config: dict) -> dict:
    """K10's CommandConfig with PanTiltCamera/pointCamera's parameters in reverse order."""
    import copy
    out = copy.deepcopy(config)
    for t in out["availableSubsystemTypes"]:
        for c in t["commands"]:
            if c["name"] == "pointCamera":
                c["parameters"].reverse()
    return out


if __name__ == "__main__":
    raise SystemExit(main())
