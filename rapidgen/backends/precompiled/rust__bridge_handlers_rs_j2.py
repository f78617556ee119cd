# mypy: ignore-errors
# Template templates/rust/bridge/handlers.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "7ab4cfa4be8a24761bb6b0d53da2b4f1e8d8ef34023806cb37adf28cb173401b"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/handlers.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_v = resolve('v')
    l_0_st = missing
    pass
    yield '// Handlers of asset '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ': written once by rapidgen, yours to edit.\n// Regeneration never touches this file (delete it to get fresh stubs). When the descriptor\n// changes, dispatch.rs changes with it and the compiler says what to update.\n//\n// Every method answers EXEC_FAILED "not implemented" until you write it; see dispatch.rs for\n// the rules (outcomes, progress, cancellation). `'
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'bridge'))
    yield ' --simulate` runs a simulated\n// robot instead of these.\n#![allow(unused_variables)]\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
        pass
        yield '\nuse rapid_runtime::{Context, Outcome};\n'
    yield '\n#[allow(unused_imports)]\nuse crate::dispatch::*;\n'
    l_1_loop = missing
    for l_1_h, l_1_loop in LoopContext(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'), undefined):
        _loop_vars = {}
        pass
        yield '\npub struct '
        yield str(environment.getattr(l_1_h, 'impl'))
        yield ';\n\nimpl '
        yield str(environment.getattr(l_1_h, 'trait'))
        yield ' for '
        yield str(environment.getattr(l_1_h, 'impl'))
        yield ' {\n'
        l_2_loop = missing
        for l_2_m, l_2_loop in LoopContext(environment.getattr(l_1_h, 'methods'), undefined):
            _loop_vars = {}
            pass
            if (not environment.getattr(l_2_loop, 'first')):
                pass
                yield '\n'
            yield '    /// '
            yield str(environment.getitem(environment.getattr(l_2_m, 'doc'), 0))
            yield '\n    fn '
            yield str(environment.getattr(l_2_m, 'name'))
            yield '(&self, ctx: &Context'
            for l_3_a in environment.getattr(l_2_m, 'params'):
                _loop_vars = {}
                pass
                yield ', '
                yield str(environment.getattr(l_3_a, 'name'))
                yield ': '
                yield str(environment.getattr(l_3_a, 'rtype'))
            l_3_a = missing
            yield ') -> Outcome {\n        Outcome::NotImplemented\n    }\n'
        l_2_loop = l_2_m = missing
        yield '}\n'
    l_1_loop = l_1_h = missing
    l_0_st = environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams')
    context.vars['st'] = l_0_st
    context.exported_vars.add('st')
    if ((undefined(name='st') if l_0_st is missing else l_0_st) and environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'inputs')):
        pass
        yield "\n/// The input streams' callbacks (see dispatch.rs, trait "
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'trait'))
        yield ').\npub struct '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'impl'))
        yield ';\n\nimpl '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'trait'))
        yield ' for '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'impl'))
        yield ' {\n'
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'inputs'):
            _loop_vars = {}
            pass
            yield '    /// '
            yield str(environment.getitem(environment.getattr(l_1_s, 'doc'), 0))
            yield '\n    fn '
            yield str(environment.getattr(l_1_s, 'method'))
            yield '(&self, sample: &'
            yield str(environment.getattr(l_1_s, 'type'))
            yield ') {\n        // the new setpoint: hand it to your control loop (no locks, no allocation here)\n    }\n\n'
        l_1_s = missing
        yield '    fn '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'state_hook'))
        yield '(&self, stream: &StreamSpec, state: StreamState) {\n        // lost with on_loss stop: bring the joints the stream drives to rest\n    }\n}\n\npub fn make_handlers() -> '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'dispatch'))
        yield ' {\n    HandlerSet {\n'
        for l_1_h in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
            _loop_vars = {}
            pass
            yield '        '
            yield str(environment.getattr(l_1_h, 'member'))
            yield ': ::std::boxed::Box::new('
            yield str(environment.getattr(l_1_h, 'impl'))
            yield '),\n'
        l_1_h = missing
        yield '    }\n    .with_streams('
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'impl'))
        yield ')\n}\n'
    else:
        pass
        yield '\npub fn make_handlers() -> HandlerSet {\n    HandlerSet {\n'
        for l_1_h in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
            _loop_vars = {}
            pass
            yield '        '
            yield str(environment.getattr(l_1_h, 'member'))
            yield ': ::std::boxed::Box::new('
            yield str(environment.getattr(l_1_h, 'impl'))
            yield '),\n'
        l_1_h = missing
        yield '    }\n}\n'

blocks = {}
debug_info = '1=14&6=16&9=18&16=23&18=27&20=29&21=34&22=37&25=41&26=43&32=57&33=60&35=63&36=65&38=67&39=71&40=75&41=77&46=83&51=85&53=87&54=91&57=97&63=102&64=106'
