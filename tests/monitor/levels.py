"""A test asset whose agent value the test sets: AgentConfig (batteryCharge) and, four
times a second, AgentState with the last value read from stdin.

    python -m tests.monitor.levels GENERATED_PYTHON_DIR PACKAGE DOMAIN ASSET

Prints "levels ready" once its writers exist; ends at EOF."""
import importlib
import sys
import threading
import time


def main() -> int:
    pydir, package, domain, asset = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    sys.path.insert(0, pydir)
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.topic import Topic

    rapid = importlib.import_module(f"{package}.rapid")
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    dp = DomainParticipant(domain)
    pub = Publisher(dp, qos=Qos(Policy.Partition([asset])))
    config = DataWriter(pub, Topic(dp, "rapid_agent_config", rapid.AgentConfig), qos=qos.writer("rapid_agent_config"))
    state = DataWriter(pub, Topic(dp, "rapid_agent_state", rapid.AgentState), qos=qos.writer("rapid_agent_state"))

    def hdr():
        return rapid.Header(srcName=asset, assetName=asset, timeStamp=time.time_ns() // 1000, statusCode=0, serial=1)

    def value(v: float):
        return rapid.ParameterUnion(discriminator=rapid.DataType.RAPID_FLOAT, value=v)
    config.write(rapid.AgentConfig(hdr=hdr(), agentTags=[], topics=["rapid_agent_state"],
                                   valueKeys=[rapid.KeyTypeValueTriple(key="batteryCharge", padding=0,
                                                                       value=value(0.0))]))
    current = [100.0]
    done = threading.Event()

    def read():
        for line in sys.stdin:
            current[0] = float(line)
        done.set()
    threading.Thread(target=read, daemon=True).start()
    print("levels ready", flush=True)
    while not done.wait(0.25):
        state.write(rapid.AgentState(hdr=hdr(), values=[value(current[0])]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
