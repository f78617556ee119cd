# mypy: ignore-errors
# Template templates/rust/asset.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "c5d6a976d2bb2c08f2054a51ea2120f61772c00b0731f1726e0ac4e8733ab912"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'asset.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_c = resolve('c')
    l_0_a = resolve('a')
    try:
        t_1 = environment.filters['rust_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'rust_comment' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'header')))
    yield "\n//! The asset's description as data: its topics, command dictionary and computed configs\n//! (docs/rust-backend.md).\n// the descriptor's numbers as declared (a range of +-3.141592653589793 is not meant as PI)\n#![allow(clippy::approx_constant)]\n\n/// A topic the asset publishes.\n#[derive(Debug, Clone, Copy, PartialEq)]\npub struct Topic {\n    /// config, sample, state or ack\n    pub role: &'static str,\n    /// the DDS type name (IDL scoped name)\n    pub type_name: &'static str,\n    pub topic: &'static str,\n    /// the QoS profile\n    pub qos: &'static str,\n    /// Hz; None: on start-up and on change\n    pub rate: Option<f64>,\n}\n\n/// A command parameter: its RAPID DataType and limits.\n#[derive(Debug, Clone, Copy, PartialEq)]\npub struct Parameter {\n    pub name: &'static str,\n    pub data_type: &'static str,\n    pub unit: Option<&'static str>,\n    pub min: Option<f64>,\n    pub max: Option<f64>,\n}\n\n/// A command of a subsystem type.\n#[derive(Debug, Clone, Copy, PartialEq)]\npub struct Command {\n    pub subsystem_type: &'static str,\n    pub name: &'static str,\n    pub abortable: bool,\n    pub suspendable: bool,\n    pub parameters: &'static [Parameter],\n}\n\n/// History of one side of a QoS profile.\n#[derive(Debug, Clone, Copy, PartialEq, Eq)]\npub enum QosHistory {\n    KeepLast(i32),\n    KeepAll,\n}\n\n/// One side (writer or reader) of a QoS profile, resolved from the RAPID QoS library as the\n/// generated QoS files have it; the partition is `PARTITION`.\n#[derive(Debug, Clone, Copy, PartialEq, Eq)]\npub struct QosSide {\n    pub reliable: bool,\n    pub transient_local: bool,\n    pub history: QosHistory,\n}\n\n/// A QoS profile a topic of the asset names (`Topic::qos`).\n#[derive(Debug, Clone, Copy, PartialEq, Eq)]\npub struct QosProfile {\n    pub name: &'static str,\n    pub writer: QosSide,\n    pub reader: QosSide,\n}\n\npub const NAME: &str = "
    yield str(environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'name'))
    yield ';\npub const DOMAIN: u32 = '
    yield str(environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'domain'))
    yield ';\npub const PARTITION: &str = '
    yield str(environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'partition'))
    yield ';\n\n/// Subsystem name and subsystem type.\npub const SUBSYSTEMS: &[(&str, &str)] = &[\n'
    for (l_1_n, l_1_t) in environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'subsystems'):
        _loop_vars = {}
        pass
        yield '    ('
        yield str(l_1_n)
        yield ', '
        yield str(l_1_t)
        yield '),\n'
    l_1_n = l_1_t = missing
    yield '];\n\npub const TOPICS: &[Topic] = &[\n'
    for (l_1_role, l_1_ty, l_1_topic, l_1_qos, l_1_rate) in environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'topics'):
        _loop_vars = {}
        pass
        yield '    Topic { role: '
        yield str(l_1_role)
        yield ', type_name: '
        yield str(l_1_ty)
        yield ', topic: '
        yield str(l_1_topic)
        yield ', qos: '
        yield str(l_1_qos)
        yield ', rate: '
        yield str(l_1_rate)
        yield ' },\n'
    l_1_role = l_1_ty = l_1_topic = l_1_qos = l_1_rate = missing
    yield '];\n\n/// The QoS profiles the topics name, as the generated QoS library resolves them.\npub const QOS_PROFILES: &[QosProfile] = &[\n'
    for l_1_q in environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'profiles'):
        _loop_vars = {}
        pass
        yield '    QosProfile { name: '
        yield str(environment.getattr(l_1_q, 'name'))
        yield ', writer: '
        yield str(environment.getattr(l_1_q, 'writer'))
        yield ', reader: '
        yield str(environment.getattr(l_1_q, 'reader'))
        yield ' },\n'
    l_1_q = missing
    yield "];\n\n/// A profile by name.\npub fn qos_profile(name: &str) -> Option<&'static QosProfile> {\n    QOS_PROFILES.iter().find(|q| q.name == name)\n}\n\n/// The profile of one of the asset's topics.\npub fn topic_qos(topic: &str) -> Option<&'static QosProfile> {\n    TOPICS.iter().find(|t| t.topic == topic).and_then(|t| qos_profile(t.qos))\n}\n\npub const COMMANDS: &[Command] = &[\n"
    for l_1_cmd in environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'commands'):
        _loop_vars = {}
        pass
        yield '    Command {\n        subsystem_type: '
        yield str(environment.getattr(l_1_cmd, 'subsystem_type'))
        yield ',\n        name: '
        yield str(environment.getattr(l_1_cmd, 'name'))
        yield ',\n        abortable: '
        yield str(('true' if environment.getattr(l_1_cmd, 'abortable') else 'false'))
        yield ',\n        suspendable: '
        yield str(('true' if environment.getattr(l_1_cmd, 'suspendable') else 'false'))
        yield ',\n        parameters: &[\n'
        for l_2_p in environment.getattr(l_1_cmd, 'parameters'):
            _loop_vars = {}
            pass
            yield '            Parameter { name: '
            yield str(environment.getattr(l_2_p, 'name'))
            yield ', data_type: '
            yield str(environment.getattr(l_2_p, 'data_type'))
            yield ', unit: '
            yield str(environment.getattr(l_2_p, 'unit'))
            yield ', min: '
            yield str(environment.getattr(l_2_p, 'min'))
            yield ', max: '
            yield str(environment.getattr(l_2_p, 'max'))
            yield ' },\n'
        l_2_p = missing
        yield '        ],\n    },\n'
    l_1_cmd = missing
    yield '];\n'
    for l_1_cfg in environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'configs'):
        _loop_vars = {}
        pass
        yield '\n/// The config published on '
        yield str(t_1(environment.getattr(l_1_cfg, 'topic')))
        yield ' ('
        yield str(t_1(environment.getattr(l_1_cfg, 'type_name')))
        yield ').\npub fn '
        yield str(environment.getattr(l_1_cfg, 'function'))
        yield '() -> '
        yield str(environment.getattr(l_1_cfg, 'type'))
        yield ' {\n    '
        yield str(environment.getattr(l_1_cfg, 'value'))
        yield '\n}\n'
    l_1_cfg = missing
    yield "\n/// Every config: topic and encoded sample (CDR_LE), as the asset publishes them.\npub fn configs() -> ::core::result::Result<::std::vec::Vec<(&'static str, ::std::vec::Vec<u8>)>, crate::cdr::EncodeError> {\n    Ok(::std::vec![\n"
    for l_1_cfg in environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'configs'):
        _loop_vars = {}
        pass
        yield '        ('
        yield str(environment.getattr(l_1_cfg, 'topic'))
        yield ', crate::cdr::serialize(&'
        yield str(environment.getattr(l_1_cfg, 'function'))
        yield '(), crate::cdr::Endianness::Little)?),\n'
    l_1_cfg = missing
    yield "    ])\n}\n\n/// Extension telemetry a simulated robot publishes (`<crate>_bridge --simulate`): topic, DDS\n/// type name, keyed, a message with plausible values (CDR_LE, the header left at its default).\n#[allow(clippy::type_complexity)]\npub fn simulated() -> ::core::result::Result<::std::vec::Vec<(&'static str, &'static str, bool, ::std::vec::Vec<u8>)>, crate::cdr::EncodeError> {\n    Ok(::std::vec![\n"
    for l_1_s in environment.getattr((undefined(name='a') if l_0_a is missing else l_0_a), 'simulated'):
        _loop_vars = {}
        pass
        yield '        ('
        yield str(environment.getattr(l_1_s, 'topic'))
        yield ', <'
        yield str(environment.getattr(l_1_s, 'type'))
        yield ' as crate::cdr::Cdr>::TYPE_NAME, <'
        yield str(environment.getattr(l_1_s, 'type'))
        yield ' as crate::cdr::Cdr>::KEYED, crate::cdr::serialize(&'
        yield str(environment.getattr(l_1_s, 'value'))
        yield ', crate::cdr::Endianness::Little)?),\n'
    l_1_s = missing
    yield '    ])\n}\n'

blocks = {}
debug_info = '1=20&65=22&66=24&67=26&71=28&72=32&77=38&78=42&84=54&85=58&100=66&102=70&103=72&104=74&105=76&107=78&108=82&114=96&116=100&117=104&118=108&125=112&126=116&136=122&137=126'
