# mypy: ignore-errors
# Template templates/rust/dds.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "2edf360cc156ac65860433cc36cbba546af07967e42ff08f12e792837457bd18"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'dds.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_c = resolve('c')
    l_0_asset = resolve('asset')
    pass
    yield '\n// Every struct and union of this crate: a keyed RustDDS topic type (the macro above).\nkeyed!(\n'
    for l_1_t in environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'types'):
        _loop_vars = {}
        pass
        yield '    '
        yield str(l_1_t)
        yield ',\n'
    l_1_t = missing
    yield ');\n'
    if (undefined(name='asset') if l_0_asset is missing else l_0_asset):
        pass
        yield '\n/// The asset\'s topic `name` (one of `asset::TOPICS`) carrying `T`; refused\n/// (`CreateError::BadParameter`) when the asset publishes no such topic or it carries\n/// another type. Its QoS profile is `asset::TOPICS[..].qos`.\npub fn asset_topic<T: TopicType>(dp: &DomainParticipant, name: &str, qos: &QosPolicies) -> CreateResult<Topic> {\n    let bad = |reason: ::std::string::String| ::rustdds::dds::CreateError::BadParameter { reason };\n    let t = crate::asset::TOPICS\n        .iter()\n        .find(|t| t.topic == name)\n        .ok_or_else(|| bad(format!("{} publishes no topic {name:?}", crate::asset::NAME)))?;\n    if t.type_name != T::TYPE_NAME {\n        return Err(bad(format!("topic {name:?} carries {}, not {}", t.type_name, T::TYPE_NAME)));\n    }\n    create_topic::<T>(dp, name, qos)\n}\n\n/// RustDDS QoS of one side of an asset profile (`asset::topic_qos(topic)?.writer`, ...):\n/// reliability (100 ms max blocking), durability and history. RustDDS 0.15 has no\n/// Partition QoS: such endpoints are in the default partition.\npub fn qos_of(side: &crate::asset::QosSide) -> QosPolicies {\n    let b = ::rustdds::QosPolicyBuilder::new();\n    let b = if side.reliable { b.reliable(::rustdds::Duration::from_millis(100)) } else { b.best_effort() };\n    let b = b.durability(if side.transient_local {\n        ::rustdds::policy::Durability::TransientLocal\n    } else {\n        ::rustdds::policy::Durability::Volatile\n    });\n    b.history(match side.history {\n        crate::asset::QosHistory::KeepLast(depth) => ::rustdds::policy::History::KeepLast { depth },\n        crate::asset::QosHistory::KeepAll => ::rustdds::policy::History::KeepAll,\n    })\n    .build()\n}\n'

blocks = {}
debug_info = '4=14&5=18&8=22'
