# mypy: ignore-errors
# Template templates/qos/rti.xml.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "bf4f7399af9c0d4c21b04baa98553bd35e41f048513861a4d5a69ca99f630c7d"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'rti.xml.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_notice = resolve('notice')
    l_0_library = resolve('library')
    l_0_asset = resolve('asset')
    l_0_profiles = resolve('profiles')
    l_0_transports = resolve('transports')
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
    pass
    l_0_m = context.vars['m'] = environment.get_template('_macros.xml.j2', 'rti.xml.j2')._get_default_module(context)
    context.exported_vars.discard('m')
    yield '<?xml version="1.0" encoding="UTF-8"?>\n<!-- '
    yield escape(environment.finalize(t_3((undefined(name='notice') if l_0_notice is missing else l_0_notice))))
    yield " -->\n<!-- RTI Connext DDS QoS profiles in RAPID's original form: qos_library "
    yield escape(environment.finalize(t_3((undefined(name='library') if l_0_library is missing else l_0_library))))
    yield ',\n     each profile stating what it adds to its base_name'
    if (undefined(name='asset') if l_0_asset is missing else l_0_asset):
        pass
        yield '; asset '
        yield escape(environment.finalize(t_3((undefined(name='asset') if l_0_asset is missing else l_0_asset))))
    yield '.\n     Connext loads USER_QOS_PROFILES.xml from the working folder, or set\n     NDDS_QOS_PROFILES=path. Participants: a Rapid*TransportQos profile; writers and\n     readers: the RAPID profile topics.json names. -->\n<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">\n  <qos_library name="'
    yield escape(environment.finalize((undefined(name='library') if l_0_library is missing else l_0_library)))
    yield '">\n'
    for l_1_p in (undefined(name='profiles') if l_0_profiles is missing else l_0_profiles):
        _loop_vars = {}
        pass
        yield '\n    <!-- '
        yield escape(environment.finalize(t_3(environment.getattr(l_1_p, 'description'))))
        yield ' -->\n    <qos_profile name="'
        yield escape(environment.finalize(environment.getattr(l_1_p, 'name')))
        yield '"'
        if environment.getattr(l_1_p, 'has_base'):
            pass
            yield ' base_name="'
            yield escape(environment.finalize(environment.getattr(l_1_p, 'base_key')))
            yield '"'
        yield '>\n'
        if environment.getattr(l_1_p, 'rti_participant'):
            pass
            yield '      <participant_qos>\n        '
            yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'rti_participant'), environment.getattr(l_1_p, 'rti_participant'), _loop_vars=_loop_vars), 8))))
            yield '\n      </participant_qos>\n'
        if (not environment.getattr(environment.getattr(l_1_p, 'writer'), 'empty')):
            pass
            yield '      <datawriter_qos>\n        '
            yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'omg_endpoint'), environment.getattr(l_1_p, 'writer'), _loop_vars=_loop_vars), 8))))
            yield '\n      </datawriter_qos>\n'
        if (not environment.getattr(environment.getattr(l_1_p, 'reader'), 'empty')):
            pass
            yield '      <datareader_qos>\n        '
            yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'omg_endpoint'), environment.getattr(l_1_p, 'reader'), _loop_vars=_loop_vars), 8))))
            yield '\n      </datareader_qos>\n'
        if environment.getattr(l_1_p, 'has_partition'):
            pass
            yield '      <publisher_qos>\n        '
            yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'omg_partition'), environment.getattr(l_1_p, 'partition'), _loop_vars=_loop_vars), 8))))
            yield '\n      </publisher_qos>\n      <subscriber_qos>\n        '
            yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'omg_partition'), environment.getattr(l_1_p, 'partition'), _loop_vars=_loop_vars), 8))))
            yield '\n      </subscriber_qos>\n'
        yield '    </qos_profile>\n'
    l_1_p = missing
    for l_1_t in (undefined(name='transports') if l_0_transports is missing else l_0_transports):
        _loop_vars = {}
        pass
        yield '\n    <!-- transport '
        yield escape(environment.finalize(t_3(environment.getattr(l_1_t, 'description'))))
        if environment.getattr(l_1_t, 'tcp_note'):
            pass
            yield ' (RTI: UDP unicast; the TCP variant is for Fast DDS only)'
        yield ' -->\n    <qos_profile name="'
        yield escape(environment.finalize(environment.getattr(l_1_t, 'name')))
        yield '" base_name="'
        yield escape(environment.finalize(environment.getattr(l_1_t, 'base_key')))
        yield '"'
        if environment.getattr(l_1_t, 'is_default'):
            pass
            yield ' is_default_qos="true"'
        yield '>\n      <participant_qos>\n        '
        yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'rti_participant'), environment.getattr(l_1_t, 'participant'), _loop_vars=_loop_vars), 8))))
        yield '\n      </participant_qos>\n    </qos_profile>\n'
    l_1_t = missing
    yield '  </qos_library>\n</dds>\n'

blocks = {}
debug_info = '1=35&3=38&4=40&5=42&10=47&11=49&13=53&14=55&15=63&17=66&20=68&22=71&25=73&27=76&30=78&32=81&35=83&40=87&42=91&43=96&45=104'
