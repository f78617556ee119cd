# mypy: ignore-errors
# Template templates/rust/bridge/main.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "813e2942988f0674a8d63a1e322c53a33caab82f6c83199f52e380cf92c054d3"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/main.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_c = resolve('c')
    l_0_v = resolve('v')
    try:
        t_1 = environment.filters['rust_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'rust_comment' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'header')))
    yield '\n//! `'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'bridge'))
    yield ' [--simulate] [--domain N] [--transport local|lan|wan] [--tables FILE]`:\n//! asset '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ' on the Rust runtime (rapid_dds::bridge): its configs, the command\n//! manager on the handlers of handlers.rs (or a simulated robot and its telemetry).\nmod dispatch;\nmod handlers;\nmod tables;\nmod transports;\n\n'
    if (not environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams')):
        pass
        yield 'use std::sync::Arc;\n\n'
    yield 'use '
    yield str(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'crate'))
    yield '::asset::{self, QosHistory};\nuse rapid_dds::bridge::{self, Asset};\nuse rapid_dds::dds::Side;\nuse rapid_dds::telemetry::Custom;\n\n/// The writer side of a topic\'s QoS profile (asset::QOS_PROFILES).\nfn writer_side(topic: &str) -> Option<Side> {\n    asset::topic_qos(topic).map(|q| Side {\n        reliable: q.writer.reliable,\n        transient_local: q.writer.transient_local,\n        depth: match q.writer.history {\n            QosHistory::KeepLast(n) => Some(n),\n            QosHistory::KeepAll => None,\n        },\n    })\n}\n\nfn asset() -> Result<Asset, String> {\n    let mut configs = Vec::new();\n    for (topic, bytes) in asset::configs().map_err(|e| format!("configs: {e}"))? {\n        let t = asset::TOPICS.iter().find(|t| t.topic == topic).ok_or(format!("config {topic}: not a topic"))?;\n        configs.push((topic, t.type_name, bytes));\n    }\n    let customs = asset::simulated()\n        .map_err(|e| format!("simulated telemetry: {e}"))?\n        .into_iter()\n        .map(|(topic, type_name, keyed, bytes)| Custom {\n            topic: topic.into(),\n            type_name: type_name.into(),\n            keyed,\n            make: Box::new(move || Ok(bytes.clone())),\n        })\n        .collect();\n    Ok(Asset { tables_json: tables::JSON, configs, qos: writer_side, transports: transports::ALL, customs })\n}\n\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        yield 'fn main() {\n    // make_handlers() gives a HandlerSet, or one with stream callbacks (HandlerSet::with_streams)\n    let (handlers, streams) = dispatch::stream_glue(handlers::make_handlers());\n    std::process::exit(bridge::main_with_streams(asset(), handlers, streams));\n}\n'
    else:
        pass
        yield 'fn main() {\n    std::process::exit(bridge::main(asset(), Arc::new(handlers::make_handlers())));\n}\n'

blocks = {}
debug_info = '1=20&2=22&3=24&10=26&13=30&49=32'
