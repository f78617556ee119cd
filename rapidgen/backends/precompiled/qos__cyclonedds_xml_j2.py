# mypy: ignore-errors
# Template templates/qos/cyclonedds.xml.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "89bf86422898655957820977c25814d96cab90f7df6274c717a95855b80ce7f0"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'cyclonedds.xml.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_notice = resolve('notice')
    l_0_t = resolve('t')
    try:
        t_1 = environment.filters['xml_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'xml_comment' found.")
    try:
        t_2 = environment.tests['none']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No test named 'none' found.")
    pass
    yield '<?xml version="1.0" encoding="UTF-8"?>\n<!-- '
    yield escape(environment.finalize(t_1((undefined(name='notice') if l_0_notice is missing else l_0_notice))))
    yield ' -->\n<!-- Cyclone DDS domain configuration, transport "'
    yield escape(environment.finalize(t_1(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'name'))))
    yield '": '
    yield escape(environment.finalize(t_1(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'description'))))
    yield '\n     Use: CYCLONEDDS_URI=file://<absolute path of this file>. Ports follow the RTPS\n     well-known mapping, so a participant\'s ports are fixed by its domain id and index.\n     QoS profiles come from ../dds-xml/ (cyclonedds.qos_provider.QosProvider). -->\n<CycloneDDS xmlns="https://cdds.io/config">\n  <Domain Id="any">\n    <General>\n'
    if environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'has_interfaces'):
        pass
        yield '      <Interfaces>\n'
        for l_1_a in environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'interfaces'):
            _loop_vars = {}
            pass
            yield '        <NetworkInterface address="'
            yield escape(environment.finalize(l_1_a))
            yield '"/>\n'
        l_1_a = missing
        yield '      </Interfaces>\n'
    yield '      <AllowMulticast>'
    yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'allow_multicast')))
    yield '</AllowMulticast>\n'
    if environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'max_message_size'):
        pass
        yield '      <MaxMessageSize>'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'max_message_size')))
        yield '</MaxMessageSize>\n      <FragmentSize>'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'fragment_size')))
        yield '</FragmentSize>\n'
    yield '    </General>\n    <Discovery>\n'
    if environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'lease'):
        pass
        yield '      <LeaseDuration>'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'lease')))
        yield '</LeaseDuration>\n'
    if environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'spdp_interval'):
        pass
        yield '      <SPDPInterval>'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'spdp_interval')))
        yield '</SPDPInterval>\n'
    if environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'participant_index'):
        pass
        yield '      <ParticipantIndex>'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'participant_index')))
        yield '</ParticipantIndex>\n'
    if (not t_2(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'max_auto_participant_index'))):
        pass
        yield '      <MaxAutoParticipantIndex>'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'max_auto_participant_index')))
        yield '</MaxAutoParticipantIndex>\n'
    if environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'has_peers'):
        pass
        yield '      <Peers>\n'
        for l_1_a in environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'peers'):
            _loop_vars = {}
            pass
            yield '        <Peer Address="'
            yield escape(environment.finalize(l_1_a))
            yield '"/>\n'
        l_1_a = missing
        yield '      </Peers>\n'
    if environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'spdp_multicast_address'):
        pass
        yield '      <SPDPMulticastAddress>'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'spdp_multicast_address')))
        yield '</SPDPMulticastAddress>\n'
    if environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'ports'):
        pass
        yield '      <Ports>\n        <Base>'
        yield escape(environment.finalize(environment.getattr(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'ports'), 'base')))
        yield '</Base>\n        <DomainGain>'
        yield escape(environment.finalize(environment.getattr(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'ports'), 'domain_gain')))
        yield '</DomainGain>\n        <ParticipantGain>'
        yield escape(environment.finalize(environment.getattr(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'ports'), 'participant_gain')))
        yield '</ParticipantGain>\n        <MulticastMetaOffset>'
        yield escape(environment.finalize(environment.getattr(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'ports'), 'd0')))
        yield '</MulticastMetaOffset>\n        <UnicastMetaOffset>'
        yield escape(environment.finalize(environment.getattr(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'ports'), 'd1')))
        yield '</UnicastMetaOffset>\n        <MulticastDataOffset>'
        yield escape(environment.finalize(environment.getattr(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'ports'), 'd2')))
        yield '</MulticastDataOffset>\n        <UnicastDataOffset>'
        yield escape(environment.finalize(environment.getattr(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'ports'), 'd3')))
        yield '</UnicastDataOffset>\n      </Ports>\n'
    yield '    </Discovery>\n'
    if environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'has_internal'):
        pass
        yield '    <Internal>\n      <HeartbeatInterval minsched="'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'heartbeat')))
        yield '">'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'heartbeat')))
        yield '</HeartbeatInterval>\n      <AutoReschedNackDelay>'
        yield escape(environment.finalize(environment.getattr((undefined(name='t') if l_0_t is missing else l_0_t), 'nack_repeat')))
        yield '</AutoReschedNackDelay>\n    </Internal>\n'
    yield '  </Domain>\n</CycloneDDS>\n'

blocks = {}
debug_info = '2=26&3=28&10=32&12=35&13=39&17=44&18=46&19=49&20=51&24=54&25=57&27=59&28=62&30=64&31=67&33=69&34=72&36=74&38=77&39=81&43=85&44=88&46=90&48=93&49=95&50=97&51=99&52=101&53=103&54=105&58=108&60=111&61=115'
