"""A rogue writer for the monitor's page: markup and script in every string it can reach.

    python -m tests.monitor.rogue GENERATED_PYTHON_DIR PACKAGE DOMAIN SECONDS

In a partition named with markup it publishes a CommandConfig (subsystem, type, command
and parameter names with markup), an AgentConfig/AgentState (a value key with markup, a
string value with markup) and TextMessages with markup and script; it also puts one such
TextMessage into K10Red's partition, and a "picture" whose MIME type is text/html. It
also writes a few commands to K10Red (cmdId with markup) from a writer that exists before
the monitor starts: the monitor's watcher then opens rapid_command first, with its own
class, and the monitor's command writer must share that topic. Prints "rogue ready" once its writers exist."""
import importlib
import sys
import time

PARTITION = 'Rogue<img src=x onerror="document.title=\'pwned\'">'
ASSET = '<b id="pwn-asset">RogueAsset</b>'
TEXT = '<script>document.title="pwned"</script><img src=x onerror="document.title=\'pwned\'"><b id="pwn">bold?</b>'
NAME = '<i id="pwn-name">x</i>'


def main() -> int:
    pydir, package, domain, seconds = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
    sys.path.insert(0, pydir)
    from cyclonedds.domain import DomainParticipant
    from cyclonedds.pub import DataWriter, Publisher
    from cyclonedds.qos import Policy, Qos
    from cyclonedds.topic import Topic

    rapid = importlib.import_module(f"{package}.rapid")
    qos = importlib.import_module(f"{package}.qos").RapidQos()
    dp = DomainParticipant(domain)
    pub = Publisher(dp, qos=Qos(Policy.Partition([PARTITION])))
    home = Publisher(dp, qos=Qos(Policy.Partition(["K10Red"])))
    topics: dict = {}
    for name, cls in (("rapid_command_config", rapid.CommandConfig), ("rapid_agent_config", rapid.AgentConfig),
                      ("rapid_agent_state", rapid.AgentState), ("rapid_textmessage", rapid.TextMessage),
                      ("rapid_imagesensor_sample-rogue", rapid.ImageSensorSample)):
        topics[name] = Topic(dp, name, cls)
    cc = DataWriter(pub, topics["rapid_command_config"], qos=qos.writer("rapid_command_config"))
    ac = DataWriter(pub, topics["rapid_agent_config"], qos=qos.writer("rapid_agent_config"))
    st = DataWriter(pub, topics["rapid_agent_state"], qos=qos.writer("rapid_agent_state"))
    tx = DataWriter(pub, topics["rapid_textmessage"], qos=qos.writer("rapid_textmessage"))
    img = DataWriter(pub, topics["rapid_imagesensor_sample-rogue"], qos=qos.writer("rapid_imagesensor_sample-hazCam"))
    commands = DataWriter(home, Topic(dp, "rapid_command", rapid.Command), qos=qos.writer("rapid_command"))
    tx_home = DataWriter(home, topics["rapid_textmessage"], qos=qos.writer("rapid_textmessage"))

    def hdr(asset=ASSET):
        return rapid.Header(srcName=ASSET, assetName=asset, timeStamp=time.time_ns() // 1000, statusCode=0, serial=1)

    def union(text):
        return rapid.ParameterUnion(discriminator=rapid.DataType.RAPID_STRING, value=text)
    cc.write(rapid.CommandConfig(hdr=hdr(), availableSubsystemTypes=[rapid.SubsystemType(name=NAME, commands=[
        rapid.CommandDef(name=NAME, abortable=False, suspendable=False,
                         parameters=[rapid.KeyTypePair(key=NAME, type=rapid.DataType.RAPID_STRING)])])],
        availableSubsystems=[rapid.Subsystem(name=NAME, subsystemTypeName=NAME)]))
    ac.write(rapid.AgentConfig(hdr=hdr(), agentTags=[], topics=[],
                               valueKeys=[rapid.KeyTypeValueTriple(key=NAME, padding=0, value=union(""))]))
    print("rogue ready", flush=True)
    end, n = time.monotonic() + seconds, 0
    while time.monotonic() < end:
        n += 1
        st.write(rapid.AgentState(hdr=hdr(), values=[union(TEXT)]))
        msg = rapid.TextMessage(hdr=hdr(), level=rapid.MessageLevel.MSG_WARN, category=NAME, message=TEXT)
        tx.write(msg)
        img.write(rapid.ImageSensorSample(hdr=hdr(), meta=rapid.ImageMetadata(sensorName="RogueCam", sensorType=NAME,
                                                                             width=1, height=1),
                                          mimeType="text/html", data=list(TEXT.encode())))
        if n <= 3:
            commands.write(rapid.Command(hdr=hdr("K10Red"), cmdName="noOp", cmdId=NAME + str(n), cmdSrc=NAME,
                                         subsysName="Admin", arguments=[],
                                         cmdAction=rapid.QueueAction.QUEUE_BYPASS, targetCmdId=""))
        if n % 4 == 0:
            tx_home.write(rapid.TextMessage(hdr=hdr("K10Red"), level=rapid.MessageLevel.MSG_WARN, category=NAME,
                                            message=TEXT))
        time.sleep(0.25)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
