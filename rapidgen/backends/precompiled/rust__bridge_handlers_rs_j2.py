# mypy: ignore-errors
# Template templates/rust/bridge/handlers.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "04803bb679bab7db778daca5485e6bf83477680804a921762db18c228e5f0a9b"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/handlers.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_v = resolve('v')
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
debug_info = '1=13&6=15&9=17&16=22&18=26&20=28&21=33&22=36&25=40&26=42&35=57&36=61'
