# mypy: ignore-errors
# Template templates/qos/fastdds.xml.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "260b0eeea331b6153a56fb392900ed65b0c14a51e66b5f19db53a74e54c944f0"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'fastdds.xml.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_notice = resolve('notice')
    l_0_library = resolve('library')
    l_0_asset = resolve('asset')
    l_0_transports = resolve('transports')
    l_0_participants = resolve('participants')
    l_0_profiles = resolve('profiles')
    l_0_links = resolve('links')
    l_0_streams = resolve('streams')
    l_0_m = missing
    try:
        t_1 = environment.filters['indent']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'indent' found.")
    try:
        t_2 = environment.filters['trim']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'trim' found.")
    try:
        t_3 = environment.filters['xml_comment']
    except KeyError:
        @internalcode
        def t_3(*unused):
            raise TemplateRuntimeError("No filter named 'xml_comment' found.")
    try:
        t_4 = environment.tests['none']
    except KeyError:
        @internalcode
        def t_4(*unused):
            raise TemplateRuntimeError("No test named 'none' found.")
    pass
    l_0_m = context.vars['m'] = environment.get_template('_macros.xml.j2', 'fastdds.xml.j2')._get_default_module(context)
    context.exported_vars.discard('m')
    yield '<?xml version="1.0" encoding="UTF-8"?>\n<!-- '
    yield escape(environment.finalize(t_3((undefined(name='notice') if l_0_notice is missing else l_0_notice))))
    yield ' -->\n<!-- Fast DDS 2.9 XML profiles of '
    yield escape(environment.finalize(t_3((undefined(name='library') if l_0_library is missing else l_0_library))))
    if (undefined(name='asset') if l_0_asset is missing else l_0_asset):
        pass
        yield ' for asset '
        yield escape(environment.finalize(t_3((undefined(name='asset') if l_0_asset is missing else l_0_asset))))
    yield '.\n     Load: FASTDDS_DEFAULT_PROFILES_FILE=this file, or\n     DomainParticipantFactory::get_instance()->load_XML_profiles_file(path).\n     Participants: create_participant_with_profile(domain, "rapid_<transport>");\n     writers and readers: create_publisher_with_profile / create_datawriter_with_profile\n     (and the subscriber/reader equivalents) with the RAPID profile name; topics.json maps\n     each topic to its profile. Type information: Fast DDS 2.9 sends none for types\n     without a TypeObject (hand-written ones, fastddsgen without -typeobject), so\n     matching is by type name.\n     Beyond the QoS library: every RAPID message is keyed (acks by cmdId, one instance per\n     command) and Fast DDS keeps at most 10 instances by default, so each endpoint has\n     resourceLimitsQos with no instance limit (0) and its history depth per instance\n     (keep-all: 400); bound instances in the application (unregister old acks). Reliable\n     writers are SYNCHRONOUS: Fast DDS 2.9\'s ASYNCHRONOUS mode lost acks replaced before\n     they were sent (EXECUTING then COMPLETED) for volatile Cyclone readers. -->\n<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">\n  <profiles>\n    <transport_descriptors>\n'
    for l_1_t in (undefined(name='transports') if l_0_transports is missing else l_0_transports):
        _loop_vars = {}
        pass
        yield '      <transport_descriptor>\n        <transport_id>'
        yield escape(environment.finalize(environment.getattr(l_1_t, 'id')))
        yield '</transport_id>\n        <type>'
        yield escape(environment.finalize(environment.getattr(l_1_t, 'type')))
        yield '</type>\n'
        if environment.getattr(l_1_t, 'max_message_size'):
            pass
            yield '        <maxMessageSize>'
            yield escape(environment.finalize(environment.getattr(l_1_t, 'max_message_size')))
            yield '</maxMessageSize>\n'
        if environment.getattr(l_1_t, 'max_initial_peers_range'):
            pass
            yield '        <maxInitialPeersRange>'
            yield escape(environment.finalize(environment.getattr(l_1_t, 'max_initial_peers_range')))
            yield '</maxInitialPeersRange>\n'
        if environment.getattr(l_1_t, 'interfaces'):
            pass
            yield '        <interfaceWhiteList>\n'
            for l_2_a in environment.getattr(l_1_t, 'interfaces'):
                _loop_vars = {}
                pass
                yield '          <address>'
                yield escape(environment.finalize(l_2_a))
                yield '</address>\n'
            l_2_a = missing
            yield '        </interfaceWhiteList>\n'
        if environment.getattr(l_1_t, 'listening_ports'):
            pass
            yield '        <listening_ports>\n'
            for l_2_p in environment.getattr(l_1_t, 'listening_ports'):
                _loop_vars = {}
                pass
                yield '          <port>'
                yield escape(environment.finalize(l_2_p))
                yield '</port>\n'
            l_2_p = missing
            yield '        </listening_ports>\n'
        yield '      </transport_descriptor>\n'
    l_1_t = missing
    yield '    </transport_descriptors>\n'
    for l_1_p in (undefined(name='participants') if l_0_participants is missing else l_0_participants):
        _loop_vars = {}
        pass
        yield '\n    <!-- '
        yield escape(environment.finalize(t_3(environment.getattr(l_1_p, 'description'))))
        yield ' -->\n    <participant profile_name="'
        yield escape(environment.finalize(environment.getattr(l_1_p, 'name')))
        yield '"'
        if environment.getattr(l_1_p, 'is_default'):
            pass
            yield ' is_default_profile="true"'
        yield '>\n'
        if (not t_4(environment.getattr(l_1_p, 'domain'))):
            pass
            yield '      <domainId>'
            yield escape(environment.finalize(environment.getattr(l_1_p, 'domain')))
            yield '</domainId>\n'
        yield '      <rtps>\n'
        if environment.getattr(l_1_p, 'participant_name'):
            pass
            yield '        <name>'
            yield escape(environment.finalize(environment.getattr(l_1_p, 'participant_name')))
            yield '</name>\n'
        if environment.getattr(l_1_p, 'prefix'):
            pass
            yield '        <prefix>'
            yield escape(environment.finalize(environment.getattr(l_1_p, 'prefix')))
            yield '</prefix>\n'
        if environment.getattr(l_1_p, 'has_builtin'):
            pass
            yield '        <builtin>\n          <discovery_config>\n            <discoveryProtocol>'
            yield escape(environment.finalize(environment.getattr(l_1_p, 'discovery')))
            yield '</discoveryProtocol>\n'
            if environment.getattr(l_1_p, 'servers'):
                pass
                yield '            <discoveryServersList>\n'
                for l_2_s in environment.getattr(l_1_p, 'servers'):
                    _loop_vars = {}
                    pass
                    yield '              <RemoteServer prefix="'
                    yield escape(environment.finalize(environment.getattr(l_2_s, 'prefix')))
                    yield '">\n                <metatrafficUnicastLocatorList>\n                  '
                    yield escape(environment.finalize(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'locator'), environment.getattr(l_2_s, 'locator'), _loop_vars=_loop_vars)))
                    yield '\n                </metatrafficUnicastLocatorList>\n              </RemoteServer>\n'
                l_2_s = missing
                yield '            </discoveryServersList>\n'
            if environment.getattr(l_1_p, 'lease'):
                pass
                yield '            <leaseDuration>'
                yield escape(environment.finalize(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'duration'), environment.getattr(l_1_p, 'lease'), _loop_vars=_loop_vars)))
                yield '</leaseDuration>\n            <leaseAnnouncement>'
                yield escape(environment.finalize(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'duration'), environment.getattr(l_1_p, 'announcement'), _loop_vars=_loop_vars)))
                yield '</leaseAnnouncement>\n'
            yield '          </discovery_config>\n'
            if environment.getattr(l_1_p, 'meta_unicast'):
                pass
                yield '          <metatrafficUnicastLocatorList>\n'
                for l_2_l in environment.getattr(l_1_p, 'meta_unicast'):
                    _loop_vars = {}
                    pass
                    yield '            '
                    yield escape(environment.finalize(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'locator'), l_2_l, _loop_vars=_loop_vars)))
                    yield '\n'
                l_2_l = missing
                yield '          </metatrafficUnicastLocatorList>\n'
            if environment.getattr(l_1_p, 'initial_peers'):
                pass
                yield '          <initialPeersList>\n'
                for l_2_l in environment.getattr(l_1_p, 'initial_peers'):
                    _loop_vars = {}
                    pass
                    yield '            '
                    yield escape(environment.finalize(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'locator'), l_2_l, _loop_vars=_loop_vars)))
                    yield '\n'
                l_2_l = missing
                yield '          </initialPeersList>\n'
            yield '        </builtin>\n'
        if environment.getattr(l_1_p, 'ports'):
            pass
            yield '        <port>\n          <portBase>'
            yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'base')))
            yield '</portBase>\n          <domainIDGain>'
            yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'domain_gain')))
            yield '</domainIDGain>\n          <participantIDGain>'
            yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'participant_gain')))
            yield '</participantIDGain>\n          <offsetd0>'
            yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd0')))
            yield '</offsetd0>\n          <offsetd1>'
            yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd1')))
            yield '</offsetd1>\n          <offsetd2>'
            yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd2')))
            yield '</offsetd2>\n          <offsetd3>'
            yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd3')))
            yield '</offsetd3>\n        </port>\n'
        if environment.getattr(l_1_p, 'default_unicast'):
            pass
            yield '        <defaultUnicastLocatorList>\n'
            for l_2_l in environment.getattr(l_1_p, 'default_unicast'):
                _loop_vars = {}
                pass
                yield '          '
                yield escape(environment.finalize(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'locator'), l_2_l, _loop_vars=_loop_vars)))
                yield '\n'
            l_2_l = missing
            yield '        </defaultUnicastLocatorList>\n'
        yield '        <userTransports>\n          <transport_id>'
        yield escape(environment.finalize(environment.getattr(l_1_p, 'transport')))
        yield '</transport_id>\n        </userTransports>\n        <useBuiltinTransports>false</useBuiltinTransports>\n'
        if environment.getattr(l_1_p, 'link'):
            pass
            yield '        <propertiesPolicy>\n          <properties>\n            <!-- the endpoint profiles <profile>@'
            yield escape(environment.finalize(environment.getattr(l_1_p, 'link')))
            yield " carry this link's timers (docs/qos.md) -->\n            <property><name>rapid.link</name><value>"
            yield escape(environment.finalize(environment.getattr(l_1_p, 'link')))
            yield '</value></property>\n          </properties>\n        </propertiesPolicy>\n'
        yield '      </rtps>\n    </participant>\n'
    l_1_p = missing
    for l_1_p in (undefined(name='profiles') if l_0_profiles is missing else l_0_profiles):
        _loop_vars = {}
        pass
        yield '\n    <!-- '
        yield escape(environment.finalize(t_3(environment.getattr(l_1_p, 'key'))))
        if environment.getattr(l_1_p, 'description'):
            pass
            yield ': '
            yield escape(environment.finalize(t_3(environment.getattr(l_1_p, 'description'))))
        if environment.getattr(l_1_p, 'has_base'):
            pass
            yield ' (base '
            yield escape(environment.finalize(t_3(environment.getattr(l_1_p, 'base_key'))))
            yield ')'
        yield ' -->\n    <data_writer profile_name="'
        yield escape(environment.finalize(environment.getattr(l_1_p, 'name')))
        yield '">\n      '
        yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'fastdds_endpoint'), environment.getattr(l_1_p, 'writer'), l_1_p, _loop_vars=_loop_vars), 6))))
        yield '\n    </data_writer>\n    <data_reader profile_name="'
        yield escape(environment.finalize(environment.getattr(l_1_p, 'name')))
        yield '">\n      '
        yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'fastdds_endpoint'), environment.getattr(l_1_p, 'reader'), l_1_p, _loop_vars=_loop_vars), 6))))
        yield '\n    </data_reader>\n'
    l_1_p = missing
    for l_1_l in (undefined(name='links') if l_0_links is missing else l_0_links):
        _loop_vars = {}
        pass
        yield '\n    <!-- transport '
        yield escape(environment.finalize(t_3(environment.getattr(l_1_l, 'transport'))))
        yield ": every profile again with its link's timers (rtt), named <profile>@"
        yield escape(environment.finalize(t_3(environment.getattr(l_1_l, 'transport'))))
        yield ' -->\n'
        for l_2_p in (undefined(name='profiles') if l_0_profiles is missing else l_0_profiles):
            _loop_vars = {}
            pass
            yield '    <data_writer profile_name="'
            yield escape(environment.finalize(environment.getattr(l_2_p, 'name')))
            yield '@'
            yield escape(environment.finalize(environment.getattr(l_1_l, 'transport')))
            yield '">\n      '
            yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'fastdds_endpoint'), environment.getattr(l_2_p, 'writer'), l_2_p, l_1_l, _loop_vars=_loop_vars), 6))))
            yield '\n      <times>\n        <heartbeatPeriod>'
            yield escape(environment.finalize(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'duration'), environment.getattr(l_1_l, 'heartbeat'), _loop_vars=_loop_vars)))
            yield '</heartbeatPeriod>\n        <nackSupressionDuration>'
            yield escape(environment.finalize(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'duration'), environment.getattr(l_1_l, 'nack_suppression'), _loop_vars=_loop_vars)))
            yield '</nackSupressionDuration>\n      </times>\n    </data_writer>\n    <data_reader profile_name="'
            yield escape(environment.finalize(environment.getattr(l_2_p, 'name')))
            yield '@'
            yield escape(environment.finalize(environment.getattr(l_1_l, 'transport')))
            yield '">\n      '
            yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'fastdds_endpoint'), environment.getattr(l_2_p, 'reader'), l_2_p, _loop_vars=_loop_vars), 6))))
            yield '\n    </data_reader>\n'
        l_2_p = missing
    l_1_l = missing
    for l_1_s in (undefined(name='streams') if l_0_streams is missing else l_0_streams):
        _loop_vars = {}
        pass
        yield '\n    <!-- '
        yield escape(environment.finalize(t_3(environment.getattr(l_1_s, 'description'))))
        yield ': best effort, keep last 1, DEADLINE, LIVELINESS, preallocated -->\n    <data_writer profile_name="'
        yield escape(environment.finalize(environment.getattr(l_1_s, 'name')))
        yield '">\n      <topic>\n        <historyQos>\n          <kind>KEEP_LAST</kind>\n          <depth>1</depth>\n        </historyQos>\n        <resourceLimitsQos>\n          <max_samples>1</max_samples>\n          <max_instances>1</max_instances>\n          <max_samples_per_instance>1</max_samples_per_instance>\n          <allocated_samples>1</allocated_samples>\n        </resourceLimitsQos>\n      </topic>\n      <qos>\n        <reliability>\n          <kind>BEST_EFFORT</kind>\n        </reliability>\n        <durability>\n          <kind>VOLATILE</kind>\n        </durability>\n        <deadline>\n          <period><sec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'deadline'), 'sec')))
        yield '</sec><nanosec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'deadline'), 'nanosec')))
        yield '</nanosec></period>\n        </deadline>\n        <liveliness>\n          <kind>AUTOMATIC</kind>\n          <lease_duration><sec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'lease'), 'sec')))
        yield '</sec><nanosec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'lease'), 'nanosec')))
        yield '</nanosec></lease_duration>\n          <announcement_period><sec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'announcement'), 'sec')))
        yield '</sec><nanosec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'announcement'), 'nanosec')))
        yield '</nanosec></announcement_period>\n        </liveliness>\n        <publishMode>\n          <kind>SYNCHRONOUS</kind>\n        </publishMode>\n        <partition>\n          <names>\n            <name>'
        yield escape(environment.finalize(environment.getattr(l_1_s, 'writer_partition')))
        yield '</name>\n          </names>\n        </partition>\n      </qos>\n      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>\n    </data_writer>\n    <data_reader profile_name="'
        yield escape(environment.finalize(environment.getattr(l_1_s, 'name')))
        yield '">\n      <topic>\n        <historyQos>\n          <kind>KEEP_LAST</kind>\n          <depth>1</depth>\n        </historyQos>\n        <resourceLimitsQos>\n          <max_samples>'
        yield escape(environment.finalize(environment.getattr(l_1_s, 'reader_instances')))
        yield '</max_samples>\n          <max_instances>'
        yield escape(environment.finalize(environment.getattr(l_1_s, 'reader_instances')))
        yield '</max_instances>\n          <max_samples_per_instance>1</max_samples_per_instance>\n          <allocated_samples>'
        yield escape(environment.finalize(environment.getattr(l_1_s, 'reader_instances')))
        yield '</allocated_samples>\n        </resourceLimitsQos>\n      </topic>\n      <qos>\n        <reliability>\n          <kind>BEST_EFFORT</kind>\n        </reliability>\n        <durability>\n          <kind>VOLATILE</kind>\n        </durability>\n        <deadline>\n          <period><sec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'deadline'), 'sec')))
        yield '</sec><nanosec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'deadline'), 'nanosec')))
        yield '</nanosec></period>\n        </deadline>\n        <liveliness>\n          <kind>AUTOMATIC</kind>\n          <lease_duration><sec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'lease'), 'sec')))
        yield '</sec><nanosec>'
        yield escape(environment.finalize(environment.getattr(environment.getattr(l_1_s, 'lease'), 'nanosec')))
        yield '</nanosec></lease_duration>\n        </liveliness>\n        <partition>\n          <names>\n            <name>'
        yield escape(environment.finalize(environment.getattr(l_1_s, 'reader_partition')))
        yield '</name>\n          </names>\n        </partition>\n      </qos>\n      <historyMemoryPolicy>PREALLOCATED_WITH_REALLOC</historyMemoryPolicy>\n    </data_reader>\n'
    l_1_s = missing
    yield '  </profiles>\n</dds>\n'

blocks = {}
debug_info = '1=44&3=47&4=49&22=55&24=59&25=61&26=63&27=66&29=68&30=71&32=73&34=76&35=80&39=84&41=87&42=91&49=98&51=102&52=104&53=110&54=113&57=116&58=119&60=121&61=124&63=126&66=129&67=131&69=134&70=138&72=140&78=144&79=147&80=149&83=152&85=155&86=159&90=163&92=166&93=170&99=175&101=178&102=180&103=182&104=184&105=186&106=188&107=190&110=192&112=195&113=199&118=204&121=206&124=209&125=211&132=215&134=219&135=230&136=232&138=234&139=236&142=239&144=243&145=247&146=251&147=255&149=257&150=259&153=261&154=265&158=269&160=273&161=275&182=277&186=281&187=285&194=289&200=291&207=293&208=295&210=297&221=299&225=303&229=307'
