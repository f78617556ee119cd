# mypy: ignore-errors
# Template templates/qos/fastdds.xml.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "5c0ed371b2252ea252a8d517b8d8c7d07af2319363124e3e653bc9da18140e02"
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
        yield '</transport_id>\n        </userTransports>\n        <useBuiltinTransports>false</useBuiltinTransports>\n      </rtps>\n    </participant>\n'
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
debug_info = '1=43&3=46&4=48&22=54&24=58&25=60&26=62&27=65&29=67&30=70&32=72&34=75&35=79&39=83&41=86&42=90&49=97&51=101&52=103&53=109&54=112&57=115&58=118&60=120&61=123&63=125&66=128&67=130&69=133&70=137&72=139&79=144&81=147&82=151&86=155&88=158&89=162&95=167&97=170&98=172&99=174&100=176&101=178&102=180&103=182&106=184&108=187&109=191&114=196&120=199&122=203&123=214&124=216&126=218&127=220&130=223&132=227&133=229&154=231&158=235&159=239&166=243&172=245&179=247&180=249&182=251&193=253&197=257&201=261'
