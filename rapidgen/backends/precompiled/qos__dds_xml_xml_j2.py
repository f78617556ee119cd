# mypy: ignore-errors
# Template templates/qos/dds_xml.xml.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "1791d2219c59a3472e53843be2465e34ddfd9635174fb8e3f935b1f41d80552e"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'dds_xml.xml.j2'

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
    l_0_m = context.vars['m'] = environment.get_template('_macros.xml.j2', 'dds_xml.xml.j2')._get_default_module(context)
    context.exported_vars.discard('m')
    yield '<?xml version="1.0" encoding="UTF-8"?>\n<!-- '
    yield escape(environment.finalize(t_3((undefined(name='notice') if l_0_notice is missing else l_0_notice))))
    yield ' -->\n<!-- OMG DDS-XML 1.0 (DDS for XML) QoS library '
    yield escape(environment.finalize(t_3((undefined(name='library') if l_0_library is missing else l_0_library))))
    if (undefined(name='asset') if l_0_asset is missing else l_0_asset):
        pass
        yield ' for asset '
        yield escape(environment.finalize(t_3((undefined(name='asset') if l_0_asset is missing else l_0_asset))))
    yield '.\n     Keys are library::profile, e.g. '
    yield escape(environment.finalize(t_3((undefined(name='library') if l_0_library is missing else l_0_library))))
    yield '::RapidSampleQos. Every profile states its\n     whole QoS (its base chain resolved; DDS defaults written out), because not every\n     loader merges base_name: Cyclone DDS 11 reads base_name but does not inherit from it.\n     Cyclone DDS (Python): cyclonedds.qos_provider.QosProvider(path).get_datawriter_qos(key);\n     C: dds_create_qos_provider(path, &provider), dds_qos_provider_get_qos(...). -->\n<dds xmlns="http://www.omg.org/spec/DDS-XML" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">\n  <qos_library name="'
    yield escape(environment.finalize((undefined(name='library') if l_0_library is missing else l_0_library)))
    yield '">\n'
    for l_1_p in (undefined(name='profiles') if l_0_profiles is missing else l_0_profiles):
        _loop_vars = {}
        pass
        yield '    <!-- '
        yield escape(environment.finalize(t_3(environment.getattr(l_1_p, 'description'))))
        yield ' -->\n    <qos_profile name="'
        yield escape(environment.finalize(environment.getattr(l_1_p, 'name')))
        yield '"'
        if environment.getattr(l_1_p, 'has_base'):
            pass
            yield ' base_name="'
            yield escape(environment.finalize(environment.getattr(l_1_p, 'base_key')))
            yield '"'
        yield '>\n      <datawriter_qos>\n        '
        yield escape(environment.finalize(t_2(t_1(context.call(environment.getattr((undefined(name='m') if l_0_m is missing else l_0_m), 'omg_endpoint'), environment.getattr(l_1_p, 'writer'), _loop_vars=_loop_vars), 8))))
        yield '\n      </datawriter_qos>\n      <datareader_qos>\n        '
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
    yield '  </qos_library>\n</dds>\n'

blocks = {}
debug_info = '1=34&3=37&4=39&5=45&11=47&12=49&13=53&14=55&16=63&19=65&21=67&23=70&26=72'
